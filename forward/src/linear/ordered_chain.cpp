#include "sedwave/forward/linear/ordered_chain.hpp"

#include <numbers>

#include "sedwave/forward/channel/geometry.hpp"

namespace sedwave::forward::linear {

channel::PreparedChannel ordered_chain(int n, double spacing) {
  channel::PreparedChannel p;
  p.box.lo = {-1.5, -1.5, -1.0};
  p.box.hi = {1.5, 1.5, (n + 2) * spacing};
  for (int i = 0; i <= n + 1; ++i) {
    dem::Grain g;
    g.id = i + 1;
    g.radius = 0.5;
    g.mass = 1.0;  // density 6/pi: unit mass for unit diameter
    g.position = {0.0, 0.0, i * spacing};
    if (i == 0) {
      g.group = channel::kLowerWallGroup;
      g.body = channel::kLowerWallBody;
    } else if (i == n + 1) {
      g.group = channel::kUpperWallGroup;
      g.body = channel::kUpperWallBody;
    }
    p.grains.push_back(g);
  }
  return p;
}

}  // namespace sedwave::forward::linear
