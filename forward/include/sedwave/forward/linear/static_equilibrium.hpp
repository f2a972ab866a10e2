#pragma once
// Static equilibrium of a frictionless packing by Newton's method on its elastic energy, with the
// slab solver for every step: the relaxation that FIRE does in tens of thousands of steps, done in
// tens of O(N) solves.
//
// Why: FIRE (channel/preparation.hpp) relaxes a long channel no faster than its slowest mode, a
// compression wave that crosses the column, so its cost grows like N^2 for a channel of N grains;
// a Newton step resolves every wavelength at once. The energy is
//   E = sum over contacts U(overlap) + F Z,
// U the normal law's elastic energy and Z the height of an optional loaded wall pushed down with the
// constant force F (a pressure P on a W x W wall: F = P W^2). Its gradient is minus the forces, its
// Hessian the linear engine's stiffness K (with the pre-stress term), so a step solves
//   (K + mu M) du = F(u),
// bordered by one row and column for the loaded wall's height, its own unknown. mu is a
// Levenberg-Marquardt shift: a step is accepted when the energy falls, and mu shrinks towards pure
// Newton (quadratic convergence) as steps succeed; it grows when a step fails, turning the step into
// a short gradient step. It also keeps rattlers and floppy grains (zero rows of K) regular.
// Contacts that open or close are found anew at every trial step. A frictionless Hooke packing can
// hold a contact at the very edge of opening (its energy has a kink there), which Newton cannot
// settle below some residual; the relaxation then stops unconverged with the residual it reached,
// and the caller finishes with FIRE, which needs no derivatives (channel/preparation.cpp).
//
// Only normal laws enter (no tangential history, no rolling): a frictionless packing, as the thesis's
// model and the preparation's compression stage. Serial (the packing on one rank, as the linear
// engine).
//
// Units: those of the packing (lengths, forces, masses as stored in the grains and contact law).
#include <span>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::linear {

/// A rigid body (wall) whose height is free under a constant downward force.
struct LoadedWall {
  int body = 2;        ///< 1 + index of the rigid body, as Grain::body
  double force = 0.0;  ///< the load F along -z [force], e.g. P W^2
};

struct StaticEquilibriumSettings {
  double residual_force_tolerance = 1e-9;  ///< max |F| on a free grain / mean contact force
  double wall_force_tolerance = 1e-9;      ///< | force of the grains on the wall / F - 1 |
  int max_iterations = 100;                ///< trial steps, accepted or not
};

struct StaticEquilibriumReport {
  int iterations = 0;            ///< trial steps taken
  int accepted = 0;              ///< of which accepted
  double residual_ratio = 0.0;   ///< max |F| on a free grain / mean contact force at the end
  double wall_force = 0.0;       ///< force of the grains on the loaded wall (along +z) at the end
  double energy_drop = 0.0;      ///< E(start) - E(end), >= 0
  bool converged = false;
};

/// Moves the free grains of `grains` (and the loaded wall's grains, along z only) to the nearest
/// static equilibrium. Rigid bodies other than the loaded wall stay where they are. Throws
/// std::invalid_argument for laws with tangential or rolling parts (history-dependent).
[[nodiscard]] StaticEquilibriumReport relax_to_equilibrium(std::vector<dem::Grain>& grains, const dem::Box& box,
                                                           const dem::ContactSpec& contact, int n_bodies,
                                                           const LoadedWall* wall,
                                                           const StaticEquilibriumSettings& settings = {});

}  // namespace sedwave::forward::linear
