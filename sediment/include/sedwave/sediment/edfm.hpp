#pragma once
// The effective density fluid model (EDFM): Biot's theory with a frame that has no rigidity
// (K_b = mu = 0), K. L. Williams, J. Acoust. Soc. Am. 110, 2276-2281 (2001).
//
// Without frame moduli H = C = M = K_Wood (Wood's bulk modulus), the Biot quadratic loses its
// s^2 term and the one remaining (fast) wave is that of a fluid of bulk modulus K_Wood and
// effective density
//   rho_eff = (rho m~ - rho_f^2) / (m~ + rho - 2 rho_f),  m~ = alpha_inf rho_f / beta + i eta F* / (k omega)
// (Williams 2001, section II; biot.hpp for m~ and F). Low frequency: rho_eff -> rho, the speed is
// Wood's and attenuation grows as f^2; high frequency: rho_eff -> the tortuosity-coupled inertia
// (rho alpha_inf rho_f/beta - rho_f^2) / (alpha_inf rho_f/beta + rho - 2 rho_f), attenuation ~ f^(1/2).
// The paper's equation numbers are not quoted (its text was not at hand); the forms are identified
// by content and checked against Stoll's equations with K_b = mu = 0 solved independently
// (tests/sediment/independent_reference.py; docs/models/poroelastic.md).
#include <numbers>
#include <string>
#include <vector>

#include "sedwave/sediment/biot.hpp"
#include "sedwave/sediment/jet_evaluated.hpp"
#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

class EffectiveDensityFluidModel final : public JetEvaluated<EffectiveDensityFluidModel>, public PoreSpace {
 public:
  static constexpr int kParameters = kPoreSpaceParameters;  ///< PoreSpaceIndex order

  EffectiveDensityFluidModel();

  [[nodiscard]] std::string name() const override { return "edfm"; }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override {
    return poroelastic_derived_quantities();
  }
  [[nodiscard]] std::string typical_free_parameters() const override { return "porosity,permeability"; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    return pore_space_derived(v);
  }

  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const BiotMedium<T> medium = pore_space_medium(v, Complex<T>(T(0.0)), Complex<T>(T(0.0)));
    const AttenuationSpeed<T> fast = attenuation_and_speed(biot_fast_wavenumber(medium, omega), omega);
    return {fast.attenuation, fast.speed};
  }

  /// A fluid: no shear wave, and the density of grains and pore water.
  template <typename T>
  T density(const T* v) const {
    return mixture_density(v[kPorosity], v[kGrainDensity], v[kWaterDensity]);
  }

 private:
  std::vector<Parameter> parameters_;
};

}  // namespace sedwave::sediment
