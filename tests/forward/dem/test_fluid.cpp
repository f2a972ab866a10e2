// The pore fluid's forces (dem/fluid.hpp) against closed forms: the squeeze film between two
// spheres, the Stokes terminal velocity with and without the porosity correction, and a dry run
// left exactly as it was by a fluid whose forces vanish.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

/// Fluid without drag or buoyancy: lubrication alone.
FluidSpec squeeze_film(double viscosity, double roughness, double cutoff) {
  FluidSpec f;
  f.viscosity = viscosity;
  f.density = 0.0;
  f.roughness = roughness;
  f.cutoff = cutoff;
  f.drag = DragLaw::none;
  return f;
}

// A free sphere (radius 1/2) pushed by a constant force F0 toward a frozen sphere of the same
// radius through a viscous film. With A = 6 pi mu R_eff^2 (R_eff = 1/4) and the gap h, the
// leading-order lubrication ODE m h'' = -F0 - A h' / h has, for a start at rest at h0, the exact
// first integral
//   m h' + A ln(h / h0) + F0 t = 0                                  (h_r < h < h_c),
// and below the roughness gap, where the force is that at h_r,
//   m h' + A h / h_r + F0 t = const.
// At small Stokes number (m h F0 / A^2 << 1) the gap closes as h0 exp(-F0 t / A). The work of the
// applied force minus the kinetic energy is what the film dissipated, the integral of A h'^2 / h.
// The same for a frictionless (non-rotating) contact and a frictional one, whose force loop takes
// the rotating path (head on, its tangential force stays zero).
class SqueezeFilm : public ::testing::TestWithParam<std::string> {};

TEST_P(SqueezeFilm, GapFollowsTheLubricationOdeAndDissipatesItsWork) {
  constexpr double radius = 0.5, r_eff = 0.25;
  constexpr double h0 = 0.08, roughness = 0.01, cutoff = 0.2;
  constexpr double viscosity = 1.0, force = 1.0;
  const double a = 6.0 * std::numbers::pi * viscosity * r_eff * r_eff;

  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1e3;
  s.contact.tangential = GetParam();
  if (GetParam() != "none") s.contact["friction"] = 0.5;
  s.skin = 0.05;
  s.fluid = squeeze_film(viscosity, roughness, cutoff);
  Grain wall = testing::make_grain(0, {0, 0, 0}, radius);
  wall.body = 1;
  Grain ball = testing::make_grain(1, {0, 0, 2 * radius + h0}, radius, 1e-2);
  const double m = ball.mass;
  s.gravity = {0, 0, -force / m};
  Engine engine(MPI_COMM_SELF, s, std::vector<Grain>{wall, ball}, {RigidBody("wall", Frozen{})});
  ASSERT_LT(m * h0 * force / (a * a), 1e-3) << "the closed forms below assume a small Stokes number";

  struct Sample {
    double t, h, v;
  };
  std::vector<Sample> path{{0.0, h0, 0.0}};
  double dissipated = 0.0;  // trapezoid sum of A v^2 / max(h, h_r) over the recorded path
  engine.add_step_callback(1, [&](const Engine& e) {
    const std::size_t i = testing::local_index(e.grains(), 1);
    const Sample now{e.time(), e.grains().position[i].z - 2 * radius, e.grains().velocity[i].z};
    const Sample& before = path.back();
    const auto power = [&](const Sample& p) { return a * p.v * p.v / std::max(p.h, roughness); };
    dissipated += 0.5 * (power(before) + power(now)) * (now.t - before.t);
    path.push_back(now);
  });
  // Until the gap has closed to half the roughness.
  while (path.back().h > 0.5 * roughness) engine.run(1000);

  // Each term of the first integral is of the order of F0 t; the residual is measured against the
  // largest, F0 t at the end.
  const double scale = force * path.back().t;
  double worst_first_integral = 0.0, worst_quasi_static = 0.0;
  std::optional<Sample> at_roughness;
  for (const Sample& p : path) {
    if (p.h > roughness) {
      worst_first_integral = std::max(worst_first_integral, std::abs(m * p.v + a * std::log(p.h / h0) + force * p.t) / scale);
      worst_quasi_static = std::max(worst_quasi_static, std::abs(p.h / (h0 * std::exp(-force * p.t / a)) - 1));
    } else {
      if (!at_roughness) at_roughness = p;
      const auto invariant = [&](const Sample& q) { return m * q.v + a * q.h / roughness + force * q.t; };
      worst_first_integral = std::max(worst_first_integral, std::abs(invariant(p) - invariant(*at_roughness)) / scale);
    }
  }
  ASSERT_TRUE(at_roughness.has_value());
  EXPECT_LT(worst_first_integral, 1e-4);
  EXPECT_LT(worst_quasi_static, 1e-3);
  // The closed-form time to reach the roughness gap, A ln(h0 / h_r) / F0, quasi-statically.
  EXPECT_NEAR(at_roughness->t / (a * std::log(h0 / roughness) / force), 1.0, 2e-3);

  const Sample& last = path.back();
  const double work = force * (h0 - last.h) - 0.5 * m * last.v * last.v;
  EXPECT_NEAR(dissipated / work, 1.0, 1e-4);
  std::printf("[ info ] first integral %.2g of F0 t, quasi-static gap %.2g, time to h_r %.2g, energy %.2g\n",
              worst_first_integral, worst_quasi_static,
              at_roughness->t / (a * std::log(h0 / roughness) / force) - 1.0, dissipated / work - 1.0);
}

INSTANTIATE_TEST_SUITE_P(TangentialLaws, SqueezeFilm, ::testing::Values("none", "spring_history"));

// A lone grain sinking from rest: m v' = (m - rho_f V) g - c v, so v = v_t (1 - exp(-c t / m)) with
// v_t = (m - rho_f V) g / c and c = 6 pi mu r f, f = 1 (Stokes) or porosity^(1 - 4.65).
class TerminalVelocity : public ::testing::TestWithParam<DragLaw> {};

TEST_P(TerminalVelocity, IsTheStokesVelocityWithTheDragCorrection) {
  constexpr double radius = 0.5, grain_density = 2.65, g = 1.0;
  FluidSpec fluid;
  fluid.viscosity = 0.05;
  fluid.density = 1.0;
  fluid.roughness = 1e-3;
  fluid.cutoff = 0.1;
  fluid.drag = GetParam();
  fluid.porosity = 0.4;
  const double f = GetParam() == DragLaw::stokes ? 1.0 : std::pow(0.4, -3.65);
  const double c = 6.0 * std::numbers::pi * fluid.viscosity * radius * f;

  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1e3;
  s.gravity = {0, 0, -g};
  s.fluid = fluid;
  const Grain ball = testing::make_grain(0, {0, 0, 0}, radius, grain_density);
  const double m = ball.mass, volume = m / grain_density;
  // Velocity Verlet sees the drag at the half-step velocity: an error of order c dt / m.
  s.time_step = 1e-4 * m / c;
  Engine engine(MPI_COMM_SELF, s, std::vector<Grain>{ball});
  const double terminal = (m - fluid.density * volume) * g / c;
  const double relaxation = m / c;
  for (const double t : {0.5 * relaxation, 2.0 * relaxation, 10.0 * relaxation}) {
    engine.run(static_cast<std::int64_t>(std::llround((t - engine.time()) / engine.time_step())));
    const double expected = terminal * (1.0 - std::exp(-engine.time() / relaxation));
    EXPECT_NEAR(-engine.grains().velocity[0].z / expected, 1.0, 1e-4) << "t / (m/c) = " << engine.time() / relaxation;
  }
}

INSTANTIATE_TEST_SUITE_P(Drag, TerminalVelocity, ::testing::Values(DragLaw::stokes, DragLaw::richardson_zaki),
                         [](const ::testing::TestParamInfo<DragLaw>& p) { return std::string(drag_law_name(p.param)); });

/// A pre-compressed Hooke column of 30 grains, one end driven, in a fluid or dry; its final state.
std::vector<Vec3> driven_column_positions(const std::optional<FluidSpec>& fluid) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1e3;
  s.contact["gamma"] = 1.0;
  s.skin = 0.05;
  s.fluid = fluid;
  std::vector<Grain> grains;
  for (int n = 0; n < 30; ++n) {
    // Slightly off axis, so that the contacts are not all parallel.
    Grain g = testing::make_grain(n, {0.01 * std::sin(n), 0.01 * std::cos(n), n * 0.99});
    if (n == 0) g.body = 1;
    if (n == 29) g.body = 2;
    grains.push_back(g);
  }
  Engine engine(MPI_COMM_SELF, s, grains, {RigidBody("driver", Wiggle{2, 1e-3, 1.0}), RigidBody("anchor", Frozen{})});
  engine.run(1000);
  std::vector<Vec3> x(30);
  for (std::size_t i = 0; i < engine.grains().n_local(); ++i) x[static_cast<std::size_t>(engine.grains().id[i])] = engine.grains().position[i];
  return x;
}

// A fluid whose forces vanish leaves a run as it is dry. Not bit for bit: on CPUs with fused
// multiply-adds the compiler contracts the lubricated force loop's sums differently from the dry
// one's (force_loop.hpp), so the two agree to round-off, which the buckling column below amplifies
// only slowly. A run without a fluid executes the dry loop itself, in which no fluid code exists.
TEST(DryLimit, VanishingViscosityConvergesToTheDryRun) {
  FluidSpec fluid = squeeze_film(1e-300, 1e-3, 0.2);
  fluid.drag = DragLaw::stokes;
  const std::vector<Vec3> dry = driven_column_positions(std::nullopt);
  const std::vector<Vec3> wet = driven_column_positions(fluid);
  double worst = 0.0;
  for (std::size_t n = 0; n < dry.size(); ++n) worst = std::max(worst, norm(wet[n] - dry[n]));
  EXPECT_LT(worst, 1e-14);
  // And a real fluid does change the run (the comparison above can fail).
  const std::vector<Vec3> viscous = driven_column_positions(squeeze_film(0.05, 1e-3, 0.2));
  double moved = 0.0;
  for (std::size_t n = 0; n < dry.size(); ++n) moved = std::max(moved, norm(viscous[n] - dry[n]));
  EXPECT_GT(moved, 1e-8);
}

// A fluid whose terms are all switched off (no film, no drag, no density) runs bit for bit as dry:
// its presence changes neither the time step, nor the lists, the ghosts or the order of the sums.
TEST(DryLimit, AFluidWithoutForcesIsTheDryRunBitForBit) {
  FluidSpec inert = squeeze_film(1.0, 1e-3, 0.2);
  inert.lubrication = false;
  inert.drag = DragLaw::none;
  const std::vector<Vec3> dry = driven_column_positions(std::nullopt);
  const std::vector<Vec3> wet = driven_column_positions(inert);
  for (std::size_t n = 0; n < dry.size(); ++n) {
    EXPECT_EQ(dry[n].x, wet[n].x) << n;
    EXPECT_EQ(dry[n].y, wet[n].y) << n;
    EXPECT_EQ(dry[n].z, wet[n].z) << n;
  }
}

TEST(FluidSpec, RefusesWhatItCannotModelNamingTheField) {
  const auto problem = [](auto change) {
    FluidSpec f = squeeze_film(1.0, 1e-3, 0.1);
    change(f);
    return f.problem();
  };
  EXPECT_EQ(problem([](FluidSpec&) {}), "");
  EXPECT_NE(problem([](FluidSpec& f) { f.viscosity = 0.0; }).find("viscosity = 0: accepted range (0, inf)"), std::string::npos);
  EXPECT_NE(problem([](FluidSpec& f) { f.viscosity = -1.0; }).find("viscosity"), std::string::npos);
  EXPECT_NE(problem([](FluidSpec& f) { f.cutoff = 1e-4; }).find("cutoff = 0.0001: accepted range (roughness, inf)"),
            std::string::npos);
  EXPECT_NE(problem([](FluidSpec& f) { f.roughness = 0.0; }).find("roughness"), std::string::npos);
  EXPECT_NE(problem([](FluidSpec& f) {
              f.drag = DragLaw::richardson_zaki;
              f.porosity = 1.0;
            }).find("porosity = 1: accepted range (0, 1)"),
            std::string::npos);

  EngineSettings s;
  s.contact["kn"] = 1.0;
  s.box.periodic = {false, false, false};
  s.fluid = squeeze_film(-1.0, 1e-3, 0.1);
  EXPECT_THROW(Engine(MPI_COMM_SELF, s, std::vector<Grain>{testing::make_grain(0, {0, 0, 0})}), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::forward::dem
