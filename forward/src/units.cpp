#include "sedwave/forward/units.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sedwave::forward {

double restitution_from_damping_ratio(double zeta) {
  if (!(zeta >= 0.0)) throw std::domain_error("damping ratio must be non-negative");
  if (zeta >= 1.0) return 0.0;
  return std::exp(-std::numbers::pi * zeta / std::sqrt((1.0 - zeta) * (1.0 + zeta)));
}

double restitution_from_gamma(double gamma, double kappa, double m_eff) {
  return restitution_from_damping_ratio(gamma / (2.0 * std::sqrt(kappa * m_eff)));
}

double hooke_collision_time(double kappa, double m_eff, double gamma) {
  const double zeta = gamma / (2.0 * std::sqrt(kappa * m_eff));
  if (zeta >= 1.0) return std::numeric_limits<double>::infinity();
  const double omega0 = std::sqrt(kappa / m_eff);
  return std::numbers::pi / (omega0 * std::sqrt((1.0 - zeta) * (1.0 + zeta)));
}

double hertz_effective_modulus(double E1, double nu1, double E2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

double hertz_force(double E_star, double R_eff, double delta) {
  return (4.0 / 3.0) * E_star * std::sqrt(R_eff) * delta * std::sqrt(delta);
}

double hertz_stiffness(double E_star, double R_eff, double delta) {
  return 2.0 * E_star * std::sqrt(R_eff * delta);
}

double hertz_overlap(double E_star, double R_eff, double force) {
  return std::cbrt(std::pow(3.0 * force / (4.0 * E_star * std::sqrt(R_eff)), 2.0));
}

double hertz_kappa_from_pressure(double E, double nu, double d, double P0) {
  const double E_star = hertz_effective_modulus(E, nu, E, nu);
  const double R_eff = d / 4.0;  // two spheres of radius d/2
  return hertz_stiffness(E_star, R_eff, hertz_overlap(E_star, R_eff, P0 * d * d));
}

double thesis_kappa_eq_2_18(double E, double d, double P0) { return 0.72 * E * d * std::cbrt(P0 / E); }

LammpsHooke lammps_hooke_from_material(double E, double nu, double e_n, double m_eff) {
  const double G = E / (2.0 * (1.0 + nu));
  const double kn = 4.0 * G / (3.0 * (1.0 - nu));
  const double kt = 4.0 * G / (2.0 - nu);
  return {kn, kt, 2.0 * damping_ratio_from_restitution(e_n) * std::sqrt(kn / m_eff)};
}

}  // namespace sedwave::forward
