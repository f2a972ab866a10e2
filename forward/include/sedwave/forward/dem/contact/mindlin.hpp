#pragma once
// Hertz-Mindlin tangential spring: the history spring of tangential_history.hpp with Mindlin's
// no-slip stiffness of two elastic spheres pressed by a Hertz contact (Mindlin 1949, J. Appl. Mech.
// 16, 259; the "no-slip" model of Di Renzo & Di Maio 2004, Chem. Eng. Sci. 59, 525, eq. 14):
//   kt = 8 G* a,   a = sqrt(R_eff delta),   1/G* = 2 (2 - nu) / G,   G = E / (2 (1 + nu)),
// for identical grains of Young's modulus E and Poisson's ratio nu. The stiffness follows the
// overlap, so a Hertz normal law (whose stiffness is 2 E* a) keeps a fixed ratio kt/kn; the shear
// displacement accumulates as for the linear spring and slides at the Coulomb limit.
#include <array>
#include <cmath>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"
#include "sedwave/forward/dem/contact/tangential_history.hpp"

namespace sedwave::forward::dem {

struct MindlinTangential {
  static constexpr std::string_view name = "mindlin";
  static constexpr std::array keys{&keys::friction, &keys::youngs_modulus, &keys::poisson_ratio, &keys::gamma_t};
  static constexpr bool enabled = true;
  static constexpr bool needs_history = true;
  static constexpr bool linearised = true;

  double shear_modulus;  ///< G* [force/length^2]
  double gamma_t;        ///< tangential dashpot per unit effective mass [1/time] (LAMMPS gamma_t)
  double friction;       ///< Coulomb coefficient mu

  static MindlinTangential from(const ContactValues& v, double /*normal_stiffness*/) {
    const double E = v.required(keys::youngs_modulus, name);
    const double nu = v.get(keys::poisson_ratio, keys::default_poisson_ratio);
    const double G = E / (2.0 * (1.0 + nu));
    return {G / (2.0 * (2.0 - nu)), v.get(keys::gamma_t, 0.0), v.get(keys::friction, 0.0)};
  }

  /// kt / sqrt(delta) = 8 G* sqrt(R_eff), and the pair's dashpot m_eff gamma_t.
  struct Pair {
    double stiffness_scale;
    double damping;
  };
  [[nodiscard]] Pair pair(double effective_mass, double r_i, double r_j) const {
    return {8.0 * shear_modulus * std::sqrt(r_i * r_j / (r_i + r_j)), effective_mass * gamma_t};
  }
  /// kt at overlap delta of a pair of effective radius R_eff.
  [[nodiscard]] double stiffness(double overlap, double effective_radius) const {
    return 8.0 * shear_modulus * std::sqrt(effective_radius * overlap);
  }
  /// Tangential force on i; updates the pair's shear displacement in place.
  [[nodiscard]] Vec3 force(const ContactPoint& c, const Pair& p, const Vec3& tangential_velocity,
                           double normal_force, double dt, Vec3& shear) const {
    const double kt = p.stiffness_scale * std::sqrt(c.overlap);
    // At zero overlap (the root of a touching distance rounded to the reach) the spring is gone.
    if (!(kt > 0.0)) {
      shear = Vec3{};
      return {};
    }
    return history_spring_force(kt, p.damping, friction, c, tangential_velocity, normal_force, dt, shear);
  }
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double effective_radius, double overlap,
                                             double /*normal_force*/) const {
    return {stiffness(overlap, effective_radius), gamma_t * effective_mass};
  }
  /// Energy of the spring at its present stiffness.
  [[nodiscard]] double energy(double overlap, double r_i, double r_j, const Vec3& shear) const {
    return 0.5 * stiffness(overlap, r_i * r_j / (r_i + r_j)) * norm2(shear);
  }
  [[nodiscard]] TangentialBlock linear_block(double overlap, double r_i, double r_j) const {
    return {stiffness(overlap, r_i * r_j / (r_i + r_j)), gamma_t, friction};
  }
};

}  // namespace sedwave::forward::dem
