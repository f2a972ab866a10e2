// Newton relaxation to static equilibrium (linear/static_equilibrium.hpp) against a closed form and
// against the DEM engine's own forces:
//  - an ordered chain under a loaded wall: every contact carries exactly the load, so every overlap
//    is F / kn and the wall sits where the closed form puts it;
//  - a prepared 3D packing, shaken and relaxed again: the DEM engine finds no residual force beyond
//    the tolerance and the wall carries the load.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/linear/ordered_chain.hpp"
#include "sedwave/forward/linear/static_equilibrium.hpp"
#include "sedwave/forward/linear/newton_stage.hpp"

namespace sedwave::forward::linear {
namespace {

dem::ContactSpec frictionless(double kn) {
  dem::ContactSpec c;
  c["kn"] = kn;
  c["restitution"] = 0.9;
  return c;
}

TEST(StaticEquilibrium, OrderedChainUnderALoadTakesTheClosedFormOverlaps) {
  const int n = 30;
  const double kn = 50.0, load = 0.2;
  channel::PreparedChannel chain = ordered_chain(n, 1.0);  // just touching: no force yet
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-2e-3, 2e-3);
  for (dem::Grain& g : chain.grains) {
    if (g.body == dem::kFreeBody) g.position.z += jitter(rng);  // along the axis: the chain stays straight
  }
  const LoadedWall wall{channel::kUpperWallBody, load};
  StaticEquilibriumSettings tight;
  tight.residual_force_tolerance = 1e-11;
  tight.wall_force_tolerance = 1e-11;
  const StaticEquilibriumReport r = relax_to_equilibrium(chain.grains, chain.box, frictionless(kn), 2, &wall, tight);
  ASSERT_TRUE(r.converged) << r.iterations << " iterations, residual " << r.residual_ratio;
  // Grain i (lower wall 0, upper wall n + 1) sits at i (1 - F / kn): every contact carries F.
  const double spacing = 1.0 - load / kn;
  for (const dem::Grain& g : chain.grains) {
    EXPECT_NEAR(g.position.z, static_cast<double>(g.id - 1) * spacing, 1e-11) << "grain " << g.id;
  }
  EXPECT_NEAR(r.wall_force, load, tight.wall_force_tolerance * load);  // what was asked for
  EXPECT_GT(r.energy_drop, 0.0);
  EXPECT_LT(r.iterations, 10);  // a few Newton steps, not a slow descent
}

TEST(StaticEquilibrium, ShakenPackingRelaxesToWhatTheDemEngineCallsStatic) {
  channel::ChannelGeometry g;
  g.n_grains = 200;
  g.seed = 7;
  channel::PreparationSettings p;
  p.pressure = 10.0;
  p.residual_force_tolerance = 1e-4;  // FIRE only roughly; the Newton relaxation does the rest
  const dem::ContactSpec contact = frictionless(726.0);
  channel::PreparedChannel packing = channel::prepare_channel(MPI_COMM_SELF, channel::generate_channel(g), contact,
                                                              g.width, p, forward::linear::newton_stage());
  std::mt19937 rng(11);
  std::normal_distribution<double> shake(0.0, 2e-3);
  for (dem::Grain& grain : packing.grains) {
    if (grain.body == dem::kFreeBody) grain.position += dem::Vec3{shake(rng), shake(rng), shake(rng)};
  }
  const LoadedWall wall{channel::kUpperWallBody, p.pressure * g.width * g.width};
  const StaticEquilibriumReport r = relax_to_equilibrium(packing.grains, packing.box, contact, 2, &wall);
  ASSERT_TRUE(r.converged) << r.iterations << " iterations, residual " << r.residual_ratio;
  EXPECT_NEAR(r.wall_force / wall.force, 1.0, 1e-9);
  EXPECT_LT(r.iterations, 20) << "Newton should converge in a few steps, not crawl";  // 9 measured

  // The DEM engine's own forces at the relaxed positions (walls frozen there).
  dem::EngineSettings s;
  s.box = packing.box;
  s.contact = contact;
  std::vector<dem::RigidBody> bodies{dem::RigidBody("lower", dem::Frozen{}), dem::RigidBody("upper", dem::Frozen{})};
  dem::Engine engine(MPI_COMM_SELF, s, packing.grains, std::move(bodies));
  engine.compute_forces();
  const channel::PackingStats stats = channel::packing_stats(engine, 1.0, g.width);
  EXPECT_LT(stats.max_residual_force / stats.mean_contact_force, 1e-9);
  EXPECT_NEAR(engine.bodies()[1].contact_force().z / wall.force, 1.0, 1e-9);
}

TEST(StaticEquilibrium, RefusesFrictionalPackings) {
  channel::PreparedChannel chain = ordered_chain(5, 0.99);
  dem::ContactSpec c = frictionless(10.0);
  c.tangential = "spring_history";
  c["kt"] = 5.0;
  c["friction"] = 0.5;
  EXPECT_THROW((void)relax_to_equilibrium(chain.grains, chain.box, c, 2, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::forward::linear
