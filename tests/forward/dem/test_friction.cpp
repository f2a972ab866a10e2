// Friction against closed forms: sliding decelerates at mu g; rolling down an incline below the
// friction angle accelerates at (5/7) g sin(theta). The wall is one huge frozen grain (R = 1e4),
// flat to 5e-5 over the distances travelled.
#include <cmath>
#include <numbers>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr double kWallRadius = 1e4;
constexpr double kStiffness = 1e4;

/// A sphere resting (at its equilibrium overlap) on the top of a huge frozen wall grain.
Engine sphere_on_wall(const ContactSpec& contact, const Vec3& gravity, const Vec3& velocity) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact = contact;
  s.gravity = gravity;
  s.skin = 0.1;
  Grain wall = testing::make_grain(0, {0, 0, -kWallRadius}, kWallRadius);
  wall.body = 1;
  Grain ball = testing::make_grain(1, {0, 0, 0}, 0.5);
  ball.position.z = 0.5 + ball.mass * gravity.z / kStiffness;  // equilibrium overlap
  ball.velocity = velocity;
  return Engine(MPI_COMM_SELF, s, std::vector<Grain>{wall, ball}, {RigidBody("wall", Frozen{})});
}

ContactSpec frictional(const std::string& law, double mu) {
  ContactSpec c;
  c["kn"] = kStiffness;
  c["restitution"] = 0.3;
  c.tangential = law;
  c["friction"] = mu;
  if (law == "coulomb_tanh") {
    c["tanh_velocity_scale"] = 1e3;  // full sliding for |v_t| >> 1e-3
  } else {
    c["kt"] = 2.0 / 7.0 * kStiffness;
    c["gamma_t"] = 0.0;
  }
  return c;
}

class Sliding : public ::testing::TestWithParam<std::string> {};

TEST_P(Sliding, DeceleratesAtMuG) {
  constexpr double mu = 0.3, g = 1.0, v0 = 1.0;
  Engine engine = sphere_on_wall(frictional(GetParam(), mu), {0, 0, -g}, {v0, 0, 0});
  // Slipping lasts until v = (5/7) v0, at t = v0 / (3.5 mu g) = 0.95: measure inside.
  engine.run(static_cast<std::int64_t>(0.1 / engine.time_step()));
  const double t0 = engine.time();
  const double v_start = engine.grains().velocity[testing::local_index(engine.grains(), 1)].x;
  engine.run(static_cast<std::int64_t>(0.6 / engine.time_step()));
  const double v_end = engine.grains().velocity[testing::local_index(engine.grains(), 1)].x;
  const double deceleration = -(v_end - v_start) / (engine.time() - t0);
  EXPECT_NEAR(deceleration / (mu * g), 1.0, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Laws, Sliding,
                         ::testing::Values("spring_history", "coulomb_tanh"));

TEST(Rolling, InclineBelowFrictionAngleRollsWithoutSlipping) {
  const double theta = 15.0 * std::numbers::pi / 180.0, g = 1.0, mu = 0.5;
  ASSERT_LT(2.0 / 7.0 * std::tan(theta), mu);  // below the friction angle for rolling
  Engine engine = sphere_on_wall(frictional("spring_history", mu),
                                 {g * std::sin(theta), 0, -g * std::cos(theta)}, {});
  std::vector<double> t, x;
  engine.add_step_callback(10, [&](const Engine& e) {
    t.push_back(e.time());
    x.push_back(e.grains().position[testing::local_index(e.grains(), 1)].x);
  });
  engine.run(static_cast<std::int64_t>(2.0 / engine.time_step()));
  // Least-squares fit x = c0 + c1 t + c2 t^2 (normal equations; well conditioned at this size).
  double s[5] = {0, 0, 0, 0, 0}, r[3] = {0, 0, 0};
  for (std::size_t k = 0; k < t.size(); ++k) {
    double p = 1.0;
    for (int j = 0; j < 5; ++j, p *= t[k]) s[j] += p;
    r[0] += x[k];
    r[1] += x[k] * t[k];
    r[2] += x[k] * t[k] * t[k];
  }
  const double a11 = s[0], a12 = s[1], a13 = s[2], a22 = s[2], a23 = s[3], a33 = s[4];
  const double det = a11 * (a22 * a33 - a23 * a23) - a12 * (a12 * a33 - a23 * a13) + a13 * (a12 * a23 - a22 * a13);
  const double c2 = (a11 * (a22 * r[2] - a23 * r[1]) - a12 * (a12 * r[2] - a23 * r[0]) + r[0] * 0 +
                     a13 * (a12 * r[1] - a22 * r[0])) / det;
  EXPECT_NEAR(2.0 * c2 / (5.0 / 7.0 * g * std::sin(theta)), 1.0, 0.01);
  // Rolling without slipping: v = omega r.
  const GrainArrays& gr = engine.grains();
  const std::size_t i = testing::local_index(gr, 1);
  EXPECT_NEAR(gr.velocity[i].x, gr.angular_velocity[i].y * 0.5, 1e-3 * gr.velocity[i].x);
}

}  // namespace
}  // namespace sedwave::forward::dem
