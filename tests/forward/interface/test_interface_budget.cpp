// What `sedwave interface` knows before a run (experiment/interface_run.hpp): the mesh's limit, the
// strike's peak overlap against a simulated strike, and what it does while running: progress with
// the time left, and a stop when the energy balance blows up.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sedwave/forward/experiment/interface_run.hpp"
#include "sedwave/forward/experiment/interface_scene.hpp"

namespace {

using namespace sedwave::forward;
using experiment::parse_interface_scene;

constexpr const char* kPlate = R"(
[plate]
length_x = 0.024
length_y = 0.008
elements_x = 8
elements_y = 4
)";

TEST(InterfaceEstimate, PlateLimitIsTheWholeMeshsBound) {
  const auto scene =
      parse_interface_scene(std::string(kPlate) + "[packing]\nrows = 1\ncolumns = 1\n[run]\nduration = 4e-5\n", "scene.toml");
  const plate::ElasticPlate whole(scene.plate_material, scene.mesh, scene.edges);
  EXPECT_DOUBLE_EQ(experiment::estimate_interface_run(scene).plate_limit, whole.stable_time_step());
}

// One bead dropped at 1 m/s on a thick steel plate: the contact radius the run measures at its
// deepest against the estimate's sqrt(r delta_max), Johnson's rigid-wall overlap
// delta_max = (15 m* v^2 / (16 E* sqrt(r)))^(2/5) with the edge node's inertia in m*. The edge node,
// pushed into the plate, springs back into the bead while it is still in contact: the simulated
// radius is 5 % above the estimate here.
TEST(InterfaceEstimate, PeakContactRadiusMatchesASimulatedStrike) {
  const auto scene = parse_interface_scene(
      "[plate]\nlength_x = 0.024\nlength_y = 0.024\nelements_x = 8\nelements_y = 8\nyoungs_modulus = 200e9\n"
      "density = 7850\nthickness = 0.05\n[packing]\nrows = 1\ncolumns = 1\nlift = 1e-6\n"
      "[run]\nduration = 2e-5\nsnapshots = 0\n",
      "scene.toml");
  const auto e = experiment::estimate_interface_run(scene);
  const auto run = experiment::run_interface(scene, nullptr);
  EXPECT_GT(run.max_contact_radius, 0.0);
  EXPECT_NEAR(run.max_contact_radius / e.contact_radius, 1.0, 0.1);
}

TEST(InterfaceRun, ProgressLinesSayHowMuchIsLeft) {
  const auto scene = parse_interface_scene(std::string(kPlate) + "[packing]\nrows = 2\ncolumns = 3\n[run]\nduration = 4e-5\n",
                                           "scene.toml");
  std::ostringstream progress;
  (void)experiment::run_interface(scene, &progress, 0.0);  // a line at every check
  EXPECT_NE(progress.str().find("% of the run), 256 steps, plate holds "), std::string::npos) << progress.str();
  EXPECT_NE(progress.str().find(" s left"), std::string::npos);
}

// A fixed step within the mesh's limit (1.43e-6 s on 2 x 1 elements) but three times the Hertz limit
// of 0.2 mm beads at 1 m/s: stopped, naming the fixed step.
TEST(InterfaceRun, AnUnstableRunIsStoppedWithItsCause) {
  const auto scene = parse_interface_scene(
      "[plate]\nlength_x = 0.024\nlength_y = 0.008\nelements_x = 2\nelements_y = 1\n[packing]\nrows = 2\ncolumns = 3\n"
      "radius = 1e-4\n[run]\nduration = 4e-5\nfixed_step = 1e-6\noutput_interval = 4e-6\n",
      "scene.toml");
  const auto e = experiment::estimate_interface_run(scene);
  ASSERT_LT(scene.recording.fixed_step, e.plate_limit);
  ASSERT_GT(scene.recording.fixed_step, 2.0 * e.hertz_limit);
  try {
    (void)experiment::run_interface(scene, nullptr);
    FAIL() << "ran to its end";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("energy balance is off by"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("the fixed step (run.fixed_step, --fixed-step) exceeds"), std::string::npos);
  }
}

}  // namespace
