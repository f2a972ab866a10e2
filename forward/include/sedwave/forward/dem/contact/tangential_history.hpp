#pragma once
// Tangential spring with history and Coulomb limit, as LAMMPS pair gran/hooke/history (Cundall &
// Strack 1979, Geotechnique 29, 47). Each contact keeps its accumulated shear displacement s; every step
//   s += v_t dt,  s -= (s.n) n                 (rotate s into the current tangent plane)
//   F_t = -(kt s + m_eff gamma_t v_t)          (spring + dashpot; gamma_t per unit m_eff, LAMMPS)
//   |F_t| > mu |F_n|  =>  F_t scaled to mu |F_n|, and s reset to the spring length that carries it.
// v_t is the relative tangential velocity of the contact point (rotation included).
#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"

namespace sedwave::forward::dem {

/// What the linear engine needs of a sticking tangential contact at its static overlap: a spring
/// and a dashpot on the contact point's tangential displacement, and the Coulomb coefficient that
/// bounds where sticking holds.
struct TangentialBlock {
  double stiffness;         ///< [force/length]
  double damping_per_mass;  ///< dashpot per unit effective mass [1/time]
  double friction;          ///< mu
};

/// One step of a history spring of stiffness kt: updates the shear displacement and returns the
/// tangential force, capped at mu |F_n| (the spring then slips to the length that carries the cap).
/// Shared by the history laws, which differ in their stiffness only.
[[nodiscard]] inline Vec3 history_spring_force(double kt, double damping_coefficient, double friction,
                                               const ContactPoint& c, const Vec3& tangential_velocity,
                                               double normal_force, double dt, Vec3& shear) {
  shear += dt * tangential_velocity;
  shear -= dot(shear, c.normal) * c.normal;
  const Vec3 damping = damping_coefficient * tangential_velocity;
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

struct TangentialSpringHistory {
  static constexpr std::string_view name = "spring_history";
  static constexpr ContactKey kt_key{"kt", "kt", "spring_history tangential stiffness kt [force/length] (default 2/7 kn)",
                                     io::Range::positive()};
  static constexpr std::array keys{&keys::friction, &kt_key, &keys::gamma_t};
  static constexpr bool enabled = true;
  static constexpr bool needs_history = true;
  static constexpr bool linearised = true;

  double kt;        ///< tangential stiffness [force/length]
  double gamma_t;   ///< tangential dashpot per unit effective mass [1/time] (LAMMPS gamma_t)
  double friction;  ///< Coulomb coefficient mu

  /// kt defaults to 2/7 of a linear normal law's stiffness (LAMMPS's kt NULL); a normal law without
  /// one (Hertz) needs kt given.
  static TangentialSpringHistory from(const ContactValues& v, double normal_stiffness) {
    if (!v.has(kt_key) && !(normal_stiffness > 0.0))
      throw std::invalid_argument("spring_history: this normal law has no constant stiffness: give 'kt'");
    return {v.get(kt_key, 2.0 / 7.0 * normal_stiffness), v.get(keys::gamma_t, 0.0), v.get(keys::friction, 0.0)};
  }

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
    return history_spring_force(kt, p.damping, friction, c, tangential_velocity, normal_force, dt, shear);
  }
  /// Tangential stiffness and damping for time-step selection.
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double /*radius*/, double /*overlap*/,
                                             double /*normal_force*/) const {
    return {kt, gamma_t * effective_mass};
  }
  /// Energy stored in the stretched spring.
  [[nodiscard]] double energy(double /*overlap*/, double /*r_i*/, double /*r_j*/, const Vec3& shear) const {
    return 0.5 * kt * norm2(shear);
  }
  [[nodiscard]] TangentialBlock linear_block(double /*overlap*/, double /*r_i*/, double /*r_j*/) const {
    return {kt, gamma_t, friction};
  }
};

}  // namespace sedwave::forward::dem
