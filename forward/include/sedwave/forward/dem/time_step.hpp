#pragma once
// Time-step selection and the stability limit of the explicit scheme.
//
// Velocity Verlet as LAMMPS runs it evaluates a dashpot with the half-step velocity. For one contact
// (m_eff x'' = -k x - c x', omega0^2 = k/m_eff, beta = c/m_eff = 2 zeta omega0) one step maps
// (x_n, w_n) (w = velocity seen by the force) linearly with trace 2 - h^2 omega0^2 - h beta and
// determinant 1 - h beta. Jury's conditions give stability iff
//   h^2 omega0^2 + 2 h beta <= 4,  i.e.  h <= h_c = 4 / (beta + sqrt(beta^2 + 4 omega0^2))
//                                              = (2/omega0) (sqrt(1 + zeta^2) - zeta).
// h_c = 2/omega0 without damping and shrinks as damping grows: 0.83/omega0 at zeta = 1 (e_n -> 0),
// ~1/(zeta omega0) for strong damping. The derivation is in docs/dem.md.
//
// The engine evaluates h_c for the lightest pair (m_eff = m_min/2) at the stiffest state it expects
// (Hooke: always kn; Hertz: the tangent stiffness at a reference overlap), for the normal, tangential
// and friction oscillators, and refuses larger user steps. The default step is a fraction (0.01, the
// thesis's choice) of the binary collision time t_col, capped so that a dense packing's collective
// modes stay stable too: their frequencies reach ~2x the pair's (FCC: omega_max^2 = 8k/m against
// 2k/m for a pair), and their damping rates, which scale like omega^2, ~4x. The cap is therefore h_c
// of an oscillator with 2 omega0 and 4 beta: h_c/2 without damping, h_c/4 for strong damping,
// where the pair limit alone left the densest modes of an overdamped packing unstable.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/critical_step.hpp"

namespace sedwave::forward::dem {

struct TimeStepInputs {
  double lightest_mass;             ///< smallest free-grain mass
  double smallest_radius;           ///< smallest grain radius
  double reference_overlap = 0.02;  ///< overlap / smallest radius at which Hertz is linearised
  double viscous_damping = 0.0;     ///< global viscous coefficient (force = -gamma_v v)
  double pair_damping = 0.0;        ///< a dashpot beside the contact's (a fluid's lubrication) of the lightest pair
  double fraction = 0.01;           ///< default dt = fraction * t_col
};

struct TimeStepLimits {
  double collision_time = 0.0;  ///< binary collision time of the lightest pair
  double stable_step = 0.0;     ///< h_c: no larger step is accepted
  double collective_step = 0.0; ///< h_c of the collective modes (2 omega0, 4 beta): caps the default
  double default_step = 0.0;    ///< fraction * collision_time, capped at collective_step
  [[nodiscard]] std::string summary() const;
};

template <class Model>
[[nodiscard]] TimeStepLimits time_step_limits(const Model& model, const TimeStepInputs& in) {
  const double m_eff = 0.5 * in.lightest_mass;
  const double r_eff = 0.5 * in.smallest_radius;
  const double overlap = in.reference_overlap * in.smallest_radius;
  const ContactOscillator n = model.normal.oscillator(m_eff, r_eff, overlap);
  const double omega0 = std::sqrt(n.stiffness / m_eff);
  const double beta = (n.damping + in.pair_damping) / m_eff + in.viscous_damping / in.lightest_mass;
  double stable = verlet_critical_step(omega0, beta);
  double collective = verlet_critical_step(2.0 * omega0, 4.0 * beta);
  if constexpr (Model::has_tangential) {
    // Sliding of the contact point mobilises translation and rotation: for solid spheres its
    // inertia is m_eff / (1 + 5/2).
    const double m_t = m_eff / 3.5;
    const double normal_force = n.stiffness * overlap;
    const ContactOscillator t = model.tangential.oscillator(m_eff, r_eff, overlap, normal_force);
    const double omega_t = std::sqrt(t.stiffness / m_t), beta_t = t.damping / m_t;
    stable = std::min(stable, verlet_critical_step(omega_t, beta_t));
    collective = std::min(collective, verlet_critical_step(2.0 * omega_t, 4.0 * beta_t));
  }
  TimeStepLimits out;
  const double zeta = beta / (2.0 * omega0);
  out.collision_time = zeta < 1.0 ? std::numbers::pi / (omega0 * std::sqrt(1.0 - zeta * zeta))
                                  : std::numbers::pi / omega0;
  out.stable_step = stable;
  out.collective_step = collective;
  out.default_step = std::min(in.fraction * out.collision_time, collective);
  return out;
}

}  // namespace sedwave::forward::dem
