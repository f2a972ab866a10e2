#pragma once
// The saturated granular model: the dry granular frame of the grain-contact family (any
// dimensionless forward model: chain theories, 3D tables) as the frame of Biot's theory, with
// water in the pores.
//
// The frame's compressional wave k_frame = omega / c_frame + i alpha_frame defines its complex
// P-wave modulus
//   M_frame(omega) = rho_frame (omega / k_frame)^2,  rho_frame = (1 - beta) rho_s,
// (the modulus a continuum of the frame's density needs to carry that wave), so that with a vacuum
// in the pores Biot's fast wave is the dry frame wave exactly. A frame Poisson ratio splits M_frame
// into the drained bulk and shear moduli (split_p_wave_modulus); biot.hpp adds the pore fluid.
//
// Permeability k and pore size a are either parameters, or derived from d and porosity:
//   Kozeny-Carman: k = d^2 beta^3 / (180 (1 - beta)^2)   (Carman, Trans. Inst. Chem. Eng. 15, 150
//                  (1937); the constant 180 for spheres as in Bear, Dynamics of Fluids in Porous
//                  Media (1972)),
//   pore size:     a = d beta / (3 (1 - beta))           (twice the hydraulic radius of a pack of
//                  spheres of diameter d; Hovem & Ingram, J. Acoust. Soc. Am. 66, 1807 (1979)).
#include <memory>
#include <string>
#include <vector>

#include "sedwave/sediment/biot.hpp"
#include "sedwave/sediment/grain_contact.hpp"
#include "sedwave/sediment/poroelastic_parameters.hpp"
#include "sedwave/sediment/site.hpp"

namespace sedwave::sediment {

/// Where permeability and pore size come from.
enum class PermeabilityFrom {
  Parameter,     ///< both are parameters of the model
  KozenyCarman,  ///< both derived from d and porosity (Kozeny-Carman; a = d beta / (3 (1 - beta)))
};

/// a = d beta / (3 (1 - beta)) [m]: twice the hydraulic radius of a sphere pack (Hovem & Ingram 1979).
template <typename T>
T hydraulic_pore_size(const T& diameter, const T& porosity) {
  return diameter * porosity / (3.0 * (1.0 - porosity));
}

class SaturatedGranularModel final : public SedimentModel {
 public:
  /// Parameter order; the last two exist only with PermeabilityFrom::Parameter.
  enum Index : int {
    kKappa = 0,
    kDiameter = 1,
    kDamping = 2,
    kGrainDensity = 3,
    kPorosity = 4,
    kGrainBulk = 5,
    kWaterDensity = 6,
    kWaterBulk = 7,
    kViscosity = 8,
    kTortuosity = 9,
    kFramePoisson = 10,
    kPermeability = 11,
    kPoreSize = 12,
  };
  static constexpr int kDerivedParameters = 11;  ///< count with PermeabilityFrom::KozenyCarman
  static constexpr int kAllParameters = 13;      ///< count with PermeabilityFrom::Parameter

  SaturatedGranularModel(std::shared_ptr<const forward::DispersionModel> model, DampingForm form,
                         PermeabilityFrom permeability);

  [[nodiscard]] std::string name() const override { return "saturated-" + model_->name(); }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] Wave evaluate(std::span<const double> values, double frequency_hz,
                              bool derivatives) const override;
  [[nodiscard]] PermeabilityFrom permeability_from() const { return permeability_; }
  /// The shear wave of the frame's shear modulus, the frame P-wave modulus split by the frame Poisson
  /// ratio nu_frame (a parameter: the one assumption), in Biot's theory (biot_shear_wavenumber).
  [[nodiscard]] bool has_shear() const override { return true; }
  [[nodiscard]] Wave evaluate_shear(std::span<const double> values, double frequency_hz,
                                    bool derivatives) const override;
  [[nodiscard]] std::string shear_summary() const override;
  [[nodiscard]] std::optional<double> bulk_density(std::span<const double> values) const override;
  [[nodiscard]] std::string uncertainty_caveat() const override { return model_->uncertainty_caveat(); }
  /// The grain contact's (without c0, which is the dry frame's speed, not this model's), then the
  /// poroelastic ones (Wood's speed, Biot's characteristic frequency).
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override { return derived_; }
  [[nodiscard]] std::vector<DerivedValue> derived_values(std::span<const double> values,
                                                         bool derivatives) const override;
  [[nodiscard]] std::string typical_free_parameters() const override;
  [[nodiscard]] const forward::DispersionModel* dimensionless_engine() const override { return model_.get(); }
  [[nodiscard]] const forward::DispersionModel& dimensionless() const { return *model_; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    std::vector<T> out = contact_.values(v[kKappa], v[kDiameter], v[kDamping], v[kGrainDensity]);
    const T permeability = permeability_of(v);
    for (const T& q : poroelastic_derived(v[kPorosity], v[kGrainDensity], v[kGrainBulk], v[kWaterDensity],
                                          v[kWaterBulk], v[kViscosity], permeability)) {
      out.push_back(q);
    }
    return out;
  }

  /// The fast wave for values in parameters() order (SI).
  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const AttenuationSpeed<T> fast =
        attenuation_and_speed(biot_fast_wavenumber(medium(v, frequency_hz), omega), omega);
    return {fast.attenuation, fast.speed};
  }

  /// The shear wave for values in parameters() order (SI).
  template <typename T>
  WaveOf<T> shear_wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const AttenuationSpeed<T> shear =
        attenuation_and_speed(biot_shear_wavenumber(medium(v, frequency_hz), omega), omega);
    return {shear.attenuation, shear.speed};
  }

 private:
  /// Biot's medium: the frame's moduli at frequency_hz and the pore space.
  template <typename T>
  BiotMedium<T> medium(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const FrameWave<T> frame =
        frame_wave(*model_, form_, v[kKappa], v[kDiameter], v[kDamping], v[kGrainDensity], frequency_hz);
    const T& porosity = v[kPorosity];
    const Complex<T> k_frame(T(omega) / frame.speed, frame.attenuation);
    const Complex<T> omega_over_k = Complex<T>(T(omega)) / k_frame;
    const Complex<T> p_wave_modulus = omega_over_k * omega_over_k * ((1.0 - porosity) * v[kGrainDensity]);
    const FrameModuli<T> moduli = split_p_wave_modulus(p_wave_modulus, v[kFramePoisson]);
    const bool derived = permeability_ == PermeabilityFrom::KozenyCarman;
    const BiotMedium<T> result{
        moduli.bulk,
        moduli.shear,
        porosity,
        v[kGrainDensity],
        v[kGrainBulk],
        v[kWaterDensity],
        v[kWaterBulk],
        v[kViscosity],
        derived ? kozeny_carman_formula(v[kDiameter], porosity) : v[kPermeability],
        v[kTortuosity],
        derived ? hydraulic_pore_size(v[kDiameter], porosity) : v[kPoreSize],
    };
    return result;
  }

  template <typename T>
  T permeability_of(const T* v) const {
    const bool derived = permeability_ == PermeabilityFrom::KozenyCarman;
    return derived ? kozeny_carman_formula(v[kDiameter], v[kPorosity]) : v[kPermeability];
  }

  std::shared_ptr<const forward::DispersionModel> model_;
  DampingForm form_;
  PermeabilityFrom permeability_;
  std::vector<Parameter> parameters_;
  GrainContactDerived contact_;
  std::vector<DerivedQuantity> derived_;
};

}  // namespace sedwave::sediment
