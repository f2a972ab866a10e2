// Combinations: functions of theta that the data may determine when the parameters are not.
// Each is ln q(theta) with its exact gradient, so the same code gives the value, the linearised
// sigma, the likelihood profile and a posterior sample's value. The grain contact's are log-linear
// in theta, except through e_n.
#include <ceres/jet.h>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <utility>

#include "fit_problem.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/inversion/plausibility.hpp"

namespace sedwave::inversion::detail {
namespace {

/// ln q = constant + sum of coefficient * theta_i.
Differentiated log_linear(const Theta& theta, double constant, std::initializer_list<std::pair<int, double>> terms) {
  Differentiated q{constant, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(theta.size()))};
  for (const auto& [i, coefficient] : terms) {
    q.a += coefficient * theta[i];
    q.v(i) += coefficient;
  }
  return q;
}

/// ln m = ln(pi/6) + ln rho_s + 3 ln d (a sphere's mass).
Differentiated log_mass(const Theta& t) {
  return log_linear(t, std::log(std::numbers::pi / 6.0), {{kGrainDensity, 1.0}, {kDiameter, 3.0}});
}

Differentiated plus(Differentiated a, const Differentiated& b, double scale = 1.0) {
  a.a += scale * b.a;
  a.v += scale * b.v;
  return a;
}

/// ln gamma_hat of the damping entry: for e_n, gamma_hat = sqrt(2) zeta(e_n) (units.hpp).
Differentiated log_gamma_hat_of_restitution(const Theta& t) {
  using Jet1 = ceres::Jet<double, 1>;
  const Jet1 g = forward::gamma_hat_from_restitution(Jet1(std::exp(t[kDamping]), 0));
  Differentiated q{std::log(g.a), Eigen::VectorXd::Zero(static_cast<Eigen::Index>(t.size()))};
  q.v(kDamping) = g.v[0] * std::exp(t[kDamping]) / g.a;
  return q;
}

Differentiated log_gamma(const Setup& s, const Theta& t) {
  if (s.parameters.damping_form() == DampingForm::Gamma) return log_linear(t, 0.0, {{kDamping, 1.0}});
  // gamma = gamma_hat sqrt(kappa m)
  return plus(plus(log_gamma_hat_of_restitution(t), log_linear(t, 0.0, {{kKappa, 0.5}})), log_mass(t), 0.5);
}

/// Low-frequency sound speed of the dry frame: the speed scale d sqrt(kappa/m) times the model's
/// c_hat as omega_hat -> 0 (1 for the chains; a 3D packing's static value for a table).
Differentiated log_c0(const Setup& s, const Theta& t) {
  const auto& frame = dynamic_cast<const sediment::GrainContactModel&>(*s.model);
  const Differentiated scale = log_linear(t, std::log(frame.dimensionless().long_wavelength_c_hat()),
                                          {{kDiameter, 1.0}, {kKappa, 0.5}});
  return plus(scale, log_mass(t), -0.5);
}
Differentiated log_tau(const Setup& s, const Theta& t) {
  return plus(log_gamma(s, t), log_linear(t, 0.0, {{kKappa, 1.0}}), -1.0);
}
Differentiated log_f_star(const Setup& s, const Theta& t) {
  Differentiated q = log_tau(s, t);
  q.a = -q.a - std::log(2.0 * std::numbers::pi);
  q.v = -q.v;
  return q;
}
Differentiated log_gamma_hat(const Setup& s, const Theta& t) {
  if (s.parameters.damping_form() == DampingForm::Restitution) return log_gamma_hat_of_restitution(t);
  return plus(plus(log_gamma(s, t), log_linear(t, 0.0, {{kKappa, 1.0}}), -0.5), log_mass(t), -0.5);
}
/// kappa over the Hertz stiffness of quartz grains of the same d at 10 kPa (plausibility.hpp);
/// Hertz kappa is proportional to d at a given pressure.
Differentiated log_kappa_over_hertz(const Setup&, const Theta& t) {
  return log_linear(t, -std::log(quartz_hertz_kappa(1.0)), {{kKappa, 1.0}, {kDiameter, -1.0}});
}

}  // namespace

std::vector<Combination> combinations_for(const Setup& s) {
  std::vector<Combination> list;
  if (!s.parameters.starts_with_grain_contact()) return list;
  if (dynamic_cast<const sediment::GrainContactModel*>(s.model)) {
    list.push_back({"c0", "m/s", "low-frequency (f -> 0) sound speed of the model", log_c0});
  }
  list.push_back({"tau", "s", "relaxation time gamma/kappa of a contact", log_tau});
  list.push_back({"f_star", "Hz", "crossover frequency 1/(2 pi tau) where attenuation bends from f^2 to f^(1/2)",
                  log_f_star});
  list.push_back({"gamma_hat", "1", "dimensionless dashpot gamma/sqrt(kappa m)", log_gamma_hat});
  list.push_back({"kappa_over_hertz", "1", "kappa over the Hertz stiffness of quartz grains of diameter d at 10 kPa",
                  log_kappa_over_hertz});
  return list;
}

}  // namespace sedwave::inversion::detail
