#pragma once
// The Biot-Stoll model: Biot's theory (biot.hpp) with a frame whose bulk and shear moduli are
// complex with constant logarithmic decrements, R. D. Stoll, Sediment Acoustics (Springer, 1989),
// ch. 2, and Stoll & Kan, J. Acoust. Soc. Am. 70, 149-156 (1981):
//   K_b (1 + i delta_b / pi),  mu (1 + i delta_s / pi)   in Stoll's exp(+i omega t) convention,
// i.e. K_b (1 - i delta_b / pi), mu (1 - i delta_s / pi) in this library's exp(-i omega t).
// The frame loss is frequency independent (a constant Q = pi / delta), the pore-fluid loss is
// Biot's viscous flow with the correction F(kappa). Equation numbers of Stoll's texts are not quoted
// (they were not at hand); tests/sediment/independent_reference.py solves Stoll's equations of
// motion in his exp(+i omega t) convention and the SAX99 test compares (docs/models/poroelastic.md).
#include <numbers>
#include <string>
#include <vector>

#include "sedwave/sediment/biot.hpp"
#include "sedwave/sediment/jet_evaluated.hpp"
#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

class BiotStollModel final : public JetEvaluated<BiotStollModel>, public PoreSpace {
 public:
  static constexpr int kParameters = 13;
  /// The pore space (PoreSpaceIndex, 0-8), then the frame:
  enum Index : int {
    kFrameBulk = 9,
    kFrameShear = 10,
    kBulkDecrement = 11,
    kShearDecrement = 12,
  };

  BiotStollModel();

  [[nodiscard]] std::string name() const override { return "biot-stoll"; }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override {
    return poroelastic_derived_quantities();
  }
  [[nodiscard]] std::string typical_free_parameters() const override { return "porosity,permeability,delta_b"; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    return pore_space_derived(v);
  }

  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const BiotMedium<T> medium = pore_space_medium(v, frame_bulk(v), frame_shear(v));
    const AttenuationSpeed<T> fast = attenuation_and_speed(biot_fast_wavenumber(medium, omega), omega);
    return {fast.attenuation, fast.speed};
  }

  /// The shear wave of the frame's shear modulus mu (1 - i delta_s / pi) (biot_shear_wavenumber):
  /// mu is a parameter, so no Poisson ratio is assumed.
  template <typename T>
  WaveOf<T> shear_wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const BiotMedium<T> medium = pore_space_medium(v, frame_bulk(v), frame_shear(v));
    const AttenuationSpeed<T> shear = attenuation_and_speed(biot_shear_wavenumber(medium, omega), omega);
    return {shear.attenuation, shear.speed};
  }
  [[nodiscard]] std::string shear_summary() const override;

  template <typename T>
  T density(const T* v) const {
    return mixture_density(v[kPorosity], v[kGrainDensity], v[kWaterDensity]);
  }

 private:
  /// K_b (1 - i delta_b / pi) and mu (1 - i delta_s / pi) (see the top of this file).
  template <typename T>
  static Complex<T> frame_bulk(const T* v) {
    return {v[kFrameBulk], -v[kFrameBulk] * v[kBulkDecrement] / std::numbers::pi};
  }
  template <typename T>
  static Complex<T> frame_shear(const T* v) {
    return {v[kFrameShear], -v[kFrameShear] * v[kShearDecrement] / std::numbers::pi};
  }

  std::vector<Parameter> parameters_;
};

}  // namespace sedwave::sediment
