// Binary head-on collisions against closed forms, the Hertz e_n mapping, and time-step stability.
#include <cmath>
#include <string>

#include "dem_test_support.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::dem {
namespace {

using testing::make_grain;


struct CollisionResult {
  double restitution;
  double contact_time;
};

/// Two grains touching at t = 0 approach at relative speed `speed` along z; runs until they have
/// separated and returns the measured restitution and contact duration (interpolated crossing).
CollisionResult collide(const ContactSpec& contact, double speed, double dt) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact = contact;
  s.time_step = dt;
  std::vector<Grain> grains{make_grain(0, {0, 0, 0}), make_grain(1, {0, 0, 1.0})};
  grains[0].velocity.z = 0.5 * speed;
  grains[1].velocity.z = -0.5 * speed;
  Engine engine(MPI_COMM_SELF, s, grains);
  double previous_gap = 0.0;
  for (int step = 0; step < 10'000'000; ++step) {
    engine.run(1);
    const GrainArrays& g = engine.grains();
    const std::size_t a = testing::local_index(g, 0), b = testing::local_index(g, 1);
    const double gap = g.position[b].z - g.position[a].z - 1.0;
    if (gap > 0.0 && step > 0) {
      const double crossing = engine.time() - dt * gap / (gap - previous_gap);
      // After separation the velocities are constant: the rebound speed is exact.
      return {(g.velocity[b].z - g.velocity[a].z) / speed, crossing};
    }
    previous_gap = gap;
  }
  throw std::runtime_error("no separation");
}

class HookeCollision : public ::testing::TestWithParam<double> {};

TEST_P(HookeCollision, RestitutionAndContactTimeMatchClosedForm) {
  const double e_n = GetParam();
  ContactSpec c;
  c["kn"] = 1000.0;
  c["restitution"] = e_n;
  const double m_eff = 0.5 * testing::sphere_mass(1.0, 0.5);
  const double gamma = gamma_from_restitution(e_n, c["kn"], m_eff);
  const double t_col = hooke_collision_time(c["kn"], m_eff, gamma);
  const CollisionResult r = collide(c, 1.0, t_col / 2000.0);
  EXPECT_NEAR(r.restitution, e_n, 1e-3);
  EXPECT_NEAR(r.contact_time / t_col, 1.0, 1e-3);
}

class HertzCollision : public ::testing::TestWithParam<double> {};

TEST_P(HertzCollision, RestitutionMatchesTarget) {
  const double e_n = GetParam();
  ContactSpec c;
  c.normal = "hertz";
  c["effective_modulus"] = hertz_effective_modulus(1e4, 0.3, 1e4, 0.3);
  c["restitution"] = e_n;
  const double m_eff = 0.5 * testing::sphere_mass(1.0, 0.5);
  const double t_col = hertz_collision_time(c["effective_modulus"], 0.25, m_eff, 1.0);
  // The restitution of Hertz-Tsuji damping is independent of the impact speed: try two.
  for (const double speed : {1.0, 0.1}) {
    const CollisionResult r = collide(c, speed, t_col / 4000.0);
    EXPECT_NEAR(r.restitution, e_n, 1e-3) << "impact speed " << speed;
  }
  // Undamped collision time closed form (Hertz 1882) at the same dt.
  if (e_n == 0.99) {
    ContactSpec elastic = c;
    elastic.erase("restitution");
    const CollisionResult r = collide(elastic, 1.0, t_col / 4000.0);
    EXPECT_NEAR(r.contact_time / t_col, 1.0, 2e-3);
    EXPECT_NEAR(r.restitution, 1.0, 1e-5);
  }
}

INSTANTIATE_TEST_SUITE_P(Restitution, HookeCollision, ::testing::Values(0.05, 0.3, 0.7, 0.9, 0.99));
INSTANTIATE_TEST_SUITE_P(Restitution, HertzCollision, ::testing::Values(0.05, 0.3, 0.7, 0.9, 0.99));

TEST(HertzRestitutionMap, InverseAndLimits) {
  EXPECT_DOUBLE_EQ(hertz_restitution(0.0), 1.0);
  for (const double e : {0.05, 0.3, 0.7, 0.9, 0.99})
    EXPECT_NEAR(hertz_restitution(hertz_alpha_from_restitution(e)), e, 1e-8);
  // Monotone decreasing.
  EXPECT_GT(hertz_restitution(0.1), hertz_restitution(0.2));
}

// ---- time step ---------------------------------------------------------------------------------

/// Largest |x| reached by velocity Verlet (force with half-step velocity, as the engine) on a
/// damped oscillator over many steps, relative to the start.
double verlet_growth(double omega0, double beta, double h) {
  double x = 1.0, w = 0.0;  // w: the velocity seen by the force
  double a = -omega0 * omega0 * x - beta * w;
  double v = 0.0;
  double largest = 0.0;
  for (int n = 0; n < 20000; ++n) {
    w = v + 0.5 * h * a;
    x += h * w;
    a = -omega0 * omega0 * x - beta * w;
    v = w + 0.5 * h * a;
    largest = std::max(largest, std::abs(x));
  }
  return largest;
}

TEST(TimeStep, DashpotStabilityLimitIsSharp) {
  for (const double zeta : {0.0, 0.1, 0.5, 0.69, 1.0, 3.0}) {
    const double omega0 = 2.0;
    const double beta = 2.0 * zeta * omega0;
    const double h_c = verlet_critical_step(omega0, beta);
    EXPECT_NEAR(h_c, 2.0 / omega0 * (std::sqrt(1.0 + zeta * zeta) - zeta), 1e-12);
    EXPECT_LT(verlet_growth(omega0, beta, 0.99 * h_c), 10.0) << "zeta " << zeta;
    EXPECT_GT(verlet_growth(omega0, beta, 1.01 * h_c), 1e6) << "zeta " << zeta;
  }
  // Damping shrinks the limit: e_n -> 0 is the hard case.
  EXPECT_LT(verlet_critical_step(1.0, 2.0), verlet_critical_step(1.0, 0.0));
}

TEST(TimeStep, DefaultIsOnePercentOfCollisionTime) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.9;
  std::vector<Grain> grains{make_grain(0, {0, 0, 0}), make_grain(1, {0, 0, 2.0})};
  const Engine engine(MPI_COMM_SELF, s, grains);
  const double m_eff = 0.5 * testing::sphere_mass(1.0, 0.5);
  const double t_col = hooke_collision_time(1000.0, m_eff, gamma_from_restitution(0.9, 1000.0, m_eff));
  EXPECT_NEAR(engine.time_step(), 0.01 * t_col, 1e-12 * t_col);
  EXPECT_NEAR(engine.time_step_limits().collision_time, t_col, 1e-12 * t_col);
}

TEST(TimeStep, RefusesUnstableUserStepWithTheLimitInTheMessage) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.05;
  std::vector<Grain> grains{make_grain(0, {0, 0, 0}), make_grain(1, {0, 0, 2.0})};
  s.time_step = 1.0;
  try {
    const Engine engine(MPI_COMM_SELF, s, grains);
    FAIL() << "an unstable time step was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stability limit"), std::string::npos) << e.what();
  }
  s.time_step = 0.001;
  EXPECT_NO_THROW(Engine(MPI_COMM_SELF, s, grains));
}

}  // namespace
}  // namespace sedwave::forward::dem
