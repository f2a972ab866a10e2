#pragma once
// Buckingham's grain-shearing theories of an unconsolidated, water-saturated granular sediment
// (no Biot frame-fluid flow; all loss from intergranular shearing), compressional and shear waves:
//
//   GS      M. J. Buckingham, J. Acoust. Soc. Am. 108, 2796-2815 (2000), "Wave propagation,
//           stress relaxation, and grain-to-grain shearing in saturated, unconsolidated marine
//           sediments"; the same dispersion relation with the reference parameter set of
//           M. J. Buckingham, J. Acoust. Soc. Am. 117, 137-152 (2005).
//   VGS(λ)  M. J. Buckingham, J. Acoust. Soc. Am. 127, 2099 (2010): the viscous grain-shearing
//           theory of M. J. Buckingham, J. Acoust. Soc. Am. 122, 1486-1501 (2007), in its VGS(λ)
//           form, whose memory function is viscous below a transition frequency 1/(2 pi tau_p).
//
// Both share one dispersion relation (SI throughout):
//   k_p = (omega / c_0) [1 + chi_p Psi(omega)]^(-1/2),   chi_p = (gamma_p + 4/3 gamma_s) / (rho_0 c_0^2),
//   c_p = omega / Re k_p,  alpha_p = -Im k_p  (the wave e^{i(omega t - k_p x)} decays: Im k_p < 0),
// where rho_0, c_0 are Wood's mixture of grains and water (the sediment with no frame rigidity):
//   rho_0 = N rho_w + (1 - N) rho_s,   1/K_0 = N/K_w + (1 - N)/K_s,   c_0 = sqrt(K_0 / rho_0).
// The memory function Psi is what distinguishes the theories:
//   GS:      Psi = (i omega T)^n                                  (power-law strain hardening)
//   VGS(λ):  Psi = (i omega T)^n (1 + 1/(i omega tau_p))^(n - 1)   (viscous at omega tau_p << 1)
// with T = 1 s an arbitrary reference time (it fixes the unit of gamma_p, gamma_s) and n the
// strain-hardening index.
//
// The shear wave of both theories (Buckingham 2000, 2005; 2010 for VGS(λ)) has the same form with
// the shear rigidity alone and no fluid stiffness:
//   k_s = (omega / c_s0) Psi_s(omega)^(-1/2),   c_s0 = sqrt(gamma_s / rho_0),
//   GS:      Psi_s = Psi = (i omega T)^n, so c_s = c_s0 (omega T)^(n/2) / cos(n pi/4) and
//            alpha_s = omega tan(n pi/4) / c_s (Buckingham 2005's closed forms);
//   VGS(λ):  Psi_s = (i omega T)^n (1 + 1/(i omega tau_s))^(n - 1), where the shear time constant is
//            not a parameter: the viscous transitions of both waves happen at one wavelength,
//            c_s(1/tau_s) tau_s = c_p(1/tau_p) tau_p (Buckingham 2010), which solved for tau_s is
//            tau_s = [c_p(1/tau_p) tau_p cos((n+1) pi/8) / (c_s0 2^((n-1)/4) T^(n/2))]^(2/(2-n))
//            (the same expression as C. W. Holland's MATLAB VGSlambda_no_tau_s). The equation numbers of the papers are not quoted: the forms above are
// identified by their content (the papers' own notation), see docs/models/grain-shearing.md.
#include <numbers>
#include <string>
#include <vector>

#include "sedwave/sediment/biot.hpp"
#include "sedwave/sediment/complex.hpp"
#include "sedwave/sediment/jet_evaluated.hpp"

namespace sedwave::sediment {

/// Reference time T of the grain-shearing memory function [s]: Buckingham's choice T = 1 s makes
/// (omega T)^n dimensionless without a further parameter (a different T rescales gamma_p, gamma_s).
inline constexpr double kGrainShearingReferenceTime = 1.0;

/// Grains and water as a suspension: Wood's (1930) mixture, the sediment with no frame rigidity.
template <typename T>
struct WoodMixture {
  T density;       ///< rho_0 [kg/m^3]
  T bulk_modulus;  ///< K_0 [Pa]
  T speed;         ///< c_0 = sqrt(K_0 / rho_0) [m/s]
};

template <typename T>
WoodMixture<T> wood_mixture(const T& porosity, const T& grain_density, const T& water_density,
                            const T& grain_bulk_modulus, const T& water_bulk_modulus) {
  using std::sqrt;
  const T density = mixture_density(porosity, grain_density, water_density);
  const T bulk_modulus = wood_bulk_modulus(porosity, grain_bulk_modulus, water_bulk_modulus);
  return {density, bulk_modulus, sqrt(bulk_modulus / density)};
}

/// The compressional wave k_p = (omega / c_0) (1 + stiffening)^(-1/2), stiffening = chi_p Psi.
template <typename T>
WaveOf<T> grain_shearing_compressional_wave(const T& wood_speed, const Complex<T>& stiffening,
                                            double omega) {
  const Complex<T> slowness_factor = Complex<T>(T(1.0)) / sqrt(Complex<T>(T(1.0)) + stiffening);
  return {T(-omega) * slowness_factor.im / wood_speed, wood_speed / slowness_factor.re};
}

/// The five parameters of the grain-water mixture (porosity, rho_s, rho_w, K_s, K_w), in this
/// order, with the given defaults (ranges are common).
struct MixtureDefaults {
  double porosity = 0.0;
  double grain_density = 0.0;        ///< [kg/m^3]
  double water_density = 0.0;        ///< [kg/m^3]
  double grain_bulk_modulus = 0.0;   ///< [Pa]
  double water_bulk_modulus = 0.0;   ///< [Pa]
};
[[nodiscard]] std::vector<Parameter> mixture_parameters(const MixtureDefaults& defaults, const std::string& source);

/// The parameter order GS and VGS(lambda) share (VGS adds tau_p last), and the two quantities both
/// build on.
struct GrainShearingParameters {
  enum Index : int {
    kPorosity = 0,
    kGrainDensity = 1,
    kWaterDensity = 2,
    kGrainBulkModulus = 3,
    kWaterBulkModulus = 4,
    kGammaP = 5,
    kGammaS = 6,
    kStrainHardening = 7,
    kViscousTime = 8,  ///< VGS(lambda) only
  };

  /// Wood's suspension of the grains in the pore water.
  template <typename T>
  static WoodMixture<T> mixture(const T* v) {
    return wood_mixture(v[kPorosity], v[kGrainDensity], v[kWaterDensity], v[kGrainBulkModulus], v[kWaterBulkModulus]);
  }
  /// wood_speed c_0 [m/s]: the speed of both theories as omega -> 0 (the memory function vanishes
  /// there: (i omega T)^n -> 0 for GS, i omega T^n tau_p^(1-n) -> 0 for VGS(lambda)), Buckingham 2000.
  [[nodiscard]] static DerivedQuantity wood_speed_quantity();
  template <typename T>
  static T low_frequency_speed(const T* v) {
    return mixture(v).speed;
  }

  /// The bulk density rho_0 [kg/m^3] (Wood's mixture: grains and pore water by volume).
  template <typename T>
  static T density(const T* v) {
    return mixture_density(v[kPorosity], v[kGrainDensity], v[kWaterDensity]);
  }

  /// The shear wave k_s = (omega / c_s0) Psi_s^(-1/2), c_s0 = sqrt(gamma_s / rho_0), for a shear memory
  /// function Psi_s (see the top of this file); alpha_s = -Im k_s in the e^{i omega t} convention.
  template <typename T>
  static WaveOf<T> shear_wave_from_memory(const T* v, const WoodMixture<T>& wood, const Complex<T>& memory,
                                          double omega) {
    using std::sqrt;
    const T reference_speed = sqrt(v[kGammaS] / wood.density);
    const Complex<T> slowness_factor = Complex<T>(T(1.0)) / sqrt(memory);
    return {T(-omega) * slowness_factor.im / reference_speed, reference_speed / slowness_factor.re};
  }

  /// chi_p = (gamma_p + 4/3 gamma_s) / (rho_0 c_0^2), with rho_0 c_0^2 = K_0 (Wood's modulus).
  template <typename T>
  static T shearing_stiffness(const T* v, const WoodMixture<T>& wood) {
    return (v[kGammaP] + T(4.0 / 3.0) * v[kGammaS]) / wood.bulk_modulus;
  }
};

/// GS (Buckingham 2000, 2005): parameters porosity, rho_s, rho_w, K_s, K_w, gamma_p, gamma_s, n;
/// defaults the reference set of Buckingham (2005) (a medium sand at 0.3 m below the seabed).
class GrainShearingModel final : public JetEvaluated<GrainShearingModel>, public GrainShearingParameters {
 public:
  static constexpr int kParameters = 8;

  GrainShearingModel();

  [[nodiscard]] std::string name() const override { return "grain-shearing"; }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override { return derived_; }
  [[nodiscard]] std::string typical_free_parameters() const override { return "porosity,gamma_p,n"; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    return {low_frequency_speed(v)};
  }

  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const WoodMixture<T> wood = mixture(v);
    const T chi = shearing_stiffness(v, wood);
    const Complex<T> memory = pow_imaginary(omega * kGrainShearingReferenceTime, v[kStrainHardening]);
    return grain_shearing_compressional_wave(wood.speed, Complex<T>(chi) * memory, omega);
  }

  /// The shear wave: Psi_s = (i omega T)^n, the compressional memory function.
  template <typename T>
  WaveOf<T> shear_wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    return shear_wave_from_memory(v, mixture(v), pow_imaginary(omega * kGrainShearingReferenceTime, v[kStrainHardening]),
                                  omega);
  }
  [[nodiscard]] std::string shear_summary() const override;

 private:
  std::vector<Parameter> parameters_;
  std::vector<DerivedQuantity> derived_;
};

/// VGS(λ) (Buckingham 2010): the GS parameters plus the compressional viscous time constant
/// tau_p [s]; defaults the SAX99 sand of Buckingham (2010).
class ViscousGrainShearingModel final : public JetEvaluated<ViscousGrainShearingModel>, public GrainShearingParameters {
 public:
  static constexpr int kParameters = 9;  ///< the GS parameters, then tau_p

  ViscousGrainShearingModel();

  [[nodiscard]] std::string name() const override { return "vgs-lambda"; }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  /// wood_speed, then viscous_frequency 1/(2 pi tau_p) [Hz]: below it the memory function is
  /// viscous and attenuation grows as f^2, above it VGS(lambda) is GS (Buckingham 2007, 2010); then
  /// tau_s [s], the shear wave's viscous time constant that follows from tau_p (shear_time).
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override { return derived_; }
  [[nodiscard]] std::string typical_free_parameters() const override { return "porosity,gamma_p,tau_p"; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    return {low_frequency_speed(v), 1.0 / (2.0 * std::numbers::pi * v[kViscousTime]), shear_time(v)};
  }

  /// The memory function Psi = (i omega T)^n (1 + 1/(i omega tau))^(n - 1) for a viscous time tau.
  template <typename T>
  static Complex<T> viscous_memory(const T& n, const T& tau, double omega) {
    // 1 + 1/(i omega tau) = 1 - i/(omega tau). For omega tau >> 1 it tends to 1 (GS); for
    // omega tau << 1, Psi -> i omega T^n tau^(1-n): a viscous (Kelvin-Voigt) response, alpha ~ f^2.
    const Complex<T> viscous_base(T(1.0), T(-1.0) / (T(omega) * tau));
    return pow_imaginary(omega * kGrainShearingReferenceTime, n) * pow(viscous_base, T(n - T(1.0)));
  }

  /// The shear viscous time constant tau_s [s] from tau_p (Buckingham 2010; see the top of this file).
  /// At omega = 1/tau_p the memory function is (T/tau_p)^n 2^((n-1)/2) e^{i (n+1) pi/4} exactly.
  template <typename T>
  static T shear_time(const T* v) {
    using std::cos;
    using std::pow;
    using std::sqrt;
    const T& n = v[kStrainHardening];
    const T& tau_p = v[kViscousTime];
    const WoodMixture<T> wood = mixture(v);
    const T memory_size = pow(T(kGrainShearingReferenceTime) / tau_p, n) * pow(T(2.0), (n - 1.0) / 2.0);
    const Complex<T> memory = polar(memory_size, T((n + 1.0) * (std::numbers::pi / 4.0)));
    const Complex<T> factor =
        Complex<T>(T(1.0)) / sqrt(Complex<T>(T(1.0)) + Complex<T>(shearing_stiffness(v, wood)) * memory);
    const T transition_speed = wood.speed / factor.re;  // c_p(1/tau_p)
    const T shear_reference_speed = sqrt(v[kGammaS] / wood.density);
    const T base = transition_speed * tau_p * cos((n + 1.0) * (std::numbers::pi / 8.0)) /
                   (shear_reference_speed * pow(T(2.0), (n - 1.0) / 4.0) *
                    pow(T(kGrainShearingReferenceTime), n / 2.0));
    return pow(base, 2.0 / (2.0 - n));
  }

  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    const WoodMixture<T> wood = mixture(v);
    const T chi = shearing_stiffness(v, wood);
    const Complex<T> memory = viscous_memory(v[kStrainHardening], v[kViscousTime], omega);
    return grain_shearing_compressional_wave(wood.speed, Complex<T>(chi) * memory, omega);
  }

  /// The shear wave: the viscous memory function with tau_s (shear_time) in place of tau_p.
  template <typename T>
  WaveOf<T> shear_wave(const T* v, double frequency_hz) const {
    const double omega = 2.0 * std::numbers::pi * frequency_hz;
    return shear_wave_from_memory(v, mixture(v), viscous_memory(v[kStrainHardening], shear_time(v), omega), omega);
  }
  [[nodiscard]] std::string shear_summary() const override;

 private:
  std::vector<Parameter> parameters_;
  std::vector<DerivedQuantity> derived_;
};

}  // namespace sedwave::sediment
