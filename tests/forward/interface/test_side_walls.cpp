// Side walls and the static precompression of a hexagonal packing between them: a bead's bounce
// on a wall against Hertz's rigid-wall closed forms and Coulomb's impulse ratio, a bead's friction
// limit against the dashpot's closed form with and without rotation, a zig-zag column
// between walls against its statically determinate forces, a wide packing against force balance
// row by row, and a loaded packing whose contacts stick, stable at the largest tolerance and growing
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
    const double input = run.energies().balance();
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
    // The friction's books hold what the bead lost: kinetic + dissipated is the input.
    EXPECT_GT(run.energies().friction_work, 0.1 * input);
    EXPECT_NEAR(run.energies().balance() / input, 1.0, 1e-5);  // the normal bounce's 1.6e-6 (above)
  }
}

// After the relaxation the packing is at rest: released, it gains no kinetic energy beyond round-off
// (measured: 2e-16 J against 3e-5 J held in its contacts).
void expect_at_rest(GranularPlate& run) {
  const double held = run.energies().contact;
  double most = 0.0;
  for (int s = 0; s < 4000; ++s) {
    run.step();
    most = std::max(most, kinetic(run));
  }
  EXPECT_LT(most, 1e-9 * held);
}

// Bond force from an overlap (Hertz, bead on bead), and the bond's angle from the horizontal.
double bond_force(const Grain& a, const Grain& b) {
  const double d = overlap(a, b);
  return d > 0.0 ? k_grain * d * std::sqrt(d) : 0.0;
}
double bond_angle(const Grain& a, const Grain& b) { return std::atan2(std::abs(b.y - a.y), std::abs(b.x - a.x)); }

// One bead per row between walls 3r apart: a zig-zag of 60-degree bonds, statically determinate.
// At rest Coulomb-tanh carries nothing, so every bond carries the load P vertically, F_k = P / sin(theta_k),
// and each bead's wall takes its bonds' horizontal parts, W = sum F cos(theta) (P/sqrt(3) at the
// ends, 2P/sqrt(3) between). The angles follow from the Hertz overlaps, dx = r + dw_k + dw_(k+1)
// between the walls and cos(theta_k) = dx / (2r - db_k), solved here by a fixed point; F = P/cos(30)
// to O(delta/r).
// One bead pressed into a frictional wall, alone (no plate, no neighbours): its friction limit is the
// predicted-velocity scheme's dashpot limit 1/beta, beta = mu k_s F_n / m_t, where the slip's inertia
// is 1/m_t = 1/m + r^2/I when the bead turns (7/2 m^-1 for a solid sphere) and 1/m when rotation is off.
TEST(SideWalls, FrictionLimitIsTheDashpotsOnTheSlipsInertia) {
  constexpr double mu = 0.4, ks = 300.0, depth = 2e-7;
  for (const bool rotation : {true, false}) {
    std::vector<Grain> bead = chain(1);
    bead[0].x = 1e-2;
    GranularPlate run(bead, steel, std::nullopt, InterfaceContacts{0.0, ks, 1.0, rotation}, StepControl{0.2});
    SideWalls wall;
    wall.left = bead[0].x - bead[0].radius + depth;
    wall.modulus = wall_modulus;
    wall.friction = mu;
    run.set_side_walls(wall);
    const Grain& g = run.grains()[0];
    const double inverse_mt = 1.0 / g.mass + (rotation ? g.radius * g.radius / g.inertia : 0.0);
    const double beta = mu * ks * k_wall * depth * std::sqrt(depth) * inverse_mt;
    // The overlap is r - (x - wall): its round-off, 10^-2 m / 2e-7 m times 10^-16, is 5e-12 of it.
    EXPECT_NEAR(run.current_limits().friction * beta, 1.0, 1e-9) << "rotation " << rotation;
  }
}

TEST(SideWalls, ZigZagColumnCarriesTheStaticallyDeterminateForces) {
  constexpr int rows = 6;
  constexpr double load = 5.0, r = bead_radius;
  auto [p, run] = loaded_packing(rows, 1, load, InterfaceContacts{0.3, 1e3, 1.0, true}, 0.3);
  std::vector<double> theta(rows - 1, std::numbers::pi / 3.0), force(rows - 1), wall(rows);
  for (int iteration = 0; iteration < 100; ++iteration) {
    for (int k = 0; k + 1 < rows; ++k) force[k] = load / std::sin(theta[k]);
    for (int k = 0; k < rows; ++k)
      wall[k] = (k > 0 ? force[k - 1] * std::cos(theta[k - 1]) : 0.0) + (k + 1 < rows ? force[k] * std::cos(theta[k]) : 0.0);
    for (int k = 0; k + 1 < rows; ++k) {
      const double dx = r + std::pow(wall[k] / k_wall, 2.0 / 3.0) + std::pow(wall[k + 1] / k_wall, 2.0 / 3.0);
      theta[k] = std::acos(dx / (2.0 * r - std::pow(force[k] / k_grain, 2.0 / 3.0)));
    }
  }
  const auto& g = run.grains();
  double left = 0.0, right = 0.0;
  for (int k = 0; k < rows; ++k) (k % 2 == 0 ? left : right) += wall[k];
  for (int k = 0; k + 1 < rows; ++k) {
    const double f = bond_force(g[k], g[k + 1]);
    if (verbose)
      std::printf("bond %d: %.7g N, closed form %.7g N (P/cos 30 = %.7g N), angle %.6f deg\n", k, f, force[k],
                  load / std::cos(std::numbers::pi / 6.0), bond_angle(g[k], g[k + 1]) * 180.0 / std::numbers::pi);
    EXPECT_NEAR(f / force[k], 1.0, 1e-4);
    EXPECT_NEAR(bond_angle(g[k], g[k + 1]) / theta[k], 1.0, 1e-6);
    EXPECT_NEAR(f / (load / std::cos(std::numbers::pi / 6.0)), 1.0, 1e-3);
  }
  EXPECT_NEAR(run.left_wall_force() / left, 1.0, 1e-4);
  EXPECT_NEAR(run.right_wall_force() / right, 1.0, 1e-4);
  EXPECT_NEAR(run.plate_normal_force() / load, 1.0, 1e-4);
  expect_at_rest(run);
}

// Bead `bead` of a relaxed packing struck at (0.2, -0.5) m/s and run for `duration`: the share of the
// strike friction took, and the largest drift of the balance over the run against the strike (the
// static state and the load's work included).
struct StruckRun {
  double friction_share;
  double worst_balance;
};
StruckRun strike_and_run(GranularPlate& run, int bead, double duration) {
  run.grains_mutable()[static_cast<std::size_t>(bead)].vy = -0.5;
  run.grains_mutable()[static_cast<std::size_t>(bead)].vx = 0.2;
  run.refresh_forces();
  const double before = run.energies().balance(), struck = kinetic(run);
  double worst = 0.0;
  const double end = run.time() + duration;
  while (run.time() < end) {
    run.step(end - run.time());
    worst = std::max(worst, std::abs(run.energies().balance() - before));
  }
  const StruckRun result{run.energies().friction_work / struck, worst / struck};
  if (verbose)
    std::printf("struck: friction took %.3g of the strike, balance within %.3g of it in %ld steps\n",
                result.friction_share, result.worst_balance, run.steps());
  return result;
}

// A hexagonal packing between walls under P on each bead of its top row: with the walls carrying no
// vertical load at rest, the bonds between any two rows carry N P vertically, and so does the plate;
// the walls push equally. A top-row bead on two beads (its row's contacts open) splits its load
// along the two 60-degree bonds, F = P / (2 cos 30) each; the corner bead on one bond takes P / cos 30.
TEST(SideWalls, HexagonalPackingCarriesItsLoadRowByRow) {
  constexpr int rows = 4, columns = 5;
  constexpr double load = 5.0;
  auto [p, run] = loaded_packing(rows, columns, load, InterfaceContacts{0.3, 1e3, 1.0, true}, 0.3);
  const auto& g = run.grains();
  std::vector<double> vertical(rows - 1, 0.0);
  std::vector<std::vector<double>> top_bonds(columns);
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      const int ri = static_cast<int>(i) / columns, rj = static_cast<int>(j) / columns;
      const double f = bond_force(g[i], g[j]);
      if (rj != ri + 1 || f == 0.0) continue;
      vertical[ri] += f * std::sin(bond_angle(g[i], g[j]));
      if (rj == rows - 1) top_bonds[static_cast<std::size_t>(j) % columns].push_back(f);
    }
  for (int k = 0; k + 1 < rows; ++k) EXPECT_NEAR(vertical[k] / (columns * load), 1.0, 1e-4) << "rows " << k;
  EXPECT_NEAR(run.plate_normal_force() / (columns * load), 1.0, 1e-4);
  EXPECT_NEAR(run.left_wall_force() / run.right_wall_force(), 1.0, 1e-4);
  const double split = load / (2.0 * std::cos(std::numbers::pi / 6.0));
  for (const auto& bonds : top_bonds) {
    ASSERT_TRUE(bonds.size() == 1 || bonds.size() == 2);
    for (const double f : bonds) EXPECT_NEAR(f / (bonds.size() == 2 ? split : 2.0 * split), 1.0, 1e-3);
  }
  // Each bead's share of the contacts' energy (its walls' whole, half of each bond) sums to the books'.
  double shares = 0.0;
  for (const double e : run.grain_energies()) shares += e;
  const Energies e = run.energies();
  EXPECT_NEAR(shares / (e.grain_translation + e.grain_rotation + e.contact), 1.0, 1e-12);
  expect_at_rest(run);
  // Struck, with friction along the walls and between beads: the balance closes (the static state
  // and the load's work included).
  const StruckRun struck = strike_and_run(run, rows * columns - 3, 3e-5);
  EXPECT_GT(struck.friction_share, 0.1);
  EXPECT_LT(struck.worst_balance, 1e-5);
}

// Walls hold a loaded packing whatever the grains' contact law (a DEM law, any tangential and
// rolling part; the walls' own contact stays Hertz with Coulomb-tanh): the relaxation runs on the
// normal law alone, so at rest the plate carries the load and the walls push equally, a history
// spring starts unloaded and the packing stays at rest; struck, friction acts and the balance closes
// with the springs' energy in the contacts' books.
TEST(SideWalls, HoldALoadedPackingWithEveryGrainContactLaw) {
  constexpr int rows = 3, columns = 3;
  constexpr double load = 5.0, mu = 0.3;
  const InterfaceContacts coulomb_tanh{mu, 1e3, 1.0, true};
  using sedwave::forward::dem::ContactSpec;
  ContactSpec hooke;
  hooke.normal = "hooke";
  hooke["kn"] = 1e7;
  hooke.tangential = "coulomb_tanh";
  hooke["friction"] = mu;
  hooke["tanh_velocity_scale"] = 1e3;
  const ContactSpec history = history_and_rolling(coulomb_tanh);
  ContactSpec mindlin = grain_contact_spec(coulomb_tanh, steel);
  mindlin.tangential = "mindlin";
  mindlin.erase("tanh_velocity_scale");
  for (const ContactSpec& spec : {hooke, history, mindlin}) {
    InterfaceContacts contacts = coulomb_tanh;
    contacts.grain_contact = spec;
    auto [p, run] = loaded_packing(rows, columns, load, contacts, mu);
    EXPECT_NEAR(run.plate_normal_force() / (columns * load), 1.0, 1e-4) << spec.normal << "+" << spec.tangential;
    EXPECT_NEAR(run.left_wall_force() / run.right_wall_force(), 1.0, 1e-4) << spec.tangential;
    EXPECT_GT(run.left_wall_force(), 0.1 * load) << spec.tangential;
    expect_at_rest(run);
    const StruckRun struck = strike_and_run(run, rows * columns - 2, 2e-5);
    EXPECT_GT(struck.friction_share, 1e-3) << spec.tangential;
    EXPECT_LT(struck.worst_balance, 1e-5) << spec.tangential;
  }
}

// The loaded packing with friction, rebuilt from a relaxed one under `control`.
GranularPlate rebuilt(const Loaded& relaxed, const InterfaceContacts& contacts, double wall_friction, double load,
                      const StepControl& control) {
  const auto& p = relaxed.packing;
  GranularPlate run(relaxed.run.grains(), steel, *relaxed.run.plate(), contacts, control);
  run.set_side_walls(side_walls_around(p, 0.0, true, true, wall_modulus, wall_friction));
  std::vector<int> top;
  for (int c = 0; c < p.columns; ++c) top.push_back((p.rows - 1) * p.columns + c);
  run.set_static_load(top, 0.0, -load);
  run.plate_displacement_mutable() = relaxed.run.plate_displacement();
  run.refresh_forces();
  return run;
}

// Small spins on every bead, |w| <= 0.002 rad/s: slips below 1e-5 m/s, k_s |slip| < 0.01 at
// k_s = 1000 s/m, so every contact sticks (Coulomb-tanh in its linear, dashpot range). The kinetic
// energy given, about 1e-13 J, is 500 times what the relaxed state's residue sets moving
// (expect_at_rest), and an unstable mode grows 10^4 times before tanh saturates. Returns it.
double nudge(GranularPlate& run) {
  double given = 0.0;
  unsigned state = 12345u;
  for (auto& g : run.grains_mutable()) {
    state = state * 1664525u + 1013904223u;  // a fixed sequence (Numerical Recipes' LCG)
    g.spin = 0.002 * (2.0 * static_cast<double>(state) / 4294967296.0 - 1.0);
    given += 0.5 * g.inertia * g.spin * g.spin;
  }
  run.refresh_forces();
  return given;
}

// The most kinetic energy the packing holds over `steps` steps, against what it was given.
double growth(GranularPlate& run, int steps) {
  const double given = nudge(run);
  double most = 0.0;
  for (int s = 0; s < steps; ++s) {
    run.step();
    most = std::max(most, kinetic(run));
  }
  return most / given;
}

// The largest tolerance a scene accepts (granular_plate.hpp, StepControl): the step theta times the
// interface's limits, those of the packing's collective modes under this scheme (dem/critical_step.hpp).
constexpr double kLargestTolerance = 0.5;

// A loaded packing whose contacts stick: Coulomb-tanh is then a dashpot c = mu k_s |F_n| at each
// contact, and it binds the step (mu k_s F_n / m is about 100 times the Hertz frequency here). The
// forces see v_(n+1/2) + (h/2) a_n, for which a dashpot mode of rate lambda (an eigenvalue of
// M^-1 C) is stable only for h < 1/lambda (the amplification matrix of v' = -lambda v has
// determinant -h lambda / 2 and trace 1 - 3 h lambda / 2). The uniform spin, every bead turning alike,
// slips each bead-bead contact at (a_i + a_j) w: its Rayleigh quotient R = sum c (a_i + a_j)^2 / sum I
// bounds lambda_max from below (a hexagon's interior: 30/7 times a pair's rate), so h = 2/R grows
// whatever the other modes do. At the largest tolerance the packing's kinetic energy never exceeds
// what it was given (friction only takes energy).
TEST(StickingPacking, StableAtTheLargestToleranceAndGrowingBeyondTheUniformSpinsLimit) {
  constexpr int rows = 4, columns = 5;
  constexpr double load = 5.0, mu = 0.5, ks = 1e3;
  const InterfaceContacts sticky{mu, ks, 1.0, true};
  const Loaded relaxed = loaded_packing(rows, columns, load, sticky, mu);
  double rate = 0.0, inertia = 0.0;
  const auto& g = relaxed.run.grains();
  for (std::size_t i = 0; i < g.size(); ++i) {
    inertia += g[i].inertia;
    for (std::size_t j = i + 1; j < g.size(); ++j) {
      const double d = overlap(g[i], g[j]);
      if (d > 0.0) rate += mu * ks * bond_force(g[i], g[j]) * std::pow(g[i].radius + g[j].radius - d, 2);
    }
  }
  rate /= inertia;
  GranularPlate stable = rebuilt(relaxed, sticky, mu, load, StepControl{kLargestTolerance});
  const StepLimits limits = stable.current_limits();
  const double step = kLargestTolerance * limits.tightest();
  const double stable_growth = growth(stable, 3000);
  StepControl beyond{kLargestTolerance};
  beyond.fixed_step = 2.0 / rate;
  GranularPlate unstable = rebuilt(relaxed, sticky, mu, load, beyond);
  const double unstable_growth = growth(unstable, 300);
  if (verbose) {
    std::printf("step at theta = %.1f: %.4g s = %.4f / R (friction limit %.4g s = %.4f / R, Hertz %.4g s); growth "
                "%.3g there, %.3g at 2/R = %.4g s\n",
                kLargestTolerance, step, step * rate, limits.friction, limits.friction * rate, limits.hertz,
                stable_growth, unstable_growth, 2.0 / rate);
    // Fixed steps in multiples of 1/R, up to and beyond where the packing's fastest mode grows.
    for (const double x : {0.3, 0.5, 0.6, 0.65, 0.7, 0.72, 0.75, 1.0}) {
      StepControl fixed{kLargestTolerance};
      fixed.fixed_step = x / rate;
      GranularPlate scan = rebuilt(relaxed, sticky, mu, load, fixed);
      std::printf("step %.2f / R = %.2f times the interface's limit: kinetic energy %.3g times the given after 5000 "
                  "steps\n", x, fixed.fixed_step / limits.tightest(), growth(scan, 5000));
    }
  }
  EXPECT_LT(stable_growth, 1.01);
  EXPECT_GT(unstable_growth, 100.0);
}

}  // namespace
