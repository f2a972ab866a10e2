#pragma once
// Physical (SI) <-> dimensionless mapping and contact-parameter conversions.
//
// Units: kappa [N/m] contact stiffness, d [m] grain diameter, rho_s [kg/m^3] grain density,
// gamma [kg/s] = [N s/m] normal dashpot coefficient, omega [rad/s], alpha [Np/m], c [m/s],
// e_n [-] normal restitution coefficient.
// Dimensionless groups (thesis eqs. 2.10-2.13), with m the mass of one grain of diameter d:
//   omega_hat = omega sqrt(m/kappa),  gamma_hat = gamma / sqrt(kappa m),
//   alpha_hat = alpha d,              c_hat = c / c0,  c0 = d sqrt(kappa/m).
//
// The grain mapping is templated so the inversion can evaluate it with ceres::Jet (automatic
// derivatives); the same code serves doubles.
#include <cmath>
#include <numbers>

namespace sedwave::forward {

/// Mass [kg] of a sphere of diameter d [m] and density rho_s [kg/m^3]: m = rho_s pi d^3 / 6.
template <typename T>
T grain_mass(const T& density, const T& diameter) {
  return density * (std::numbers::pi / 6.0) * diameter * diameter * diameter;
}

/// The physical scales of one grain contact: converts SI quantities to and from dimensionless ones.
template <typename T>
struct GrainScales {
  T kappa;     ///< contact stiffness [N/m]
  T diameter;  ///< grain diameter d [m]
  T density;   ///< grain density rho_s [kg/m^3]

  [[nodiscard]] T mass() const { return grain_mass(density, diameter); }
  /// Time unit sqrt(m/kappa) [s].
  [[nodiscard]] T time_scale() const {
    using std::sqrt;
    return sqrt(mass() / kappa);
  }
  /// Speed unit c0 = d sqrt(kappa/m) [m/s]: the low-frequency sound speed of the chain.
  [[nodiscard]] T speed_scale() const { return diameter / time_scale(); }
  /// Dashpot unit sqrt(kappa m) [kg/s].
  [[nodiscard]] T damping_scale() const {
    using std::sqrt;
    return sqrt(kappa * mass());
  }

  [[nodiscard]] T omega_hat(const T& omega) const { return omega * time_scale(); }
  [[nodiscard]] T gamma_hat(const T& gamma) const { return gamma / damping_scale(); }
  [[nodiscard]] T gamma(const T& gamma_hat) const { return gamma_hat * damping_scale(); }
  /// alpha [Np/m] from alpha_hat.
  [[nodiscard]] T alpha(const T& alpha_hat) const { return alpha_hat / diameter; }
  /// c [m/s] from c_hat.
  [[nodiscard]] T speed(const T& c_hat) const { return c_hat * speed_scale(); }
};

// ---- Restitution <-> damping for a linear spring-dashpot binary collision -------------------------
// A head-on collision of two grains with reduced mass m_eff = m1 m2 / (m1 + m2) through a Hooke
// spring kappa and dashpot gamma is a damped oscillator with damping ratio
//   zeta = gamma / (2 sqrt(kappa m_eff)).
// For zeta < 1 it separates after half a damped period and e_n = exp(-pi zeta / sqrt(1 - zeta^2)),
// i.e. zeta = -ln e_n / sqrt(pi^2 + ln^2 e_n). For zeta >= 1 the grains never rebound: e_n = 0.

/// Damping ratio zeta [-] for restitution e_n in (0, 1].
template <typename T>
T damping_ratio_from_restitution(const T& e_n) {
  using std::log;
  using std::sqrt;
  const T ln_e = log(e_n);
  return -ln_e / sqrt(std::numbers::pi * std::numbers::pi + ln_e * ln_e);
}

/// Restitution e_n [-] for damping ratio zeta >= 0 (0 when zeta >= 1: no rebound).
double restitution_from_damping_ratio(double zeta);

/// Dashpot gamma [kg/s] = 2 zeta sqrt(kappa m_eff) giving restitution e_n in a Hooke collision.
template <typename T>
T gamma_from_restitution(const T& e_n, const T& kappa, const T& m_eff) {
  using std::sqrt;
  return 2.0 * damping_ratio_from_restitution(e_n) * sqrt(kappa * m_eff);
}

/// Restitution of a Hooke collision with dashpot gamma [kg/s], stiffness kappa [N/m], m_eff [kg].
double restitution_from_gamma(double gamma, double kappa, double m_eff);

/// Contact duration [s] of a Hooke-dashpot collision: pi / sqrt(kappa/m_eff - (gamma/(2 m_eff))^2).
/// Infinite (no rebound) for zeta >= 1.
double hooke_collision_time(double kappa, double m_eff, double gamma);

/// gamma_hat of two equal grains (m_eff = m/2) colliding with restitution e_n: sqrt(2) zeta.
/// Note gamma_hat <= sqrt(2) for any e_n > 0: strongly overdamped sediments need gamma directly.
template <typename T>
T gamma_hat_from_restitution(const T& e_n) {
  return std::numbers::sqrt2 * damping_ratio_from_restitution(e_n);
}

// ---- Hertz contact --------------------------------------------------------------------------------
// Two elastic spheres: F = (4/3) E* sqrt(R_eff) delta^(3/2), with 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2
// and 1/R_eff = 1/R1 + 1/R2. The tangent stiffness is dF/d delta = 2 E* sqrt(R_eff delta).

/// Effective modulus E* [Pa] of two materials (E [Pa], nu [-]).
double hertz_effective_modulus(double E1, double nu1, double E2, double nu2);
/// Hertz normal force [N] at overlap delta [m].
double hertz_force(double E_star, double R_eff, double delta);
/// Hertz tangent stiffness dF/d delta [N/m] at overlap delta [m].
double hertz_stiffness(double E_star, double R_eff, double delta);
/// Overlap [m] at which the Hertz force equals F [N].
double hertz_overlap(double E_star, double R_eff, double force);

/// Exact tangent stiffness kappa [N/m] of a contact between two equal grains (diameter d [m],
/// modulus E [Pa], Poisson ratio nu) carrying the force F0 = P0 d^2 of a confining pressure P0 [Pa]
/// (thesis section 2.2.2): kappa = (3/2)^(1/3) E*^(2/3) P0^(1/3) d with E* = E / (2 (1 - nu^2)).
double hertz_kappa_from_pressure(double E, double nu, double d, double P0);

/// The thesis's rounded form, eq. 2.18: kappa = 0.72 E d (P0/E)^(1/3). The exact constant for nu = 0
/// is (3/8)^(1/3) = 0.7211...; hertz_kappa_from_pressure(E, 0, d, P0) reproduces it.
double thesis_kappa_eq_2_18(double E, double d, double P0);

// ---- LAMMPS gran/hooke convention (for interoperability) ------------------------------------------
// pair gran/hooke[/history] takes kn, kt [force/distance] and gamma_n, gamma_t [1/time]; the normal
// force is kn delta - m_eff gamma_n v_n, so gamma_n is a dashpot per unit reduced mass. The LAMMPS
// example scripts (and the thesis) set them from Young's modulus and Poisson's ratio:
//   G = E / (2 (1 + nu)),  kn = 4 G / (3 (1 - nu)),  kt = 4 G / (2 - nu),
//   gamma_n = 2 zeta sqrt(kn / m_eff)  (zeta from e_n as above).

struct LammpsHooke {
  double kn;       ///< normal stiffness [N/m]
  double kt;       ///< tangential stiffness [N/m]
  double gamma_n;  ///< normal dashpot per unit reduced mass [1/s]
};

/// LAMMPS example-script stiffnesses from E [Pa] and nu, and gamma_n for restitution e_n and the
/// reduced mass m_eff [kg] of the pair it is tuned for.
LammpsHooke lammps_hooke_from_material(double E, double nu, double e_n, double m_eff);
/// Dashpot gamma [kg/s] of this project's convention from LAMMPS's gamma_n [1/s].
inline double gamma_from_lammps(double gamma_n, double m_eff) { return gamma_n * m_eff; }
/// LAMMPS's gamma_n [1/s] from this project's gamma [kg/s].
inline double lammps_gamma_n(double gamma, double m_eff) { return gamma / m_eff; }

}  // namespace sedwave::forward
