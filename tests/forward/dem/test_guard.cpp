// The guard stops a run that blows up, with a message that says where and why.
#include <cmath>
#include <string>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

TEST(Guard, FiresOnATimeStepAboveTheCollectiveStabilityLimit) {
  // The pair limit is accepted, but an FCC packing has modes twice as stiff as one pair.
  EngineSettings s;
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.9;
  s.guard.check_interval = 10;
  std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.01, 11, s.box);
  {
    Engine probe(MPI_COMM_SELF, s, grains);
    s.time_step = 0.95 * probe.time_step_limits().stable_step;
  }
  Engine engine(MPI_COMM_SELF, s, grains);
  try {
    engine.run(20000);
    FAIL() << "the guard did not fire";
  } catch (const GuardError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("at step"), std::string::npos) << message;
    EXPECT_NE(message.find("stable time step"), std::string::npos) << message;
    EXPECT_NE(message.find("time step"), std::string::npos) << message;
  }
}

// Strongly overdamped contacts (pair damping ratio 20): the dashpots alone set the stability limit.
// An FCC packing's densest mode damps 4x faster than one pair, so half the pair's limit (the old
// default) lets it grow, while the default step keeps the run stable and dissipative: with dashpots
// only, kinetic plus elastic energy can only fall.
TEST(Guard, DefaultStepKeepsAnOverdampedPackingStable) {
  EngineSettings s;
  s.contact["kn"] = 1000.0;
  const double m_eff = 0.5 * testing::sphere_mass(1.0, 0.5);
  s.contact["gamma"] = 2.0 * 20.0 * std::sqrt(s.contact["kn"] * m_eff);
  s.guard.check_interval = 10;
  const std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.1, 11, s.box);
  Engine engine(MPI_COMM_SELF, s, grains);
  const TimeStepLimits limits = engine.time_step_limits();
  EXPECT_NEAR(engine.time_step(), 0.25 * limits.stable_step, 0.02 * limits.stable_step);
  const double start = engine.kinetic_energy() + engine.elastic_energy();
  EXPECT_NO_THROW(engine.run(5000));
  EXPECT_LT(engine.kinetic_energy() + engine.elastic_energy(), start);

  s.time_step = 0.5 * limits.stable_step;
  Engine pair_limited(MPI_COMM_SELF, s, grains);
  bool grew = false;
  try {
    pair_limited.run(5000);
    grew = pair_limited.kinetic_energy() + pair_limited.elastic_energy() > start;
  } catch (const GuardError&) {
    grew = true;
  }
  EXPECT_TRUE(grew) << "half the pair limit was stable here too: the test no longer shows why the default is lower";
}

TEST(Guard, QuietOnAHealthyRun) {
  EngineSettings s;
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.9;
  s.guard.check_interval = 10;
  std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.1, 11, s.box);
  Engine engine(MPI_COMM_SELF, s, grains);
  EXPECT_NO_THROW(engine.run(2000));
}

}  // namespace
}  // namespace sedwave::forward::dem
