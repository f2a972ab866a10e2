#pragma once
// The simulation box: an axis-aligned cuboid, periodic or open along each axis.
// Channels are periodic in x and y; z (the long axis) is open or periodic. Along an open axis the
// bounds only describe where the grains are (they are shrink-wrapped at every neighbour rebuild).
#include <array>
#include <cmath>

#include "sedwave/forward/dem/vec3.hpp"

namespace sedwave::forward::dem {

struct Box {
  Vec3 lo{0.0, 0.0, 0.0};
  Vec3 hi{1.0, 1.0, 1.0};
  std::array<bool, 3> periodic{true, true, false};

  [[nodiscard]] double length(int axis) const { return hi[axis] - lo[axis]; }

  /// Maps a coordinate into [lo, hi) along every periodic axis (open axes are left alone).
  void wrap(Vec3& p) const {
    for (int a = 0; a < 3; ++a) {
      if (!periodic[a]) continue;
      const double L = length(a);
      double& c = p[a];
      if (c < lo[a] || c >= hi[a]) {
        c -= L * std::floor((c - lo[a]) / L);
        if (c >= hi[a]) c = lo[a];  // floor() round-off at the upper face
      }
    }
  }
};

}  // namespace sedwave::forward::dem
