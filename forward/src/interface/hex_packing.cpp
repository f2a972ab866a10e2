#include "sedwave/forward/interface/hex_packing.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace sedwave::forward::interface {

std::vector<Grain> make_hex_packing(const HexPacking& p) {
  if (p.rows < 1 || p.columns < 1) throw std::invalid_argument("hex packing: rows and columns must be >= 1");
  // Grains are indexed by int: the count is taken in 64 bits and refused before it overflows.
  if (std::int64_t{p.rows} * p.columns > std::numeric_limits<int>::max())
    throw std::invalid_argument("hex packing: more grains than an int indexes");
  if (!(p.radius > 0.0) || !(p.density > 0.0))
    throw std::invalid_argument("hex packing: radius and density must be > 0");
  if (!(p.gap >= 0.0) || !(p.lift >= 0.0)) throw std::invalid_argument("hex packing: gap and lift must be >= 0");
  const double pitch = 2.0 * p.radius + p.gap;
  const double layer = pitch * std::sqrt(3.0) / 2.0;  // distance between adjacent rows of a triangular lattice
  const double mass = (4.0 / 3.0) * std::numbers::pi * p.radius * p.radius * p.radius * p.density;
  std::vector<Grain> grains;
  grains.reserve(static_cast<std::size_t>(p.rows) * static_cast<std::size_t>(p.columns));
  for (int row = 0; row < p.rows; ++row) {
    const double shift = (row % 2 == 1) ? 0.5 * pitch : 0.0;
    for (int c = 0; c < p.columns; ++c) {
      Grain g;
      if (p.orientation == HexOrientation::rows_parallel) {
        g.x = p.x_offset + p.radius + shift + c * pitch;
        g.y = p.lift + p.radius + row * layer;
      } else {
        g.x = p.x_offset + p.radius + row * layer;
        g.y = p.lift + p.radius + shift + c * pitch;
      }
      g.radius = p.radius;
      g.mass = mass;
      g.inertia = 0.4 * mass * p.radius * p.radius;
      grains.push_back(g);
    }
  }
  return grains;
}

double hex_packing_width(const HexPacking& p) {
  const double pitch = 2.0 * p.radius + p.gap;
  return p.orientation == HexOrientation::rows_parallel
             ? (p.columns - 1) * pitch + 2.0 * p.radius + (p.rows > 1 ? 0.5 * pitch : 0.0)
             : (p.rows - 1) * pitch * std::sqrt(3.0) / 2.0 + 2.0 * p.radius;
}

}  // namespace sedwave::forward::interface
