// What `sedwave interface` knows before a run (experiment/interface_run.hpp): the mesh's limit, the
// strike's peak overlap against a simulated strike, and what it does while running: progress with
// the time left, and a stop when the energy balance blows up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

// The direct strike's arrival (`--direct`) on three meshes against the dilatational front's
// depth / c_L, c_L^2 = E / (rho (1 - nu^2)) in plane stress: the front (the speed reaching 0.663 of its
// first maximum) converges to it, the speed reaching 10 % of its maximum stays in the mesh's precursor.
TEST(InterfaceRun, DirectStrikesFrontConvergesToTheDilatationalFront) {
  const double depth = 0.02;
  std::vector<double> front_error, precursor_error;
  for (const int n : {10, 20, 40}) {  // elements over the depth: h = 2, 1, 0.5 mm
    auto scene = parse_interface_scene(
        "[plate]\nlength_x = 0.04\nlength_y = 0.02\nelements_x = " + std::to_string(2 * n) + "\nelements_y = " +
            std::to_string(n) + "\n[plate.edges]\nbottom = \"absorbing\"\n[packing]\nrows = 1\ncolumns = 4\n"
            "[run]\nduration = 6e-6\noutput_interval = 5e-9\nsnapshots = 0\nprobe_x = [0.02]\nprobe_depth = 0.02\n",
        "scene.toml");
    scene.drive.direct = true;
    const auto run = experiment::run_interface(scene, nullptr);
    const auto& m = scene.plate_material;
    const double transit = depth / std::sqrt(m.youngs_modulus / (m.density * (1.0 - m.poisson_ratio * m.poisson_ratio)));
    front_error.push_back(run.arrival[0] / transit - 1.0);
    const auto& v = run.probe_velocity[0];
    const double tenth = 0.1 * *std::max_element(v.begin(), v.end());
    std::size_t k = 0;
    while (v[k] < tenth) ++k;
    precursor_error.push_back(run.series.time[k] / transit - 1.0);
    if (std::getenv("SEDWAVE_VERBOSE"))
      std::printf("h %.2g mm: front %+.4f, 10 %% of the peak %+.4f of depth/c_L\n", 20.0 / n, front_error.back(),
                  precursor_error.back());
  }
  for (std::size_t i = 1; i < front_error.size(); ++i) {
    EXPECT_LT(std::abs(front_error[i]), 0.7 * std::abs(front_error[i - 1])) << "converges";
    EXPECT_LT(precursor_error[i], 0.0) << "precursor ahead of the front";
  }
  EXPECT_LT(std::abs(front_error.back()), 0.01);
  EXPECT_GT(std::abs(precursor_error.back()), 3.0 * std::abs(front_error.back()));
}

}  // namespace
