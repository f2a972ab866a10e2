#pragma once
// Linear (Hooke) normal contact with a viscous dashpot, the thesis's model (eq. 3.1, normal part):
//   F_n = kn delta - gamma v_n,   delta = overlap, v_n = separation rate.
// With the restitution dashpot a binary collision rebounds with exactly e_n and lasts
//   t_col = pi / sqrt(kn/m_eff - (gamma/(2 m_eff))^2)   (units.hpp: hooke_collision_time).
// The force is not clipped at zero: near separation the dashpot may pull briefly, which is what
// makes the e_n mapping exact (and is what LAMMPS gran/hooke does).
#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/dashpot.hpp"

namespace sedwave::forward::dem {

struct HookeNormal {
  double kn;              ///< normal stiffness [force/length]
  LinearDashpot dashpot;  ///< normal damping

  /// What the force needs of one pair beyond its geometry: the pair's dashpot, fixed by its masses.
  struct Pair {
    double gamma;  ///< [force time/length]
  };
  /// effective_mass = 1 / (1/m_i + 1/m_j) (a rigid-wall grain counts as infinitely heavy).
  [[nodiscard]] Pair pair(double effective_mass, double /*r_i*/, double /*r_j*/) const {
    return {dashpot.gamma(kn, effective_mass)};
  }
  /// The normal force is a spring and a dashpot in parallel: spring(overlap) - dashpot(overlap) v_n.
  [[nodiscard]] double spring(double overlap, const Pair& /*p*/) const { return kn * overlap; }
  [[nodiscard]] double dashpot_at(double /*overlap*/, const Pair& p) const { return p.gamma; }
  /// Normal force magnitude on i along the contact normal (positive = repulsive).
  [[nodiscard]] double force(const ContactPoint& c, const Pair& p) const {
    return spring(c.overlap, p) - dashpot_at(c.overlap, p) * c.normal_velocity;
  }
  /// Stiffness and damping of the contact (the same at any overlap).
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double /*radius*/,
                                             double /*overlap*/) const {
    return {kn, dashpot.gamma(kn, effective_mass)};
  }
  /// Elastic energy stored at overlap delta.
  [[nodiscard]] double energy(double overlap, double /*r_i*/, double /*r_j*/) const {
    return 0.5 * kn * overlap * overlap;
  }
};

}  // namespace sedwave::forward::dem
