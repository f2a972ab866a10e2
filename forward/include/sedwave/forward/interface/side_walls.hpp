#pragma once
// Rigid side walls beside the packing: the half-planes x <= left and x >= right, fixed in space,
// standing on the plate without touching it (docs/interface.md, "Side walls"). A bead presses on a
// wall through a Hertz contact of a sphere on a flat (R* = r, E* of bead and wall) with
// Coulomb-tanh friction along the wall (y), the contacts' k_s. The walls do no work: they hold a
// packing that a static load would spread, so that it can be precompressed at rest.
#include <optional>

#include "sedwave/forward/interface/hex_packing.hpp"

namespace sedwave::forward::interface {

struct SideWalls {
  std::optional<double> left;   ///< x of the left wall's face (beads to its right)
  std::optional<double> right;  ///< x of the right wall's face (beads to its left)
  double modulus = 0.0;         ///< Hertz E* of a bead on the wall [force/length^2]
  double friction = 0.0;        ///< mu of Coulomb-tanh along the wall (0: frictionless)
};

/// Walls at `gap` from the packing's outermost beads (0: touching them), on the sides asked for.
[[nodiscard]] SideWalls side_walls_around(const HexPacking& p, double gap, bool left, bool right, double modulus,
                                          double friction);

}  // namespace sedwave::forward::interface
