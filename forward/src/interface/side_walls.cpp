#include "sedwave/forward/interface/side_walls.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"

namespace sedwave::forward::interface {
double GranularPlate::wall_overlap(const Grain& g, double face, double normal) {
  return g.radius - normal * (g.x - face);
}

SideWalls side_walls_around(const HexPacking& p, double gap, bool left, bool right, double modulus, double friction) {
  SideWalls walls;
  if (left) walls.left = p.x_offset - gap;
  if (right) walls.right = p.x_offset + hex_packing_width(p) + gap;
  walls.modulus = modulus;
  walls.friction = friction;
  return walls;
}

void GranularPlate::set_side_walls(const SideWalls& walls) {
  if ((walls.left || walls.right) && !(walls.modulus > 0.0))
    throw std::invalid_argument("interface: a side wall needs a Hertz modulus > 0");
  if (!(walls.friction >= 0.0)) throw std::invalid_argument("interface: a side wall's friction must be >= 0");
  if (walls.friction > 0.0 && !(contacts_.tanh_velocity_scale > 0.0))
    throw std::invalid_argument("interface: tanh_velocity_scale must be > 0");
  if (walls.left && walls.right && !(*walls.left < *walls.right))
    throw std::invalid_argument("interface: the left wall must stand left of the right one");
  walls_ = walls;
  compute_forces(0.0);
}

// A sphere on a flat (R* = r) through the DEM's Hertz law, no dashpot. The wall's normal points into
// the packing: +x for the left wall, -x for the right one. The contact point lies at -normal r from
// the centre, so its velocity along the wall is v_y - normal w r, and a friction force F_t along y
// there has the torque (-normal r x) x (F_t y) = -normal r F_t z.
void GranularPlate::add_wall_contacts(int index) {
  const auto i = static_cast<std::size_t>(index);
  const auto& g = grains_[i];
  for (int side = 0; side < 2; ++side) {
    const auto& face = side == 0 ? walls_.left : walls_.right;
    if (!face) continue;
    const double normal = side == 0 ? 1.0 : -1.0;
    const double overlap = wall_overlap(g, *face, normal);
    if (overlap <= 0.0) continue;
    const dem::HertzNormal law{walls_.modulus, 0.0};
    const double fn = law.spring(overlap, {g.radius, 0.0});
    conservative_[i].fx += normal * fn;
    contact_energy_ += dem::HertzNormal::energy_of_force(fn, overlap);
    wall_force_[side] += fn;
    if (walls_.friction <= 0.0) continue;
    const auto& seen = seen_[i];
    const dem::Vec3 slip{0.0, seen.vy - normal * seen.spin * g.radius, 0.0};
    const dem::CoulombTanhFriction friction{walls_.friction, contacts_.tanh_velocity_scale};
    const dem::ContactPoint point{{normal, 0.0, 0.0}, overlap, 0.0, g.radius, std::numeric_limits<double>::infinity()};
    dem::Vec3 unused;
    const double ft = friction.force(point, {}, slip, fn, 0.0, unused).y;
    friction_[i].fy += ft;
    friction_[i].torque -= normal * g.radius * ft;
  }
}

void GranularPlate::add_wall_energies(std::vector<double>& held) const {
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& g = grains_[i];
    for (const auto& [face, normal] : {std::pair{walls_.left, 1.0}, std::pair{walls_.right, -1.0}}) {
      const double overlap = face ? wall_overlap(g, *face, normal) : 0.0;
      if (overlap > 0.0) held[i] += dem::HertzNormal{walls_.modulus, 0.0}.energy(overlap, {g.radius, 0.0});
    }
  }
}

}  // namespace sedwave::forward::interface
