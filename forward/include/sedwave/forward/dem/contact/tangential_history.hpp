#pragma once
// Tangential spring with history and Coulomb limit, as LAMMPS pair gran/hooke/history (Cundall &
// Strack). Each contact keeps its accumulated shear displacement s; every step
//   s += v_t dt,  s -= (s.n) n                 (rotate s into the current tangent plane)
//   F_t = -(kt s + m_eff gamma_t v_t)          (spring + dashpot; gamma_t per unit m_eff, LAMMPS)
//   |F_t| > mu |F_n|  =>  F_t scaled to mu |F_n|, and s reset to the spring length that carries it.
// v_t is the relative tangential velocity of the contact point (rotation included).
#include <cmath>

#include "sedwave/forward/dem/contact/contact_point.hpp"

namespace sedwave::forward::dem {

struct TangentialSpringHistory {
  static constexpr bool enabled = true;
  static constexpr bool needs_history = true;

  double kt;        ///< tangential stiffness [force/length]
  double gamma_t;   ///< tangential dashpot per unit effective mass [1/time] (LAMMPS gamma_t)
  double friction;  ///< Coulomb coefficient mu

  /// The pair's dashpot, m_eff gamma_t [force time/length].
  struct Pair {
    double damping;
  };
  [[nodiscard]] Pair pair(double effective_mass, double /*r_i*/, double /*r_j*/) const {
    return {effective_mass * gamma_t};
  }
  /// Tangential force on i; updates the pair's shear displacement in place.
  [[nodiscard]] Vec3 force(const ContactPoint& c, const Pair& p, const Vec3& tangential_velocity,
                           double normal_force, double dt, Vec3& shear) const {
    shear += dt * tangential_velocity;
    shear -= dot(shear, c.normal) * c.normal;
    const Vec3 damping = p.damping * tangential_velocity;
    Vec3 ft = -(kt * shear + damping);
    const double limit = friction * std::abs(normal_force);
    const double ft2 = norm2(ft);
    if (ft2 > limit * limit) {
      const double scale = limit / std::sqrt(ft2);
      shear = scale * (shear + (1.0 / kt) * damping) - (1.0 / kt) * damping;
      ft *= scale;
    }
    return ft;
  }
  /// Tangential stiffness and damping for time-step selection.
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double /*normal_force*/) const {
    return {kt, gamma_t * effective_mass};
  }
};

}  // namespace sedwave::forward::dem
