#pragma once
// Hertz normal contact with a Tsuji-type dashpot:
//   F_n = k_h delta^(3/2) - alpha sqrt(m_eff k_h) delta^(1/4) v_n,   k_h = (4/3) E* sqrt(R_eff),
// E* the effective modulus (units.hpp: hertz_effective_modulus) and 1/R_eff = 1/r_i + 1/r_j.
// Scaling delta and t (see docs/dem.md) turns a binary collision into the universal equation
//   y'' = -y^(3/2) - alpha y^(1/4) y',  y(0) = 0, y'(0) = 1,
// so the restitution depends on alpha only, never on the impact speed. e_n(alpha) has no closed form;
// hertz_restitution() integrates the universal equation and hertz_alpha_from_restitution() inverts it
// (both to ~1e-6), which is the documented, tested e_n mapping for Hertz.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::dem {

/// Restitution coefficient of a Hertz-Tsuji collision with dimensionless damping alpha >= 0.
[[nodiscard]] double hertz_restitution(double alpha);
/// Damping alpha giving restitution e_n in (0, 1].
[[nodiscard]] double hertz_alpha_from_restitution(double e_n);
/// Duration of an undamped Hertz collision at impact speed v: 2.9432 delta_max / v
/// = 2.868 (m_eff^2 / (R E*^2 v))^(1/5).
[[nodiscard]] double hertz_collision_time(double effective_modulus, double effective_radius,
                                          double effective_mass, double impact_speed);

struct HertzNormal {
  static constexpr std::string_view name = "hertz";
  static constexpr ContactKey modulus_key{"effective_modulus", "effective-modulus",
                                          "hertz E* [force/length^2]; or youngs_modulus (and poisson_ratio): "
                                          "E* = E / (2 (1 - nu^2))",
                                          io::Range::positive()};
  static constexpr std::array keys{&modulus_key, &keys::youngs_modulus, &keys::poisson_ratio, &keys::restitution,
                                   &keys::gamma};
  /// The keys that choose the dashpot (at most one may be given).
  static constexpr std::array dashpot_keys{&keys::restitution, &keys::gamma};

  double effective_modulus;  ///< E* [force/length^2]
  double alpha;              ///< dimensionless dashpot (from e_n via hertz_alpha_from_restitution)

  /// E*, or E and nu of identical grains; restitution or alpha (key gamma), or neither (undamped).
  static HertzNormal from(const ContactValues& v) {
    if (v.has(modulus_key) == v.has(keys::youngs_modulus))
      throw std::invalid_argument("hertz: give exactly one of 'effective_modulus' or 'youngs_modulus'");
    double modulus = 0.0;
    if (v.has(modulus_key)) {
      modulus = v.required(modulus_key, name);
    } else {
      const double E = v.required(keys::youngs_modulus, name);
      const double nu = v.get(keys::poisson_ratio, keys::default_poisson_ratio);
      modulus = hertz_effective_modulus(E, nu, E, nu);
    }
    if (v.has(keys::restitution) && v.has(keys::gamma))
      throw std::invalid_argument("hertz: give at most one of restitution, gamma");
    const double alpha = v.has(keys::restitution) ? hertz_alpha_from_restitution(v.required(keys::restitution, name))
                                                  : v.get(keys::gamma, 0.0);
    return {modulus, alpha};
  }

  /// What the force needs of one pair beyond its geometry, fixed by its radii and masses.
  struct Pair {
    double effective_radius;  ///< R_eff
    double damping;           ///< alpha sqrt(m_eff (4/3) E*): the dashpot is this times a^(1/2)
  };
  [[nodiscard]] Pair pair(double effective_mass, double r_i, double r_j) const {
    return {r_i * r_j / (r_i + r_j), alpha * std::sqrt(effective_mass * (4.0 / 3.0) * effective_modulus)};
  }
  /// k_h = (4/3) E* sqrt(R): the spring is k_h delta^(3/2).
  [[nodiscard]] static double stiffness(double effective_modulus, double effective_radius) {
    return (4.0 / 3.0) * effective_modulus * std::sqrt(effective_radius);
  }
  /// The normal force is a spring and a dashpot in parallel: spring(overlap) - dashpot(overlap) v_n.
  [[nodiscard]] double spring(double overlap, const Pair& p) const {
    const double contact_radius = std::sqrt(p.effective_radius * overlap);  // a = sqrt(R delta)
    return (4.0 / 3.0) * effective_modulus * contact_radius * overlap;     // k_h delta^(3/2)
  }
  /// alpha sqrt(m_eff k_h sqrt(delta)) = damping a^(1/2)
  [[nodiscard]] double dashpot_at(double overlap, const Pair& p) const {
    return p.damping * std::sqrt(std::sqrt(p.effective_radius * overlap));
  }
  [[nodiscard]] double force(const ContactPoint& c, const Pair& p) const {
    return spring(c.overlap, p) - dashpot_at(c.overlap, p) * c.normal_velocity;
  }
  /// Linearisation at a given overlap: tangent stiffness 2 E* sqrt(R delta) and the dashpot there.
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double effective_radius,
                                             double overlap) const {
    const double a = std::sqrt(effective_radius * overlap);
    return {2.0 * effective_modulus * a,
            alpha * std::sqrt(effective_mass * (4.0 / 3.0) * effective_modulus * a)};
  }
  /// A Hertz contact has no stiffness at zero overlap (its energy has no kink there).
  [[nodiscard]] double stiffness_at_contact() const { return 0.0; }
  /// (2/5) k_h delta^(5/2): (2/5) the spring's force times delta, with its one root and no power.
  [[nodiscard]] double energy(double overlap, double r_i, double r_j) const {
    return energy(overlap, Pair{r_i * r_j / (r_i + r_j), 0.0});
  }
  /// The same for a pair's effective radius (a sphere on a flat: R_eff = r).
  [[nodiscard]] double energy(double overlap, const Pair& p) const { return energy_of_force(spring(overlap, p), overlap); }
  /// The spring's energy where its force at `overlap` is `force` (already computed): (2/5) F delta.
  [[nodiscard]] static double energy_of_force(double force, double overlap) { return 0.4 * force * overlap; }
};

}  // namespace sedwave::forward::dem
