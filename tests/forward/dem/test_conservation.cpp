// Conservation laws: energy without damping in a dense packing; linear and angular momentum.
#include <cmath>
#include <numeric>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

const auto* const kMpi = ::testing::AddGlobalTestEnvironment(new testing::MpiEnvironment);

/// Parameter: newton on (every pair across the periodic faces computed once, reactions sent back).
class Conservation : public ::testing::TestWithParam<bool> {};

TEST_P(Conservation, EnergyDriftBelow1e6OverHundredThousandStepsInDensePacking) {
  EngineSettings s;
  s.newton = GetParam();
  s.contact.kn = 1000.0;  // no damping
  std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.1, 7, s.box);
  Engine engine(MPI_COMM_SELF, s, grains);
  // Verlet's energy oscillates (it conserves a nearby shadow energy); the drift is the change of
  // its average, measured over the first and the last tenth of the run.
  constexpr int steps = 100'000, every = 10, window = steps / every / 10;
  std::vector<double> energy;
  engine.add_step_callback(every, [&](const Engine& e) { energy.push_back(e.kinetic_energy() + e.elastic_energy()); });
  const Vec3 p0 = engine.linear_momentum();
  engine.run(steps);
  const double first = std::accumulate(energy.begin(), energy.begin() + window, 0.0) / window;
  const double last = std::accumulate(energy.end() - window, energy.end(), 0.0) / window;
  EXPECT_LT(std::abs(last - first) / first, 1e-6) << "first " << first << " last " << last;
  const Vec3 p1 = engine.linear_momentum();
  const double scale = 0.1 * testing::sphere_mass(1.0, 0.5) * static_cast<double>(grains.size());
  EXPECT_LT(norm(p1 - p0) / scale, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Newton, Conservation, ::testing::Bool());

TEST(Momentum, LinearAndAngularMomentumOfAFrictionalRollingCluster) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact.kn = 1000.0;
  s.contact.restitution = 0.5;
  s.contact.tangential = TangentialLawKind::spring_history;
  s.contact.kt = 800.0;
  s.contact.gamma_t = 5.0;
  s.contact.friction = 0.4;
  s.contact.rolling = RollingLawKind::constant_torque;
  s.contact.rolling_friction = 0.1;
  s.contact.rolling_regularisation = 0.1;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Grain> grains;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        Grain g = testing::make_grain(static_cast<std::int64_t>(grains.size()),
                                      {1.02 * i + 0.05 * u(rng), 1.02 * j + 0.05 * u(rng), 1.02 * k},
                                      0.5 + 0.05 * u(rng));
        g.velocity = {u(rng), u(rng), u(rng)};
        g.angular_velocity = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
        grains.push_back(g);
      }
  Engine engine(MPI_COMM_SELF, s, grains);
  const Vec3 p0 = engine.linear_momentum(), l0 = engine.angular_momentum();
  const double e0 = engine.kinetic_energy();
  engine.run(5000);
  EXPECT_LT(norm(engine.linear_momentum() - p0), 1e-12 * 64);
  EXPECT_LT(norm(engine.angular_momentum() - l0), 1e-11 * 64);
  EXPECT_LT(engine.kinetic_energy(), 0.9 * e0);  // friction and damping did work
}

}  // namespace
}  // namespace sedwave::forward::dem
