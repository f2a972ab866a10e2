// Tiling a periodic cell on several ranks (run with mpirun -np 3): every rank builds only its share
// of the copies, and together they hold exactly the channel one rank builds alone, grain for grain.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>

#include "hooke_contact.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::channel {
namespace {

using testing::hooke_contact;

std::vector<dem::Grain> by_id(std::vector<dem::Grain> grains) {
  std::sort(grains.begin(), grains.end(), [](const dem::Grain& a, const dem::Grain& b) { return a.id < b.id; });
  return grains;
}

TEST(TilingPerRank, RanksTogetherHoldTheChannelOneRankBuilds) {
  const int rank = parallel::rank(MPI_COMM_WORLD), ranks = parallel::size(MPI_COMM_WORLD);
  ASSERT_GE(ranks, 2) << "run under mpirun -np 3";
  // A loose z-periodic column serves as the cell: tiling does not ask for equilibrium.
  ChannelGeometry geometry;
  geometry.n_grains = 200;
  geometry.periodic = true;
  PreparedChannel cell;
  cell.box = generate_channel(geometry).box;
  if (rank == 0) cell.grains = generate_channel(geometry).grains;
  constexpr int kCopies = 7;  // not a multiple of the rank count

  const PreparedChannel spread = tile_periodic_cell(MPI_COMM_WORLD, cell, hooke_contact(), kCopies, 1.5);
  const std::size_t share = spread.grains.size();
  EXPECT_GE(share, (kCopies / ranks) * 200u) << "rank " << rank;
  EXPECT_LE(share, (kCopies / ranks + 1) * 200u) << "rank " << rank;
  const std::vector<dem::Grain> gathered = by_id(parallel::gather_on_root(MPI_COMM_WORLD, spread.grains));
  if (rank != 0) return;

  const PreparedChannel alone = tile_periodic_cell(MPI_COMM_SELF, cell, hooke_contact(), kCopies, 1.5);
  ASSERT_EQ(gathered.size(), kCopies * 200u);
  ASSERT_EQ(alone.grains.size(), gathered.size());
  for (std::size_t k = 0; k < gathered.size(); ++k) {
    const dem::Grain &a = alone.grains[k], &b = gathered[k];
    ASSERT_EQ(a.id, b.id) << k;
    EXPECT_EQ(a.group, b.group) << "grain " << a.id;
    EXPECT_EQ(a.body, b.body) << "grain " << a.id;
    EXPECT_EQ(a.radius, b.radius) << "grain " << a.id;
    EXPECT_EQ(a.mass, b.mass) << "grain " << a.id;
    EXPECT_EQ(a.position, b.position) << "grain " << a.id;
  }
  EXPECT_EQ(alone.box.lo, spread.box.lo);
  EXPECT_EQ(alone.box.hi, spread.box.hi);
  // The channel as the DEM measures it: the same contacts; forces summed in another order.
  EXPECT_EQ(alone.report.stats.contacts, spread.report.stats.contacts);
  EXPECT_NEAR(alone.report.wall_force, spread.report.wall_force, 1e-9 * std::abs(alone.report.wall_force) + 1e-12);
}

}  // namespace
}  // namespace sedwave::forward::channel
