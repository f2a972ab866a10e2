#pragma once
// What a contact law sees of one touching pair (i, j): its geometry and motion now. Built once per
// pair by the force loop and shared by the normal, tangential and rolling laws of a ContactModel.
// What depends only on the grains' masses and radii (a dashpot from the effective mass, an effective
// radius) is each law's `Pair`, tabulated when the neighbour list is built (force_loop.hpp).
#include "sedwave/forward/dem/vec3.hpp"

namespace sedwave::forward::dem {

struct ContactPoint {
  Vec3 normal;             ///< unit vector from j to i (a repulsive force on i points along it)
  double overlap;          ///< r_i + r_j - |x_i - x_j| > 0
  double normal_velocity;  ///< (v_i - v_j) . normal: positive while the grains separate
  double radius_i;
  double radius_j;
};

/// Linearisation of a contact around a reference state, for time-step selection: the pair behaves
/// like m_eff x'' = -stiffness x - damping x'.
struct ContactOscillator {
  double stiffness;  ///< [force/length]
  double damping;    ///< [force time/length]
};

}  // namespace sedwave::forward::dem
