#pragma once
// The grain-contact family: a dry granular frame whose stiffness and loss sit in spring-dashpot
// contacts (contact stiffness kappa, grain diameter d, dashpot gamma or restitution e_n, grain
// density rho_s), with any dimensionless forward model of forward/ (1D chain theories, 3D tables)
// behind it. The mapping is forward/units.hpp's GrainScales:
//   omega_hat = omega sqrt(m/kappa), gamma_hat = gamma / sqrt(kappa m)  (or sqrt(2) zeta(e_n)),
//   alpha = alpha_hat / d,  c = c_hat d sqrt(kappa/m),  m = rho_s pi d^3 / 6.
// The dimensionless model is a black box with exact first derivatives (forward::DispersionPoint);
// lift() carries them onto Jets by the chain rule, so every model gets exact Jacobians.
#include <ceres/jet.h>

#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/sediment/jet_evaluated.hpp"
#include "sedwave/sediment/site.hpp"

namespace sedwave::sediment {

enum class DampingForm { Gamma, Restitution };

/// alpha_hat and c_hat in the scalar type of the evaluation; sigmas are the model's own.
template <typename T>
struct HatWave {
  T alpha_hat;
  T c_hat;
  double sigma_alpha_hat = 0.0;
  double sigma_c_hat = 0.0;
};

inline HatWave<double> lift(const forward::DispersionModel& model, double omega_hat, double gamma_hat) {
  const forward::DispersionPoint p = model.evaluate(omega_hat, gamma_hat);
  return {p.alpha_hat, p.c_hat, p.sigma_alpha_hat, p.sigma_c_hat};
}

/// Chain rule: f(a + v) = f(a) + (df/d omega_hat) v_omega + (df/d gamma_hat) v_gamma.
template <int N>
HatWave<ceres::Jet<double, N>> lift(const forward::DispersionModel& model, const ceres::Jet<double, N>& omega_hat,
                                    const ceres::Jet<double, N>& gamma_hat) {
  const forward::DispersionPoint p = model.evaluate(omega_hat.a, gamma_hat.a);
  using Jet = ceres::Jet<double, N>;
  const Jet alpha(p.alpha_hat, p.d_alpha_hat.d_omega_hat * omega_hat.v + p.d_alpha_hat.d_gamma_hat * gamma_hat.v);
  const Jet c(p.c_hat, p.d_c_hat.d_omega_hat * omega_hat.v + p.d_c_hat.d_gamma_hat * gamma_hat.v);
  return {alpha, c, p.sigma_alpha_hat, p.sigma_c_hat};
}

/// The dry frame's wave and its dimensionless coordinates at one frequency.
template <typename T>
struct FrameWave {
  T omega_hat;
  T gamma_hat;
  HatWave<T> hat;
  T attenuation;  ///< [Np/m]
  T speed;        ///< [m/s]
  T speed_scale;  ///< d sqrt(kappa/m) [m/s]
};

/// The dry granular frame's compressional wave: kappa [N/m], d [m], damping (gamma [kg/s] or e_n),
/// rho_s [kg/m^3] at frequency_hz.
template <typename T>
FrameWave<T> frame_wave(const forward::DispersionModel& model, DampingForm form, const T& kappa, const T& diameter,
                        const T& damping, const T& grain_density, double frequency_hz) {
  const forward::GrainScales<T> scales{kappa, diameter, grain_density};
  // e_n is defined for a collision of two equal grains (m_eff = m/2), so it maps to gamma_hat
  // alone: gamma_hat = sqrt(2) zeta(e_n), independent of kappa and d.
  const T gamma_hat =
      form == DampingForm::Gamma ? scales.gamma_hat(damping) : forward::gamma_hat_from_restitution(damping);
  const T omega_hat = scales.omega_hat(T(2.0 * std::numbers::pi * frequency_hz));
  const HatWave<T> hat = lift(model, omega_hat, gamma_hat);
  return {omega_hat, gamma_hat, hat, scales.alpha(hat.alpha_hat), scales.speed(hat.c_hat), scales.speed_scale()};
}

/// Effective pressure at which kappa is compared with Hertz: about 1 m below the seafloor in sand
/// ((rho_bulk - rho_water) g z = (2000 - 1025) 9.81 1 = 9.6 kPa).
inline constexpr double kReferencePressure = 1.0e4;  ///< [Pa]
/// Porosity of the reference pack: a medium sand (Hamilton 1980: sands 0.37-0.47).
inline constexpr double kReferencePorosity = 0.38;

/// Hertz contact stiffness [N/m] of quartz grains (kQuartz) of diameter d [m] in a dense random pack
/// (porosity kReferencePorosity, coordination kDensePackCoordination) at effective pressure P [Pa]:
/// the same relation as the site inputs' kappa prior (hertz_kappa_at_pressure), so
/// kappa_over_hertz and a site's kappa prior agree.
[[nodiscard]] double quartz_hertz_kappa(double diameter, double pressure = kReferencePressure);

/// The grain contact's derived quantities, written once for the dry and the saturated frame:
///   c0     = c_hat(0) d sqrt(kappa/m)     low-frequency speed of the dry frame (dry frame only)
///   tau    = gamma / kappa                 relaxation time of a contact
///   f_star = 1 / (2 pi tau)                where attenuation bends from f^2 to f^(1/2)
///   gamma_hat = gamma / sqrt(kappa m)      the dimensionless dashpot (sqrt(2) zeta(e_n) for e_n)
///   kappa_over_hertz = kappa / kappa_Hertz(d, 10 kPa)   (kappa_Hertz is proportional to d)
/// with m = rho_s pi d^3 / 6 (forward/units.hpp's GrainScales).
class GrainContactDerived {
 public:
  /// `dry_frame`: the dimensionless model whose c_hat as omega_hat -> 0 gives c0 (the caller keeps
  /// it alive), or nullptr where c0 is not the model's own speed (the saturated frame).
  GrainContactDerived(DampingForm form, const forward::DispersionModel* dry_frame);

  [[nodiscard]] const std::vector<DerivedQuantity>& quantities() const { return quantities_; }

  template <typename T>
  std::vector<T> values(const T& kappa, const T& diameter, const T& damping, const T& grain_density) const {
    using std::sqrt;
    const forward::GrainScales<T> scales{kappa, diameter, grain_density};
    const T root_kappa_m = sqrt(kappa * scales.mass());
    const T gamma_hat =
        form_ == DampingForm::Gamma ? damping / root_kappa_m : forward::gamma_hat_from_restitution(damping);
    const T gamma = form_ == DampingForm::Gamma ? damping : gamma_hat * root_kappa_m;
    const T tau = gamma / kappa;
    std::vector<T> out;
    if (dry_frame_) out.push_back(dry_frame_->long_wavelength_c_hat() * scales.speed_scale());
    out.push_back(tau);
    out.push_back(1.0 / (2.0 * std::numbers::pi * tau));
    out.push_back(gamma_hat);
    out.push_back(kappa / (diameter * quartz_hertz_kappa(1.0)));
    return out;
  }

 private:
  DampingForm form_;
  const forward::DispersionModel* dry_frame_;
  std::vector<DerivedQuantity> quantities_;
};

/// Names, units, defaults and ranges of the four grain-contact parameters (kappa, d, gamma or e_n,
/// rho_s), in this order.
[[nodiscard]] std::vector<Parameter> grain_contact_parameters(DampingForm form);

/// A dry granular frame as a sediment model (parameters: grain_contact_parameters).
class GrainContactModel final : public JetEvaluated<GrainContactModel> {
 public:
  static constexpr int kParameters = 4;
  enum Index : int { kKappa = 0, kDiameter = 1, kDamping = 2, kGrainDensity = 3 };

  GrainContactModel(std::shared_ptr<const forward::DispersionModel> model, DampingForm form);

  [[nodiscard]] std::string name() const override { return model_->name(); }
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] std::string uncertainty_caveat() const override { return model_->uncertainty_caveat(); }
  [[nodiscard]] const std::vector<DerivedQuantity>& derived_quantities() const override {
    return derived_.quantities();
  }
  [[nodiscard]] std::string typical_free_parameters() const override;
  [[nodiscard]] const forward::DispersionModel* dimensionless_engine() const override { return model_.get(); }
  [[nodiscard]] std::optional<DimensionlessWave> dimensionless_wave(std::span<const double> values,
                                                                    double frequency_hz) const override;
  [[nodiscard]] const forward::DispersionModel& dimensionless() const { return *model_; }
  [[nodiscard]] DampingForm damping_form() const { return form_; }

  template <typename T>
  std::vector<T> derived(const T* v) const {
    return derived_.values(v[kKappa], v[kDiameter], v[kDamping], v[kGrainDensity]);
  }

  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    const FrameWave<T> f = frame_wave(*model_, form_, v[kKappa], v[kDiameter], v[kDamping], v[kGrainDensity],
                                      frequency_hz);
    const double d = value_of(v[kDiameter]);
    return {f.attenuation, f.speed, f.hat.sigma_alpha_hat / d, f.hat.sigma_c_hat * value_of(f.speed_scale)};
  }

 private:
  static double value_of(double x) { return x; }
  template <int N>
  static double value_of(const ceres::Jet<double, N>& x) {
    return x.a;
  }

  std::shared_ptr<const forward::DispersionModel> model_;
  DampingForm form_;
  std::vector<Parameter> parameters_;
  GrainContactDerived derived_;
};

}  // namespace sedwave::sediment
