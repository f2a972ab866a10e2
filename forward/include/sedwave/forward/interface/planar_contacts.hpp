#pragma once
// Hertz + Coulomb-tanh contacts between spheres in the plane z = 0 (the interface's default grain
// contact), evaluated over arrays so that the compiler runs several contacts at a time in SIMD lanes:
// two at a time in the baseline x86-64 instruction set, four where the processor has AVX2 (chosen
// when the program starts; the lanes round as one contact at a time does, so the results are the
// same on either). The laws are the DEM engine's (dem::HertzNormal's spring and dashpot,
// dem::CoulombTanhFriction's force) and the composition is the engine's (dem::ContactModel) written
// in the plane: with the tangent t = (-n_y, n_x), the slip v_rel - v_n n + n x (a_i w_i + a_j w_j) z
// is t (v_rel . t - a_i w_i - a_j w_j), the friction force is F_t t, and the torques about z are
// -a_i F_t and -a_j F_t, with the lever arms a = r - delta/2 to the middle of the overlap.
// Units: any consistent set (SI in scenes).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"

namespace sedwave::forward::interface {

/// arm^2/I: what turning adds to the inverse mass of a slip at `arm` from the centre of a grain of
/// moment of inertia I.
[[nodiscard]] inline double turning_inverse_mass(double arm, double inertia) { return arm * arm / inertia; }

/// delta_max^(5/2) of the largest overlap a Hertz pair can reach from its state: its elastic energy
/// now plus the relative kinetic energy of approach, (2/5) k delta_max^(5/2) = (2/5) k delta_+^(5/2)
/// + m v_n^2 / 2 when closing (v_n < 0). Zero when neither touching nor closing. `closing_factor`
/// is the pair's (5/4) m / k. The step limit ranks pairs by it (docs/interface.md, "The self-adaptive
/// step").
[[nodiscard]] inline double reach_energy(double overlap, double normal_velocity, double closing_factor) {
  const double touching = std::max(overlap, 0.0);
  const double closing = normal_velocity < 0.0 ? closing_factor * normal_velocity * normal_velocity : 0.0;
  return touching * touching * std::sqrt(touching) + closing;
}

/// Each touching pair i-j: the centres' offset x_i - x_j and its squared length, the relative velocity
/// v_i - v_j and the spins w_i, w_j the forces see, the radii and moments of inertia, the normal
/// law's pair constants, the distance r_i + r_j at which the grains touch, 1/m_i + 1/m_j, and the
/// pair's (5/4) m / k for reach_energy.
struct PlanarPairs {
  const double *d2, *dx, *dy, *dvx, *dvy, *spin_i, *spin_j, *radius_i, *radius_j, *inertia_i, *inertia_j;
  const double *effective_radius, *damping, *reach, *inverse_mass, *closing_factor;
};

/// Each pair's contact: the distance, the unit normal n (from j to i), the overlap, the normal
/// velocity v_rel . n, the normal law's spring force and dashpot coefficient (0 undamped), the
/// friction force along t, and the slip's inverse mass 1/m_i + 1/m_j [+ a_i^2/I_i + a_j^2/I_j where
/// the grains turn], and reach_energy. The normal force on i is (spring - dashpot v_n) n.
struct PlanarContacts {
  double *distance, *nx, *ny, *overlap, *normal_velocity, *spring, *dashpot, *tangential, *inverse_slip_mass;
  double* reach_energy;
};

/// The first `count` pairs' contacts. `damped`: whether the normal law has a dashpot (else it is
/// taken as 0 without evaluating it); `turning`: whether the grains turn. The arrays do not overlap.
void evaluate_planar_contacts(const dem::HertzNormal& normal, const dem::CoulombTanhFriction& friction, bool damped,
                              bool turning, const PlanarPairs& pairs, const PlanarContacts& contacts,
                              std::size_t count);

}  // namespace sedwave::forward::interface
