#pragma once
// Whitened residuals of field observations against any forward model, templated so Ceres can
// evaluate them with doubles and with ceres::Jet (automatic derivatives).
//
// The chain is: theta = (ln kappa, ln d, ln damping)  --GrainScales-->  (omega_hat, gamma_hat)
//   --DispersionModel-->  (alpha_hat, c_hat)  --GrainScales-->  (alpha [Np/m], c [m/s]).
// The middle step is a black box with exact first derivatives (DispersionPoint's gradients); it is
// lifted to Jets by the chain rule in evaluate_model(), so any model (closed form, table, ...) gets
// exact Jacobians without knowing about Ceres.
#include <ceres/jet.h>

#include <cmath>
#include <numbers>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/parameters.hpp"

namespace sedwave::inversion {

/// Model output at one point; sigmas are the model's own uncertainty (not differentiated).
template <typename T>
struct Dispersion {
  T alpha_hat;
  T c_hat;
  double sigma_alpha_hat = 0.0;
  double sigma_c_hat = 0.0;
};

inline Dispersion<double> evaluate_model(const forward::DispersionModel& model, double omega_hat,
                                         double gamma_hat) {
  const forward::DispersionPoint p = model.evaluate(omega_hat, gamma_hat);
  return {p.alpha_hat, p.c_hat, p.sigma_alpha_hat, p.sigma_c_hat};
}

/// Chain rule: f(a + v) = f(a) + (df/dw) v_w + (df/dg) v_g for each output.
template <int N>
Dispersion<ceres::Jet<double, N>> evaluate_model(const forward::DispersionModel& model,
                                                 const ceres::Jet<double, N>& omega_hat,
                                                 const ceres::Jet<double, N>& gamma_hat) {
  const forward::DispersionPoint p = model.evaluate(omega_hat.a, gamma_hat.a);
  using Jet = ceres::Jet<double, N>;
  const Jet alpha(p.alpha_hat, p.d_alpha_hat.d_omega_hat * omega_hat.v + p.d_alpha_hat.d_gamma_hat * gamma_hat.v);
  const Jet c(p.c_hat, p.d_c_hat.d_omega_hat * omega_hat.v + p.d_c_hat.d_gamma_hat * gamma_hat.v);
  return {alpha, c, p.sigma_alpha_hat, p.sigma_c_hat};
}

inline double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) {
  return x.a;
}

/// The physical prediction of a forward model at one frequency.
template <typename T>
struct Prediction {
  T omega_hat;
  T gamma_hat;
  Dispersion<T> hat;
  T alpha;  ///< [Np/m]
  T speed;  ///< [m/s]
  T speed_scale;  ///< c0 = d sqrt(kappa/m) [m/s]
};

/// Maps theta to physical predictions through one forward model.
class Predictor {
 public:
  Predictor(const forward::DispersionModel& model, DampingForm damping, double density)
      : model_(&model), damping_(damping), density_(density) {}

  template <typename T>
  Prediction<T> operator()(const T& ln_kappa, const T& ln_diameter, const T& ln_damping, double frequency_hz) const {
    using std::exp;
    const forward::GrainScales<T> scales{exp(ln_kappa), exp(ln_diameter), T(density_)};
    // e_n is defined for a collision of two equal grains (m_eff = m/2), so it maps to gamma_hat
    // alone: gamma_hat = sqrt(2) zeta(e_n), independent of kappa and d.
    const T gamma_hat = damping_ == DampingForm::Gamma ? scales.gamma_hat(exp(ln_damping))
                                                       : forward::gamma_hat_from_restitution(exp(ln_damping));
    const T omega_hat = scales.omega_hat(T(2.0 * std::numbers::pi * frequency_hz));
    const Dispersion<T> hat = evaluate_model(*model_, omega_hat, gamma_hat);
    return {omega_hat, gamma_hat, hat, scales.alpha(hat.alpha_hat), scales.speed(hat.c_hat), scales.speed_scale()};
  }

  [[nodiscard]] const forward::DispersionModel& model() const { return *model_; }
  [[nodiscard]] DampingForm damping() const { return damping_; }
  [[nodiscard]] double density() const { return density_; }

 private:
  const forward::DispersionModel* model_;
  DampingForm damping_;
  double density_;
};

/// One whitened residual. Attenuation spans decades, so it is compared in log space with a relative
/// sigma; sound speed is compared linearly. A model's own uncertainty adds in quadrature.
class ObservationResidual {
 public:
  /// `sigma` is the observation's 1-sigma uncertainty in SI (already defaulted if the file had none).
  ObservationResidual(Predictor predictor, const Observation& observation, double sigma)
      : predictor_(predictor), observation_(observation), sigma_(sigma) {}

  template <typename T>
  bool operator()(const T* ln_kappa, const T* ln_diameter, const T* ln_damping, T* residual) const {
    using std::log;
    using std::sqrt;
    const Prediction<T> p = predictor_(*ln_kappa, *ln_diameter, *ln_damping, observation_.frequency_hz);
    if (observation_.quantity == Quantity::Attenuation) {
      const double relative_model = p.hat.sigma_alpha_hat / value_of(p.hat.alpha_hat);
      const double relative_data = sigma_ / observation_.value;
      const double sigma_log = std::sqrt(relative_data * relative_data + relative_model * relative_model);
      residual[0] = (log(p.alpha) - std::log(observation_.value)) / sigma_log;
    } else {
      const double model_sigma = p.hat.sigma_c_hat * value_of(p.speed_scale);
      const double sigma = std::sqrt(sigma_ * sigma_ + model_sigma * model_sigma);
      residual[0] = (p.speed - observation_.value) / sigma;
    }
    return true;
  }

 private:
  Predictor predictor_;
  Observation observation_;
  double sigma_;
};

}  // namespace sedwave::inversion
