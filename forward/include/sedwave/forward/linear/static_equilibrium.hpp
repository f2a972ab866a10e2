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
// bordered by one row and column for the loaded wall's height, its own unknown, by block Cholesky
// with the slab solver. Three things make this work on long, disordered columns:
//  * Active set. The energy is piecewise quadratic with kinks (a Hooke contact keeps its stiffness
//    down to zero overlap, then has none), so Newton with the present contacts overshoots wherever a
//    step opens a contact or closes a gap. Each step's model holds touching the pairs (contacts and
//    nearby gaps) that its own solution overlaps, re-solved until that set stops changing.
//  * A positive definite model. Where K is indefinite (the pre-stress -f/r makes a compressed chain
//    buckle sideways, and a packing on its way to a minimum has unstable soft spots) the model drops
//    the pre-stress, which keeps the step downhill and every long-wavelength mode exact. mu only
//    regularises rattlers: a fixed Levenberg-Marquardt floor would stall the longest modes of a long
//    column, whose stiffness per mass is of order (d / L)^2.
//  * A backtracking line search on the true energy (Armijo), inside a trust region on the relative
//    displacement across contacts.
// Where a packing is still rearranging (a soft spot collapsing), Newton's steps crawl; the caller
// then alternates with FIRE, which follows the instability dynamically (channel/preparation.cpp).
// Measured: docs/linear.md, "Preparing long channels".
//
// A box periodic along z (a periodic cell, channel/periodic_cell.hpp) is relaxed too: its contacts
// wrap around, which breaks the slab structure, so its steps use a sparse Cholesky factorisation.
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
  int iterations = 0;            ///< trial steps taken (energy evaluations)
  int directions = 0;            ///< Newton directions solved for (factorisations that succeeded)
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
