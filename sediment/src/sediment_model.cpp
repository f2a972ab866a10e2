#include "sedwave/sediment/sediment_model.hpp"

#include <algorithm>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sedwave::sediment {

const std::vector<DerivedQuantity>& SedimentModel::derived_quantities() const {
  static const std::vector<DerivedQuantity> kNone;
  return kNone;
}

std::vector<DerivedValue> SedimentModel::derived_values(std::span<const double>, bool) const { return {}; }

std::string SedimentModel::typical_free_parameters() const {
  std::string list;
  for (const Parameter& p : parameters()) list += (list.empty() ? "" : ",") + p.name;
  return list;
}

Wave SedimentModel::evaluate_shear(std::span<const double>, double, bool) const {
  throw std::logic_error("model '" + name() + "' predicts no shear wave");
}

std::optional<DimensionlessWave> SedimentModel::dimensionless_wave(std::span<const double>, double) const {
  return std::nullopt;
}

bool SedimentModel::has_parameter(const std::string& name) const {
  const std::vector<Parameter>& ps = parameters();
  return std::any_of(ps.begin(), ps.end(), [&](const Parameter& p) { return p.name == name; });
}

int SedimentModel::index_of(const std::string& name) const {
  const std::vector<Parameter>& ps = parameters();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps[i].name == name) return static_cast<int>(i);
  }
  std::string accepted;
  for (const Parameter& p : ps) accepted += (accepted.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("model '" + this->name() + "' has no parameter '" + name + "' (accepted: " +
                              accepted + ")");
}

std::vector<double> SedimentModel::default_values() const {
  std::vector<double> v;
  for (const Parameter& p : parameters()) v.push_back(p.default_value);
  return v;
}

void SedimentModel::check_values(std::span<const double> values) const {
  const std::vector<Parameter>& ps = parameters();
  if (values.size() != ps.size()) {
    throw std::invalid_argument(name() + ": " + std::to_string(ps.size()) + " parameter values expected, got " +
                                std::to_string(values.size()));
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < ps[i].lower || values[i] > ps[i].upper) {
      std::ostringstream msg;
      msg << "model '" << name() << "': " << ps[i].name << " = " << values[i] << " " << ps[i].unit
          << " lies outside its physical range [" << ps[i].lower << ", " << ps[i].upper << "] " << ps[i].unit;
      throw std::invalid_argument(msg.str());
    }
  }
}

}  // namespace sedwave::sediment
