#include "sedwave/sediment/layered_seabed.hpp"

#include <algorithm>
#include <stdexcept>

#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::sediment {
namespace {

std::string layer_label(std::size_t i) {
  std::string label = "l";
  label += std::to_string(i + 1);
  return label;
}

/// "lN." + name, appended piece by piece (GCC 12 misreads chained operator+ here: -Wrestrict).
std::string prefixed(std::size_t i, const std::string& name) {
  std::string out = layer_label(i);
  out += '.';
  out += name;
  return out;
}

/// A layer's thickness: a metre-scale default only to start a search from (a fit or run is given it).
Parameter thickness_of(std::size_t i) {
  std::string meaning = "thickness of layer ";
  meaning += layer_label(i);
  meaning += " (l1 = the top layer)";
  return {prefixed(i, "thickness"), "m", 1.0, 1e-3, 1e3, true, meaning, false};
}

}  // namespace

LayeredSeabed::LayeredSeabed(std::vector<std::shared_ptr<const SedimentModel>> layers,
                             std::shared_ptr<const SedimentModel> halfspace)
    : layers_(std::move(layers)), halfspace_(std::move(halfspace)) {
  if (layers_.empty()) throw std::invalid_argument("a layered seabed needs at least one layer over its half-space");
  if (!halfspace_) throw std::invalid_argument("a layered seabed needs a half-space model");
  parameters_ = halfspace_->parameters();
  derived_ = halfspace_->derived_quantities();
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    for (DerivedQuantity q : layers_[i]->derived_quantities()) {
      q.name = prefixed(i, q.name);
      q.meaning.insert(0, layer_label(i) + ": ");
      derived_.push_back(std::move(q));
    }
  }
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    if (!layers_[i]) throw std::invalid_argument("layer " + layer_label(i) + " has no model");
    layer_offset_.push_back(parameters_.size());
    parameters_.push_back(thickness_of(i));
    for (Parameter p : layers_[i]->parameters()) {
      p.name = prefixed(i, p.name);
      p.meaning.insert(0, layer_label(i) + ": ");
      parameters_.push_back(std::move(p));
    }
  }
}

std::string LayeredSeabed::name() const {
  std::string out(kLayeredPrefix);
  for (const auto& l : layers_) {
    out += l->name();
    out += kLayerSeparator;
  }
  return out + halfspace_->name();
}

std::string LayeredSeabed::summary() const {
  std::string out = "layers over a half-space: ";
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    out += layer_label(i);
    out += ' ';
    out += layers_[i]->name();
    out += ", ";
  }
  return out + "half-space " + halfspace_->name() + "; its own wave is the top layer's";
}

std::vector<double> LayeredSeabed::slice(std::span<const double> values, std::size_t offset, std::size_t count) {
  return {values.begin() + static_cast<std::ptrdiff_t>(offset), values.begin() + static_cast<std::ptrdiff_t>(offset + count)};
}

std::vector<SeabedPart> LayeredSeabed::layer_parts(std::span<const double> values) const {
  std::vector<SeabedPart> parts;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const std::size_t at = layer_offset_[i];
    parts.push_back({layers_[i], slice(values, at + 1, layers_[i]->parameters().size()), values[at]});
  }
  return parts;
}

SeabedPart LayeredSeabed::halfspace_part(std::span<const double> values) const {
  return {halfspace_, slice(values, 0, halfspace_->parameters().size()), 0.0};
}

Wave LayeredSeabed::top_wave(const Wave& w, bool derivatives) const {
  if (!derivatives) return w;
  Wave out = w;
  const std::size_t first = layer_offset_.front() + 1;
  out.d_attenuation.assign(parameters_.size(), 0.0);
  out.d_speed.assign(parameters_.size(), 0.0);
  for (std::size_t i = 0; i < w.d_attenuation.size(); ++i) {
    out.d_attenuation[first + i] = w.d_attenuation[i];
    out.d_speed[first + i] = w.d_speed[i];
  }
  return out;
}

Wave LayeredSeabed::evaluate(std::span<const double> values, double frequency_hz, bool derivatives) const {
  const SeabedPart top = layer_parts(values).front();
  return top_wave(top.model->evaluate(top.values, frequency_hz, derivatives), derivatives);
}

Wave LayeredSeabed::evaluate_shear(std::span<const double> values, double frequency_hz, bool derivatives) const {
  const SeabedPart top = layer_parts(values).front();
  return top_wave(top.model->evaluate_shear(top.values, frequency_hz, derivatives), derivatives);
}

std::string LayeredSeabed::shear_summary() const {
  const std::string top = layers_.front()->shear_summary();
  return top.empty() ? top : "the top layer's: " + top;
}

std::optional<double> LayeredSeabed::bulk_density(std::span<const double> values) const {
  const SeabedPart top = layer_parts(values).front();
  return top.model->bulk_density(top.values);
}

std::vector<DerivedValue> LayeredSeabed::derived_values(std::span<const double> values, bool derivatives) const {
  // Each part's values with its gradient placed among all parameters (at `first`).
  std::vector<DerivedValue> out;
  const auto append = [&](const SeabedPart& part, std::size_t first) {
    for (DerivedValue d : part.model->derived_values(part.values, derivatives)) {
      if (derivatives) {
        std::vector<double> all(parameters_.size(), 0.0);
        std::copy(d.gradient.begin(), d.gradient.end(), all.begin() + static_cast<std::ptrdiff_t>(first));
        d.gradient = std::move(all);
      }
      out.push_back(std::move(d));
    }
  };
  append(halfspace_part(values), 0);
  const std::vector<SeabedPart> layers = layer_parts(values);
  for (std::size_t i = 0; i < layers.size(); ++i) append(layers[i], layer_offset_[i] + 1);
  return out;
}

std::string LayeredSeabed::typical_free_parameters() const {
  std::string out = halfspace_->typical_free_parameters();
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    out += ',';
    out += prefixed(i, "thickness");
    const std::string own = layers_[i]->typical_free_parameters();
    for (std::size_t start = 0; start < own.size();) {
      const std::size_t comma = std::min(own.find(',', start), own.size());
      out += ',';
      out += prefixed(i, own.substr(start, comma - start));
      start = comma + 1;
    }
  }
  return out;
}

}  // namespace sedwave::sediment
