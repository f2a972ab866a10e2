// Conservation laws: energy without damping in a dense packing; linear and angular momentum.
#include <cmath>
#include <numeric>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

/// Parameter: newton on (every pair across the periodic faces computed once, reactions sent back).
class Conservation : public ::testing::TestWithParam<bool> {};

TEST_P(Conservation, EnergyDriftBelow1e6OverHundredThousandStepsInDensePacking) {
  EngineSettings s;
  s.newton = GetParam();
  s.contact["kn"] = 1000.0;  // no damping
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

// Two grains touching only through the periodic corner (x and y faces at once): the list refers to
// the partner grain itself with the box shift (no image copy), and the forces are kn * overlap
// along the line to the image, equal and opposite, with newton on and off.
TEST(PeriodicImages, ContactThroughTheCornerIsListedAsTheShiftedSourceGrain) {
  for (const bool newton : {false, true}) {
    EngineSettings s;
    s.newton = newton;
    s.contact["kn"] = 1000.0;
    s.box.lo = {0.0, 0.0, 0.0};
    s.box.hi = {3.0, 3.0, 10.0};
    s.box.periodic = {true, true, false};
    const std::vector<Grain> grains{testing::make_grain(1, {0.1, 0.1, 5.0}), testing::make_grain(2, {2.6, 2.6, 5.0})};
    Engine engine(MPI_COMM_SELF, s, grains);
    engine.compute_forces();
    const GrainArrays& g = engine.grains();
    const NeighborList& list = engine.neighbor_list();
    const std::size_t a = testing::local_index(g, 1), b = testing::local_index(g, 2);
    ASSERT_EQ(list.n_pairs(), newton ? 1U : 2U);
    for (std::size_t i = 0; i < list.n_rows(); ++i) {
      for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k) {
        const auto j = static_cast<std::size_t>(list.partners()[k]);
        EXPECT_EQ(j, i == a ? b : a) << "a local grain, not an image copy";
        const Vec3 expected_shift = i == a ? Vec3{-3.0, -3.0, 0.0} : Vec3{3.0, 3.0, 0.0};
        EXPECT_EQ(list.shift(k), expected_shift);
      }
    }
    const Vec3 d = Vec3{0.1, 0.1, 5.0} - Vec3{2.6 - 3.0, 2.6 - 3.0, 5.0};
    const double overlap = 1.0 - norm(d);
    const Vec3 expected = (1000.0 * overlap / norm(d)) * d;
    EXPECT_LT(norm(g.force[a] - expected), 1e-12 * norm(expected)) << "newton " << newton;
    EXPECT_LT(norm(g.force[b] + expected), 1e-12 * norm(expected)) << "newton " << newton;
  }
}

TEST(Momentum, LinearAndAngularMomentumOfAFrictionalRollingCluster) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.5;
  s.contact.tangential = "spring_history";
  s.contact["kt"] = 800.0;
  s.contact["gamma_t"] = 5.0;
  s.contact["friction"] = 0.4;
  s.contact.rolling = "constant_torque";
  s.contact["rolling_friction"] = 0.1;
  s.contact["rolling_regularisation"] = 0.1;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Grain> grains;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        // The draws in a fixed order (a function's arguments have none): radius, then x and y.
        const double radius = 0.5 + 0.05 * u(rng);
        const Vec3 position{1.02 * i + 0.05 * u(rng), 1.02 * j + 0.05 * u(rng), 1.02 * k};
        Grain g = testing::make_grain(static_cast<std::int64_t>(grains.size()), position, radius);
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
