#include "sedwave/forward/channel/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {
namespace {

/// Portable standard normal deviates (Box-Muller on mt19937_64's exact bit stream).
class NormalSource {
 public:
  explicit NormalSource(std::uint64_t seed) : rng_(seed) {}
  double uniform() { return (static_cast<double>(rng_() >> 11) + 0.5) * 0x1.0p-53; }
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double phi = 2.0 * std::numbers::pi * uniform();
    spare_ = r * std::sin(phi);
    has_spare_ = true;
    return r * std::cos(phi);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// Uniform grid over the periodic x-y cross-section and z, for overlap checks during placement.
class PlacementGrid {
 public:
  /// Cells of at least `cell` across; along z periodic over [z_lo, z_hi) or open (cells clamp).
  PlacementGrid(double width, double z_lo, double z_hi, double cell, bool periodic_z)
      : width_(width), z_lo_(z_lo), length_(z_hi - z_lo), periodic_z_(periodic_z),
        n_xy_(std::max(1, static_cast<int>(width / cell))),
        n_z_(periodic_z ? std::max(1, static_cast<int>((z_hi - z_lo) / cell))
                        : std::max(1, static_cast<int>((z_hi - z_lo) / cell) + 1)),
        cell_xy_(width / n_xy_), cell_z_(periodic_z ? length_ / n_z_ : cell),
        cells_(static_cast<size_t>(n_xy_ * n_xy_ * n_z_)) {}

  [[nodiscard]] bool overlaps(const std::vector<dem::Grain>& grains, const dem::Vec3& p, double r) const {
    const int cx = cell_x(p.x), cy = cell_x(p.y), cz = cell_z(p.z);
    // Neighbouring cells far enough to hold any partner: radii are below one cell.
    // A periodic axis of fewer than 5 cells would visit a cell twice; harmless (overlap is a yes/no).
    for (int dz = -2; dz <= 2; ++dz) {
      int z = cz + dz;
      if (periodic_z_) z = ((z % n_z_) + n_z_) % n_z_;
      else if (z < 0 || z >= n_z_) continue;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          for (size_t k : cells_[index(wrap(cx + dx), wrap(cy + dy), z)]) {
            const dem::Grain& g = grains[k];
            const double ddx = periodic(p.x - g.position.x), ddy = periodic(p.y - g.position.y);
            double ddz = p.z - g.position.z;
            if (periodic_z_) ddz -= length_ * std::round(ddz / length_);
            const double reach = r + g.radius;
            if (ddx * ddx + ddy * ddy + ddz * ddz < reach * reach) return true;
          }
        }
      }
    }
    return false;
  }
  void insert(size_t k, const dem::Vec3& p) { cells_[index(cell_x(p.x), cell_x(p.y), cell_z(p.z))].push_back(k); }

 private:
  [[nodiscard]] int cell_x(double x) const { return std::clamp(static_cast<int>(x / cell_xy_), 0, n_xy_ - 1); }
  [[nodiscard]] int cell_z(double z) const { return std::clamp(static_cast<int>((z - z_lo_) / cell_z_), 0, n_z_ - 1); }
  [[nodiscard]] int wrap(int c) const { return ((c % n_xy_) + n_xy_) % n_xy_; }
  [[nodiscard]] size_t index(int x, int y, int z) const { return static_cast<size_t>((z * n_xy_ + y) * n_xy_ + x); }
  [[nodiscard]] double periodic(double d) const { return d - width_ * std::round(d / width_); }
  double width_, z_lo_, length_;
  bool periodic_z_;
  int n_xy_, n_z_;
  double cell_xy_, cell_z_;
  std::vector<std::vector<size_t>> cells_;
};

double sample_diameter(const SizeDistribution& s, NormalSource& normal) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const double d = s.mean + s.sd * normal.normal();
    if (d >= s.min && d <= s.max) return d;
  }
  throw std::invalid_argument("grain-size distribution puts almost no mass inside [min, max]");
}

/// One wall: a square grid of wall grains tiling the periodic cross-section, at height z_centre
/// plus clipped normal offsets.
void add_wall(const ChannelGeometry& g, double z_centre, std::int32_t group, std::int32_t body, std::int64_t& next_id,
              NormalSource& normal, std::vector<dem::Grain>& grains) {
  const int per_side = std::max(1, static_cast<int>(std::ceil(g.width / (0.65 * g.wall_diameter))));
  const double spacing = g.width / per_side;
  for (int iy = 0; iy < per_side; ++iy) {
    for (int ix = 0; ix < per_side; ++ix) {
      dem::Grain w;
      w.id = next_id++;
      w.group = group;
      w.body = body;
      w.radius = 0.5 * g.wall_diameter;
      w.mass = sphere_mass(g.density, g.wall_diameter);
      const double offset = std::clamp(g.wall_roughness * normal.normal(), -0.5, 0.5);
      w.position = {(ix + 0.5) * spacing, (iy + 0.5) * spacing, z_centre + offset};
      grains.push_back(w);
    }
  }
}

void validate(const ChannelGeometry& g) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("channel geometry: " + what); };
  if (g.n_grains < 1) fail("n_grains must be positive");
  if (!(g.width >= g.sizes.max)) fail("width must be at least the largest grain diameter");
  if (!(g.sizes.min > 0.0 && g.sizes.min <= g.sizes.mean && g.sizes.mean <= g.sizes.max)) {
    fail("size range must satisfy 0 < min <= mean <= max");
  }
  if (!(g.sizes.sd >= 0.0)) fail("size sd must be non-negative");
  if (!(g.density > 0.0)) fail("density must be positive");
  if (!(g.wall_diameter > 0.0)) fail("wall_diameter must be positive");
  if (!(g.initial_packing_fraction > 0.0 && g.initial_packing_fraction <= 0.3)) {
    fail("initial_packing_fraction must lie in (0, 0.3] (random sequential addition jams below 0.38)");
  }
}

}  // namespace

double sphere_mass(double density, double diameter) { return grain_mass(density, diameter); }

ChannelConfiguration generate_channel(const ChannelGeometry& g) {
  validate(g);
  NormalSource normal(g.seed);
  std::vector<double> diameters(static_cast<size_t>(g.n_grains));
  double volume = 0.0;
  for (double& d : diameters) {
    d = sample_diameter(g.sizes, normal);
    volume += std::numbers::pi / 6.0 * d * d * d;
  }
  const double wall_r = 0.5 * g.wall_diameter;
  ChannelConfiguration c;
  // Flow grains start above the roughest lower-wall grain; a periodic cell has no walls.
  c.flow_bottom = g.periodic ? 0.0 : 2.0 * wall_r + 0.5 + 0.5 * g.sizes.max;
  const double length = volume / (g.initial_packing_fraction * g.width * g.width);
  c.flow_top = c.flow_bottom + length;

  std::int64_t next_id = 1;
  PlacementGrid grid = g.periodic ? PlacementGrid(g.width, c.flow_bottom, c.flow_top, g.sizes.max, true)
                                  : PlacementGrid(g.width, c.flow_bottom - 1.0, c.flow_top + 1.0, g.sizes.max, false);
  for (double d : diameters) {
    dem::Grain grain;
    grain.id = next_id++;
    grain.group = kFlowGroup;
    grain.radius = 0.5 * d;
    grain.mass = sphere_mass(g.density, d);
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      grain.position = {g.width * normal.uniform(), g.width * normal.uniform(),
                        c.flow_bottom + (c.flow_top - c.flow_bottom) * normal.uniform()};
      placed = !grid.overlaps(c.grains, grain.position, grain.radius);
    }
    if (!placed) throw std::runtime_error("channel geometry: random placement failed; lower initial_packing_fraction");
    grid.insert(c.grains.size(), grain.position);
    c.grains.push_back(grain);
  }
  if (g.periodic) {
    c.box.lo = {0.0, 0.0, c.flow_bottom};
    c.box.hi = {g.width, g.width, c.flow_top};
    c.box.periodic = {true, true, true};
    return c;
  }
  add_wall(g, wall_r, kLowerWallGroup, kLowerWallBody, next_id, normal, c.grains);
  add_wall(g, c.flow_top + 0.5 + 0.5 * g.sizes.max + wall_r, kUpperWallGroup, kUpperWallBody, next_id, normal, c.grains);

  c.box.lo = {0.0, 0.0, -g.wall_diameter};
  c.box.hi = {g.width, g.width, c.flow_top + 2.0 * g.wall_diameter + 2.0};
  c.box.periodic = {true, true, false};
  return c;
}

}  // namespace sedwave::forward::channel
