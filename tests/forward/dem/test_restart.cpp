// Checkpoint/restart: a run interrupted after its checkpoint and restored into a fresh engine ends
// bit-identically to one never interrupted (one rank), contact history included.
#include <cstdio>
#include <filesystem>
#include <map>

#include "dem_test_support.hpp"

namespace sedwave::forward::dem {
namespace {

struct Scene {
  EngineSettings settings;
  std::vector<Grain> grains;
  std::vector<RigidBody> bodies;
};

Scene frictional_packing(const std::string& checkpoint, bool newton = false) {
  Scene s;
  s.settings.newton = newton;
  s.settings.contact["kn"] = 1000.0;
  s.settings.contact["restitution"] = 0.7;
  s.settings.contact.tangential = "spring_history";
  s.settings.contact["kt"] = 2.0 / 7.0 * 1000.0;
  s.settings.contact["friction"] = 0.5;
  s.settings.gravity = {0, 0, -1};
  s.grains = testing::compressed_fcc(3, 0.005, 0.3, 5, s.settings.box);
  s.settings.box.periodic[2] = false;  // a column standing on a wiggling floor
  for (Grain& g : s.grains)
    if (g.position.z < 0.5) g.body = 1;
  s.bodies.emplace_back("floor", Wiggle{2, 1e-3, 0.37});
  s.settings.checkpoint = {checkpoint, 150};
  return s;
}

std::map<std::int64_t, Grain> by_id(const Engine& e) {
  std::map<std::int64_t, Grain> out;
  for (std::size_t i = 0; i < e.grains().n_local(); ++i) out[e.grains().id[i]] = e.grains().grain(i);
  return out;
}

/// Parameter: newton on (pairs across the periodic faces computed once, reactions sent back).
class Restart : public ::testing::TestWithParam<bool> {};

TEST_P(Restart, InterruptedRunEndsBitIdentical) {
  const bool newton = GetParam();
  // Distinct names per parameter: ctest may run the two cases at once.
  const std::string suffix = newton ? "_newton.h5" : ".h5";
  const std::string straight_file = testing::temp_path("dem_straight" + suffix);
  const std::string killed_file = testing::temp_path("dem_killed" + suffix);

  Scene a = frictional_packing(straight_file, newton);
  Engine straight(MPI_COMM_SELF, a.settings, a.grains, a.bodies);
  straight.run(400);

  Scene b = frictional_packing(killed_file, newton);
  {
    Engine killed(MPI_COMM_SELF, b.settings, b.grains, b.bodies);
    killed.run(230);  // checkpoint at 150; the 80 steps after it are lost, as under SIGKILL
  }
  Engine restored(MPI_COMM_SELF, b.settings, b.grains, b.bodies);
  restored.restore_checkpoint(killed_file);
  EXPECT_EQ(restored.step_count(), 150);
  restored.run(250);

  ASSERT_EQ(restored.step_count(), straight.step_count());
  EXPECT_EQ(restored.time(), straight.time());
  ASSERT_FALSE(straight.contact_history().empty());
  const auto x = by_id(straight), y = by_id(restored);
  ASSERT_EQ(x.size(), y.size());
  for (const auto& [id, g] : x) {
    const Grain& h = y.at(id);
    ASSERT_EQ(g.position, h.position) << "grain " << id;
    ASSERT_EQ(g.velocity, h.velocity) << "grain " << id;
    ASSERT_EQ(g.angular_velocity, h.angular_velocity) << "grain " << id;
    ASSERT_EQ(g.force, h.force) << "grain " << id;
  }
  EXPECT_EQ(straight.bodies()[0].contact_force(), restored.bodies()[0].contact_force());
  std::remove(straight_file.c_str());
  std::remove(killed_file.c_str());
}

INSTANTIATE_TEST_SUITE_P(Newton, Restart, ::testing::Bool());

TEST(RestartFile, CheckpointIsReplacedAtomically) {
  const std::string file = testing::temp_path("dem_atomic.h5");
  Scene s = frictional_packing(file);
  Engine engine(MPI_COMM_SELF, s.settings, s.grains, s.bodies);
  engine.run(300);
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_FALSE(std::filesystem::exists(file + ".tmp"));
  Engine other(MPI_COMM_SELF, s.settings, s.grains, s.bodies);
  other.restore_checkpoint(file);
  EXPECT_EQ(other.step_count(), 300);
  std::remove(file.c_str());
}

}  // namespace
}  // namespace sedwave::forward::dem
