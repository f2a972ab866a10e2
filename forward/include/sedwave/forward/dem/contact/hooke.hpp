#pragma once
// Linear (Hooke) normal contact with a viscous dashpot, the thesis's model (eq. 3.1, normal part):
//   F_n = kn delta - gamma v_n,   delta = overlap, v_n = separation rate.
// With the restitution dashpot a binary collision rebounds with exactly e_n and lasts
//   t_col = pi / sqrt(kn/m_eff - (gamma/(2 m_eff))^2)   (units.hpp: hooke_collision_time).
// The force is not clipped at zero: near separation the dashpot may pull briefly, which is what
// makes the e_n mapping exact (and is what LAMMPS gran/hooke does).
#include <array>
#include <stdexcept>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/dashpot.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::dem {

struct HookeNormal {
  static constexpr std::string_view name = "hooke";
  static constexpr ContactKey kn_key{"kn", "kn",
                                     "normal stiffness kn [force/length]; or youngs_modulus (and poisson_ratio): "
                                     "kn = 4G/(3(1-nu)), G = E/(2(1+nu)) (LAMMPS example scripts)",
                                     io::Range::positive()};
  static constexpr ContactKey gamma_n_key{"lammps_gamma_n", "gamma-n",
                                          "hooke dashpot per unit reduced mass [1/time] (LAMMPS gamma_n)",
                                          io::Range::non_negative()};
  static constexpr std::array keys{&kn_key, &keys::youngs_modulus, &keys::poisson_ratio, &keys::restitution,
                                   &keys::gamma, &gamma_n_key};
  /// The keys that choose the dashpot (at most one may be given).
  static constexpr std::array dashpot_keys{&keys::restitution, &keys::gamma, &gamma_n_key};

  double kn;              ///< normal stiffness [force/length]
  LinearDashpot dashpot;  ///< normal damping

  /// kn, or E and nu; at most one of restitution, gamma, lammps_gamma_n (none: undamped).
  static HookeNormal from(const ContactValues& v) {
    if (v.has(kn_key) == v.has(keys::youngs_modulus))
      throw std::invalid_argument("give exactly one of 'kn' or 'youngs_modulus'");
    const double kn = v.has(kn_key) ? v.required(kn_key, name)
                                    : lammps_hooke_from_material(v.required(keys::youngs_modulus, name),
                                                                 v.get(keys::poisson_ratio, keys::default_poisson_ratio),
                                                                 1.0, 1.0).kn;
    if (int(v.has(keys::restitution)) + int(v.has(keys::gamma)) + int(v.has(gamma_n_key)) > 1)
      throw std::invalid_argument("hooke: give at most one of restitution, gamma, lammps_gamma_n");
    LinearDashpot dashpot = LinearDashpot::constant(v.get(keys::gamma, 0.0));
    if (v.has(keys::restitution)) dashpot = LinearDashpot::from_restitution(v.required(keys::restitution, name));
    if (v.has(gamma_n_key)) dashpot = LinearDashpot::lammps_gamma_n(v.required(gamma_n_key, name));
    return {kn, dashpot};
  }

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
  /// Stiffness and damping of the contact (the same at any overlap): time steps, linear engine.
  [[nodiscard]] ContactOscillator oscillator(double effective_mass, double /*radius*/,
                                             double /*overlap*/) const {
    return {kn, dashpot.gamma(kn, effective_mass)};
  }
  /// Stiffness kept down to zero overlap, where the contact opens: a kink in the energy that the
  /// linear engine's static solver must see (and the packing's stiffness unit kappa).
  [[nodiscard]] double stiffness_at_contact() const { return kn; }
  /// Elastic energy stored at overlap delta.
  [[nodiscard]] double energy(double overlap, double /*r_i*/, double /*r_j*/) const {
    return 0.5 * kn * overlap * overlap;
  }
  /// The spring's energy where its force at `overlap` is `force` (already computed): (1/2) F delta.
  [[nodiscard]] static double energy_of_force(double force, double overlap) { return 0.5 * force * overlap; }
};

}  // namespace sedwave::forward::dem
