// The interface's step limits for velocity-dependent forces (dem/critical_step.hpp): the closed form
// of the predicted-velocity scheme against its amplification matrix and against a simulated bead
// rubbing on a held edge, and a hexagonal packing's collective friction mode (30/7 of a pair's rate)
// against the adaptive step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "sedwave/forward/dem/critical_step.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::dem::HexagonalCollective;
using sedwave::forward::dem::predicted_velocity_critical_step;
using sedwave::forward::dem::verlet_critical_step;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;

using Matrix = std::array<std::array<double, 3>, 3>;

// One step of x'' = -omega^2 x - beta w on the state (x, v, a): kick, drift, the force at the
// velocity `seen` (predicted: v_{n+1/2} + h/2 a_n; else the half-step velocity), kick.
std::array<double, 3> scheme_step(const std::array<double, 3>& s, double h, double omega, double beta, bool predicted) {
  const double half = s[1] + 0.5 * h * s[2];
  const double x = s[0] + h * half;
  const double seen = predicted ? half + 0.5 * h * s[2] : half;
  const double a = -omega * omega * x - beta * seen;
  return {x, half + 0.5 * h * a, a};
}

// The spectral radius of the step's amplification matrix, as the growth rate of its powers.
double spectral_radius(double h, double omega, double beta, bool predicted) {
  Matrix m{};
  for (int j = 0; j < 3; ++j) {
    std::array<double, 3> e{};
    e[static_cast<std::size_t>(j)] = 1.0;
    const auto col = scheme_step(e, h, omega, beta, predicted);
    for (int i = 0; i < 3; ++i) m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = col[static_cast<std::size_t>(i)];
  }
  // ||M^(2^k)||^(1/2^k), renormalised at each squaring.
  double log_norm = 0.0, power = 1.0;
  for (int k = 0; k < 14; ++k) {
    Matrix sq{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int l = 0; l < 3; ++l) sq[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] +=
            m[static_cast<std::size_t>(i)][static_cast<std::size_t>(l)] * m[static_cast<std::size_t>(l)][static_cast<std::size_t>(j)];
    double norm = 0.0;
    for (const auto& row : sq)
      for (const double x : row) norm = std::max(norm, std::abs(x));
    for (auto& row : sq)
      for (double& x : row) x /= norm;
    log_norm = 2.0 * log_norm + std::log(norm);
    power *= 2.0;
    m = sq;
  }
  return std::exp(log_norm / power);
}

TEST(CriticalStep, ClosedFormsAreWhereTheAmplificationMatrixLeavesTheUnitCircle) {
  // omega = 1; zeta = beta / 2 from an undamped spring to a pure dashpot (omega = 0, beta = 1).
  const std::array<std::array<double, 2>, 5> cases{{{1.0, 0.0}, {1.0, 0.2}, {1.0, 1.0}, {1.0, 6.0}, {0.0, 1.0}}};
  for (const auto& [omega, beta] : cases) {
    for (const bool predicted : {true, false}) {
      const double h_c = predicted ? predicted_velocity_critical_step(omega, beta) : verlet_critical_step(omega, beta);
      EXPECT_LE(spectral_radius(0.995 * h_c, omega, beta, predicted), 1.0 + 1e-3) << omega << " " << beta;
      EXPECT_GT(spectral_radius(1.005 * h_c, omega, beta, predicted), 1.0 + 1e-4) << omega << " " << beta;
    }
  }
  // The predicted velocity halves a dashpot's limit, and at zeta = 0.5 gives 0.83/omega, not 1.24.
  EXPECT_DOUBLE_EQ(predicted_velocity_critical_step(0.0, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(verlet_critical_step(0.0, 2.0), 1.0);
  EXPECT_NEAR(predicted_velocity_critical_step(1.0, 1.0), 2.0 / (1.0 + std::sqrt(2.0)), 1e-15);
  EXPECT_NEAR(verlet_critical_step(1.0, 1.0), 4.0 / (1.0 + std::sqrt(5.0)), 1e-15);
}

// A bead pressed on a held edge by a static load and slipping slowly: Coulomb-tanh is a dashpot
// c = mu F k_s on the slip v + r w, of rate beta = c (1/m + r^2/I) = 3.5 c/m. Returns the slip after
// `steps` fixed steps of h, relative to the first.
double slip_growth(double h_over_limit, int steps) {
  const double load = 5.0;  // [N]
  auto grains = chain(1, 0.0);
  auto& g = grains[0];
  const double modulus = grain_plate_modulus(steel, aluminium, PlateContactModel::interpolated);
  const double k = (4.0 / 3.0) * modulus * std::sqrt(g.radius);
  g.y = g.radius - std::pow(load / k, 2.0 / 3.0);  // at rest under the load
  g.x = 0.5e-3;
  InterfaceContacts contacts;
  contacts.friction = 0.3;
  contacts.tanh_velocity_scale = 100.0;
  const double beta = contacts.friction * load * contacts.tanh_velocity_scale * (1.0 / g.mass + g.radius * g.radius / g.inertia);
  const double slip0 = 1e-12 / contacts.tanh_velocity_scale;  // linear in tanh while it grows 1e6-fold
  g.vx = slip0;
  StepControl control;
  control.fixed_step = h_over_limit * predicted_velocity_critical_step(0.0, beta);
  ElasticPlate plate(aluminium, {1, 1, 1e-3, 1e-3}, {EdgeCondition::clamped, EdgeCondition::clamped,
                                                     EdgeCondition::clamped, EdgeCondition::clamped});
  GranularPlate run({g}, steel, plate, contacts, control);
  run.set_static_load({0}, 0.0, -load);
  for (int i = 0; i < steps; ++i) run.step();
  const auto& end = run.grains()[0];
  return std::abs(end.vx + end.radius * end.spin) / slip0;
}

TEST(CriticalStep, ABeadRubbingOnAHeldEdgeIsStableJustBelowOneOverBetaAndUnstableJustAbove) {
  // Per step the slip mode is multiplied by -0.973 at 0.98 h_c and -1.027 at 1.02 h_c.
  EXPECT_LT(slip_growth(0.98, 800), 1.0);
  EXPECT_GT(slip_growth(1.02, 800), 1e5);
  // Between 1/beta and the half-step velocity's 2/beta this scheme is unstable.
  EXPECT_GT(slip_growth(1.3, 40), 1e3);
}

// A hexagonal patch of 7 x 7 steel beads pressed together (every neighbour overlapping by 1 nm), all
// spinning alike: the uniform-spin friction mode. k_s is large so that friction, not the Hertz
// springs, sets the step. Fills the contact's c/m = mu k_s F_n / m and its (lever arm / r)^2.
struct Patch {
  double c_over_m = 0.0;
  double arm_squared = 0.0;
  /// The uniform-spin mode's rate: each of an interior bead's six contacts slips at 2 a w, so
  /// w' = -6 (2 c a w) a / (2/5 m r^2) w = -30 (c/m) (a/r)^2 w.
  [[nodiscard]] double mode_rate() const { return 30.0 * c_over_m * arm_squared; }
  /// A pair's slip rate, beta = c (2/m + 2 a^2/I) = (c/m) (2 + 5 (a/r)^2) (7 c/m at a = r).
  [[nodiscard]] double pair_rate() const { return c_over_m * (2.0 + 5.0 * arm_squared); }
};

GranularPlate spinning_patch(double spin, double tolerance, Patch& patch) {
  auto grains = make_hex_packing(steel_beads(7, 7));
  const double r = grains[0].radius, delta = 1e-9;
  const double shrink = 1.0 - delta / (2.0 * r);
  for (auto& g : grains) g.x *= shrink, g.y *= shrink, g.spin = spin;
  InterfaceContacts contacts;
  contacts.friction = 0.3;
  contacts.tanh_velocity_scale = 1e8;
  const double k = (4.0 / 3.0) * sedwave::forward::hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                                           steel.youngs_modulus, steel.poisson_ratio) *
                   std::sqrt(0.5 * r);
  patch.c_over_m = contacts.friction * contacts.tanh_velocity_scale * k * delta * std::sqrt(delta) / grains[0].mass;
  patch.arm_squared = std::pow((r - 0.5 * delta) / r, 2);
  return GranularPlate(grains, steel, std::nullopt, contacts, StepControl{tolerance});
}

constexpr double kSpin = 1e-9;        // k_s 2 r w = 5e-4: the linear range of tanh
constexpr int kInterior = 3 * 7 + 3;  // row 3, column 3: six neighbours

TEST(CollectiveFriction, AHexagonalPatchSpinsDownAtThirtySeventhsOfAPairsRate) {
  Patch patch;
  GranularPlate run = spinning_patch(kSpin, 0.5, patch);
  const double h = 1e-6 / patch.mode_rate();
  run.step(h);
  const double rate = -(run.grains()[kInterior].spin - kSpin) / (h * kSpin);
  EXPECT_NEAR(rate / patch.mode_rate(), 1.0, 1e-5);
  EXPECT_NEAR(rate / patch.pair_rate(), HexagonalCollective::friction_with_spin, 1e-5);
}

TEST(CollectiveFriction, TheAdaptiveStepKeepsTheUniformSpinModeStable) {
  Patch patch;
  GranularPlate run = spinning_patch(kSpin, 0.5, patch);
  // The limit lies within the mode's own, 1/rate (a pair's 2/beta would not).
  EXPECT_LE(run.current_limits().friction, 1.0 / patch.mode_rate());
  // At the largest tolerance the interior's spin decays (at the pair's limit it grew 5.8-fold a step).
  for (int i = 0; i < 200; ++i) run.step();
  const double w = run.grains()[kInterior].spin;
  EXPECT_TRUE(std::isfinite(w));
  EXPECT_LT(std::abs(w), kSpin);
}

// A step takes the grain pairs' rates off the force evaluation that ended the step before it (at the
// velocities its forces saw, a half kick from the state's). On the struck frictional packing they stay
// within 10^-3 of the limits computed afresh from the state before each step; a velocity set
// by hand after a step is seen by the next one.
TEST(StepLimits, AStepsLimitsFromTheForcePassTrackTheStatesOwn) {
  InterfaceContacts contacts;
  contacts.friction = 0.3;
  contacts.tanh_velocity_scale = 100.0;
  contacts.rotation = true;
  GranularPlate run(struck_packing(), steel, free_plate(), contacts, StepControl{0.2});
  double worst_hertz = 0.0, worst_friction = 0.0;
  int compared = 0;
  while (run.time() < 4e-6) {
    const StepLimits fresh = run.current_limits();
    run.step();
    const StepLimits& used = run.last_limits();
    EXPECT_EQ(used.plate, fresh.plate);
    if (std::isfinite(fresh.hertz)) worst_hertz = std::max(worst_hertz, std::abs(used.hertz / fresh.hertz - 1.0));
    if (std::isfinite(fresh.friction))
      worst_friction = std::max(worst_friction, std::abs(used.friction / fresh.friction - 1.0));
    ++compared;
  }
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst_hertz, 1e-3);  // measured 3.7e-5 over 290 steps
  EXPECT_LT(worst_friction, 1e-3);  // 4.6e-6
  // Two beads of the top row driven at each other at 20 m/s by hand: the next step's Hertz limit is
  // the state's, not the last force evaluation's.
  const StepLimits before = run.current_limits();
  auto& grains = run.grains_mutable();
  grains[8].vx = 20.0, grains[9].vx = -20.0;
  const StepLimits fresh = run.current_limits();
  ASSERT_LT(fresh.hertz, 0.5 * before.hertz);
  run.step();
  EXPECT_EQ(run.last_limits().hertz, fresh.hertz);
}

}  // namespace
