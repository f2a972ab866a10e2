// The guard stops a run that blows up, with a message that says where and why.
#include <string>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

const auto* const kMpi = ::testing::AddGlobalTestEnvironment(new testing::MpiEnvironment);

TEST(Guard, FiresOnATimeStepAboveTheCollectiveStabilityLimit) {
  // The pair limit is accepted, but an FCC packing has modes twice as stiff as one pair.
  EngineSettings s;
  s.contact.kn = 1000.0;
  s.contact.restitution = 0.9;
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

TEST(Guard, QuietOnAHealthyRun) {
  EngineSettings s;
  s.contact.kn = 1000.0;
  s.contact.restitution = 0.9;
  s.guard.check_interval = 10;
  std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.1, 11, s.box);
  Engine engine(MPI_COMM_SELF, s, grains);
  EXPECT_NO_THROW(engine.run(2000));
}

}  // namespace
}  // namespace sedwave::forward::dem
