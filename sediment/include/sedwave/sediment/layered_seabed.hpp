#pragma once
// A layered seabed as one sediment model: layers of any models (top first) over a half-space of
// another, so that a fit of reflection data treats every layer's parameters and thickness like any
// model's parameters (docs/reflection.md, "Fitting layered seabeds").
//
//   layered:edfm+biot-stoll     an EDFM layer over a Biot-Stoll half-space
//
// Parameters: the half-space's under their own names, then for each layer N (1 = top) its thickness
// lN.thickness [m] and its model's parameters as lN.NAME. The seabed's own wave (evaluate(), what
// in-situ speed and attenuation rows compare) is its top layer's: probes and cores sample the
// sediment at the surface. Reflection (seabed_reflection.hpp: seabed_of) sees the whole stack.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment {

struct SeabedPart;

class LayeredSeabed final : public SedimentModel {
 public:
  /// Throws std::invalid_argument for no layer or a missing model.
  LayeredSeabed(std::vector<std::shared_ptr<const SedimentModel>> layers, std::shared_ptr<const SedimentModel> halfspace);

  [[nodiscard]] std::string name() const override;
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] Wave evaluate(std::span<const double> values, double frequency_hz, bool derivatives) const override;
  [[nodiscard]] bool has_shear() const override { return layers_.front()->has_shear(); }
  [[nodiscard]] Wave evaluate_shear(std::span<const double> values, double frequency_hz, bool derivatives) const override;
  [[nodiscard]] std::string shear_summary() const override;
  [[nodiscard]] std::optional<double> bulk_density(std::span<const double> values) const override;
  [[nodiscard]] std::string typical_free_parameters() const override;
  /// The half-space's derived quantities under their own names, then each layer's as lN.NAME.
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override { return derived_; }
  [[nodiscard]] std::vector<DerivedValue> derived_values(std::span<const double> values, bool derivatives) const override;

  /// The layers (top first) and the half-space at parameter `values`, each with its own values and
  /// (layers) thickness.
  [[nodiscard]] std::vector<SeabedPart> layer_parts(std::span<const double> values) const;
  [[nodiscard]] SeabedPart halfspace_part(std::span<const double> values) const;

 private:
  /// A part's values out of the whole vector: `offset` is where they start.
  [[nodiscard]] static std::vector<double> slice(std::span<const double> values, std::size_t offset, std::size_t count);
  /// The top layer's wave, its gradient placed among all parameters.
  [[nodiscard]] Wave top_wave(const Wave& w, bool derivatives) const;

  std::vector<std::shared_ptr<const SedimentModel>> layers_;
  std::shared_ptr<const SedimentModel> halfspace_;
  std::vector<std::size_t> layer_offset_;  ///< index of lN.thickness; its model's values follow
  std::vector<Parameter> parameters_;
  std::vector<DerivedQuantity> derived_;
};

/// The catalog's specification prefix: "layered:" then the parts' specifications separated by '+'
/// (a comparison's model list is comma-separated), top first, the half-space last.
inline constexpr std::string_view kLayeredPrefix = "layered:";
inline constexpr char kLayerSeparator = '+';

}  // namespace sedwave::sediment
