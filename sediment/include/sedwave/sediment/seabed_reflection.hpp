#pragma once
// A seabed described by sediment models (sediment_model.hpp), layer by layer, turned into the media
// of reflection.hpp at each frequency: each model's compressional wave, its shear wave where it has
// one, and its bulk density.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sedwave/sediment/reflection.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment {

/// One part of the seabed: a model, its parameter values (SI, parameters() order) and, for a layer,
/// its thickness [m] (ignored for the half-space).
struct SeabedPart {
  std::shared_ptr<const SedimentModel> model;
  std::vector<double> values;
  double thickness = 0.0;
};

/// Water over layers (top first) over a half-space.
struct SeabedModel {
  double water_speed = 1500.0;     ///< [m/s]
  double water_density = 1025.0;   ///< [kg/m^3]
  std::vector<SeabedPart> layers;
  SeabedPart halfspace;
  /// Treat every part as a fluid (shear waves left out) even where its model has a shear wave.
  bool fluid_only = false;
};

/// The medium a part's model predicts at frequency_hz: c_p, alpha_p, c_s and alpha_s where the
/// model has a shear wave (and !fluid_only), and its bulk density. Throws std::invalid_argument
/// naming the part (`what`) where the model fixes no bulk density (the dry frame alone).
[[nodiscard]] AcousticMedium medium_of(const SeabedPart& part, double frequency_hz, bool fluid_only,
                                       const std::string& what);

/// The seabed a model describes at parameter `values` (SI, its parameters() order), under water of
/// `water_speed` [m/s] and `water_density` [kg/m^3]: a layered seabed's layers and half-space
/// (layered_seabed.hpp), any other model as a half-space.
[[nodiscard]] SeabedModel seabed_of(const std::shared_ptr<const SedimentModel>& model, std::span<const double> values,
                                    double water_speed, double water_density);

/// The same for a model the caller keeps alive longer than the seabed (held without owning it).
[[nodiscard]] SeabedModel seabed_of(const SedimentModel& model, std::span<const double> values, double water_speed,
                                    double water_density);

/// Every part's medium at frequency_hz.
[[nodiscard]] LayeredHalfspace layered_halfspace_at(const SeabedModel& seabed, double frequency_hz);

}  // namespace sedwave::sediment
