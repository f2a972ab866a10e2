#include "sedwave/sediment/seabed_reflection.hpp"

#include "sedwave/sediment/layered_seabed.hpp"

#include <optional>
#include <stdexcept>

namespace sedwave::sediment {

AcousticMedium medium_of(const SeabedPart& part, double frequency_hz, bool fluid_only, const std::string& what) {
  if (!part.model) throw std::invalid_argument("seabed: " + what + " has no model");
  const std::optional<double> density = part.model->bulk_density(part.values);
  if (!density) {
    throw std::invalid_argument("seabed: " + what + ": model '" + part.model->name() +
                                "' fixes no bulk density (a dry frame is no seabed on its own); use a model of "
                                "grains and pore water (sedwave models)");
  }
  const Wave p = part.model->evaluate(part.values, frequency_hz, false);
  AcousticMedium m{p.speed, p.attenuation, 0.0, 0.0, *density};
  if (!fluid_only && part.model->has_shear()) {
    const Wave s = part.model->evaluate_shear(part.values, frequency_hz, false);
    m.shear_speed = s.speed;
    m.shear_attenuation = s.attenuation;
  }
  return m;
}

SeabedModel seabed_of(const std::shared_ptr<const SedimentModel>& model, std::span<const double> values,
                      double water_speed, double water_density) {
  SeabedModel seabed;
  seabed.water_speed = water_speed;
  seabed.water_density = water_density;
  if (const auto* layered = dynamic_cast<const LayeredSeabed*>(model.get())) {
    seabed.layers = layered->layer_parts(values);
    seabed.halfspace = layered->halfspace_part(values);
  } else {
    seabed.halfspace = {model, {values.begin(), values.end()}, 0.0};
  }
  return seabed;
}

SeabedModel seabed_of(const SedimentModel& model, std::span<const double> values, double water_speed,
                      double water_density) {
  // An aliasing pointer with no owner: it points at the model and never deletes it.
  return seabed_of(std::shared_ptr<const SedimentModel>(std::shared_ptr<const SedimentModel>{}, &model), values,
                   water_speed, water_density);
}

LayeredHalfspace layered_halfspace_at(const SeabedModel& seabed, double frequency_hz) {
  LayeredHalfspace out;
  out.water = {seabed.water_speed, 0.0, 0.0, 0.0, seabed.water_density};
  for (std::size_t i = 0; i < seabed.layers.size(); ++i) {
    const SeabedPart& l = seabed.layers[i];
    out.layers.push_back({medium_of(l, frequency_hz, seabed.fluid_only, "layer l" + std::to_string(i + 1)),
                          l.thickness});
  }
  out.halfspace = medium_of(seabed.halfspace, frequency_hz, seabed.fluid_only, "half-space");
  return out;
}

}  // namespace sedwave::sediment
