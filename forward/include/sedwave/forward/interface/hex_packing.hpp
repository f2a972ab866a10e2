#pragma once
// Hexagonal (triangular-lattice) packings of equal spheres in the plane z = 0, resting above the
// plate's top edge y = 0. Units: any consistent set (SI in scenes).
#include <vector>

namespace sedwave::forward::interface {

/// One sphere confined to the plane: position (x, y), velocity, spin about z, radius, mass, inertia.
struct Grain {
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  double spin = 0.0;  ///< omega_z
  double radius = 0.0;
  double mass = 0.0;
  double inertia = 0.0;  ///< (2/5) m r^2 of a solid sphere
};

/// rows_parallel: rows of touching grains run along the plate (x), alternate rows shifted by half a
/// pitch; rows_perpendicular: chains of touching grains stand on the plate (along y), alternate
/// chains shifted by half a pitch (so only every other chain touches the plate).
enum class HexOrientation { rows_parallel, rows_perpendicular };

struct HexPacking {
  int rows = 1;          ///< layers counted away from the plate (rows_parallel) or along it (perpendicular)
  int columns = 1;       ///< grains per row (rows_parallel) or per chain (perpendicular)
  double radius = 0.0;   ///< sphere radius
  double density = 0.0;  ///< grain density [mass/length^3]
  double gap = 0.0;      ///< surface gap between lattice neighbours (pitch = 2 r + gap)
  double x_offset = 0.0; ///< x of the packing's left boundary
  double lift = 0.0;     ///< gap between the lowest grains and the plate edge y = 0
  HexOrientation orientation = HexOrientation::rows_parallel;
};

/// The packing's grains, at rest, ordered row by row from the plate upwards (rows_parallel) or chain
/// by chain from the left (rows_perpendicular).
[[nodiscard]] std::vector<Grain> make_hex_packing(const HexPacking& p);

/// The packing's width along x, from its left boundary x_offset to its rightmost bead's edge
/// (rows_parallel: the odd rows' half-pitch shift included when there are two rows or more).
[[nodiscard]] double hex_packing_width(const HexPacking& p);

}  // namespace sedwave::forward::interface
