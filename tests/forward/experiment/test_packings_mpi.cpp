// A scene's packing spread over ranks (run with mpirun -np 3): read, written, hashed, measured and
// shared with the task farm's groups with no rank holding it whole, each giving what one rank
// holding every grain gives. The packing is the shipped 1000-grain one (data/tables/).
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "sedwave/forward/channel/packing_units.hpp"
#include "sedwave/forward/experiment/packings.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::experiment {
namespace {

constexpr const char* kPacking = SEDWAVE_SOURCE_DIR "/data/tables/thesis_w3_small.packing.h5";

int rank() { return parallel::rank(MPI_COMM_WORLD); }
int ranks() { return parallel::size(MPI_COMM_WORLD); }

void expect_same_grains(const std::vector<dem::Grain>& a, const std::vector<dem::Grain>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].id, b[k].id) << "row " << k;
    EXPECT_EQ(a[k].group, b[k].group) << "grain " << a[k].id;
    EXPECT_EQ(a[k].body, b[k].body) << "grain " << a[k].id;
    EXPECT_EQ(a[k].radius, b[k].radius) << "grain " << a[k].id;
    EXPECT_EQ(a[k].mass, b[k].mass) << "grain " << a[k].id;
    EXPECT_EQ(a[k].position, b[k].position) << "grain " << a[k].id;
  }
}

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class SpreadPacking : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_GE(ranks(), 2) << "run under mpirun -np 3";
    whole_ = read_packing(MPI_COMM_SELF, kPacking);
    spread_ = read_packing(MPI_COMM_WORLD, kPacking);
  }
  channel::PreparedChannel whole_;   ///< every grain, on every rank
  channel::PreparedChannel spread_;  ///< this rank's share
};

TEST_F(SpreadPacking, EachRankReadsItsShareAndTheHashIsOneRanks) {
  const std::size_t n = whole_.grains.size();
  EXPECT_LE(spread_.grains.size(), n / static_cast<std::size_t>(ranks()) + 1) << "rank " << rank();
  EXPECT_GE(spread_.grains.size(), n / static_cast<std::size_t>(ranks())) << "rank " << rank();
  const std::vector<dem::Grain> gathered = parallel::gather_on_root(MPI_COMM_WORLD, spread_.grains);
  if (rank() == 0) expect_same_grains(gathered, whole_.grains);
  EXPECT_EQ(spread_.box.lo, whole_.box.lo);
  EXPECT_EQ(spread_.box.hi, whole_.box.hi);
  EXPECT_EQ(packing_fingerprint(MPI_COMM_WORLD, spread_), packing_fingerprint(whole_));
  // Any other packing hashes differently: one grain moved by one ulp.
  channel::PreparedChannel moved = spread_;
  if (rank() == ranks() - 1) moved.grains.back().position.z = std::nextafter(moved.grains.back().position.z, 1e9);
  EXPECT_NE(packing_fingerprint(MPI_COMM_WORLD, moved), packing_fingerprint(whole_));
}

TEST_F(SpreadPacking, WrittenFromSharesAreTheFilesOneRankWrites) {
  std::string dir = (std::filesystem::temp_directory_path() / ("sedwave_spread_" + std::to_string(::getpid()))).string();
  parallel::broadcast(MPI_COMM_WORLD, dir);
  if (rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  write_packing(MPI_COMM_WORLD, dir + "/spread.h5", spread_, "scene text");
  if (rank() == 0) {
    write_packing(dir + "/whole.h5", whole_, "scene text");
    const channel::PreparedChannel back = read_packing(dir + "/spread.h5");
    expect_same_grains(back.grains, whole_.grains);
    EXPECT_EQ(back.box.lo, whole_.box.lo);
    EXPECT_EQ(back.box.hi, whole_.box.hi);
    EXPECT_EQ(back.report.pressure, whole_.report.pressure);
    const std::string twin = file_text(dir + "/spread.data");
    EXPECT_GT(twin.size(), 1000u * 50u);
    EXPECT_EQ(twin, file_text(dir + "/whole.data"));
    std::filesystem::remove_all(dir);
  }
}

/// The piece files beside `path` (PATH.piece-*).
std::vector<std::filesystem::path> pieces_of(const std::filesystem::path& path) {
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
    if (entry.path().filename().string().starts_with(path.filename().string() + ".piece-")) out.push_back(entry.path());
  }
  return out;
}

TEST_F(SpreadPacking, ALargePackingIsWrittenInPiecesAndReadAsOneFile) {
  std::string dir = (std::filesystem::temp_directory_path() / ("sedwave_pieces_" + std::to_string(::getpid()))).string();
  parallel::broadcast(MPI_COMM_WORLD, dir);
  if (rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::filesystem::path path = dir + "/packing.h5";
  // "Large" here: more than 100 grains in all, pieces of at most 128 (each rank's third in 3).
  write_packing(MPI_COMM_WORLD, path, spread_, "scene text", {100, 128});
  std::size_t expected = 0;  // at least one piece per rank, at most 128 grains each
  for (const std::uint64_t n : parallel::all_gather(MPI_COMM_WORLD, std::uint64_t{spread_.grains.size()}))
    expected += std::max<std::uint64_t>(1, (n + 127) / 128);
  EXPECT_EQ(pieces_of(path).size(), expected);
  if (rank() == 0) {
    const channel::PreparedChannel back = read_packing(path);
    expect_same_grains(back.grains, whole_.grains);
    EXPECT_EQ(back.box.hi, whole_.box.hi);
    EXPECT_EQ(back.report.pressure, whole_.report.pressure);
  }
  expect_same_grains(read_packing(MPI_COMM_WORLD, path).grains, spread_.grains);

  // A piece left behind when the file was copied: refused on every rank, naming the piece.
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) std::filesystem::remove(pieces_of(path).back());
  MPI_Barrier(MPI_COMM_WORLD);
  try {
    (void)read_packing(MPI_COMM_WORLD, path);
    ADD_FAILURE() << "rank " << rank() << " read a packing without its piece";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("lacks its piece"), std::string::npos) << e.what();
  }
  // Written again as one file: the old pieces go.
  write_packing(MPI_COMM_WORLD, path, spread_, "scene text");
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(pieces_of(path).empty());
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0) std::filesystem::remove_all(dir);
}

TEST_F(SpreadPacking, StaticContactsAndUnitsAreTheOneRankNetworks) {
  dem::ContactSpec hertz;
  hertz.normal = "hertz";
  hertz["effective_modulus"] = 5e4;
  hertz["restitution"] = 0.9;
  // On one rank from the serial contact network; spread, from a DEM force evaluation.
  const channel::StaticContacts alone = channel::static_contacts(MPI_COMM_SELF, whole_, hertz);
  const channel::StaticContacts spread = channel::static_contacts(MPI_COMM_WORLD, spread_, hertz);
  ASSERT_GT(alone.mean_stiffness, 0.0);
  ASSERT_GT(alone.upper_wall_force, 0.0);
  EXPECT_NEAR(spread.mean_stiffness, alone.mean_stiffness, 1e-12 * alone.mean_stiffness);
  EXPECT_NEAR(spread.mean_dashpot, alone.mean_dashpot, 1e-12 * alone.mean_dashpot);
  EXPECT_NEAR(spread.upper_wall_force, alone.upper_wall_force, 1e-9 * alone.upper_wall_force);
  const channel::PackingUnits a = channel::packing_units(MPI_COMM_SELF, whole_, hertz);
  const channel::PackingUnits s = channel::packing_units(MPI_COMM_WORLD, spread_, hertz);
  EXPECT_NEAR(s.kappa, a.kappa, 1e-12 * a.kappa);
  EXPECT_NEAR(s.damping_scale, a.damping_scale, 1e-12 * a.damping_scale);
  EXPECT_NEAR(s.diameter, a.diameter, 1e-14 * a.diameter);
  EXPECT_NEAR(s.porosity, a.porosity, 1e-13);
}

TEST_F(SpreadPacking, GroupsOfOneRankHoldItWholeAndOneGroupKeepsTheShares) {
  channel::PreparedChannel each = spread_;
  share_packing_with_groups(MPI_COMM_WORLD, each, 1);
  expect_same_grains(each.grains, whole_.grains);
  channel::PreparedChannel one_group = spread_;
  share_packing_with_groups(MPI_COMM_WORLD, one_group, ranks());
  expect_same_grains(one_group.grains, spread_.grains);
}

TEST_F(SpreadPacking, SpreadingByIdSortsGrainsFromAnyRanksInAnyOrder) {
  // Every third grain, on the next rank over, shuffled.
  std::vector<dem::Grain> mixed;
  for (std::size_t k = 0; k < whole_.grains.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(ranks())) == (rank() + 1) % ranks()) mixed.push_back(whole_.grains[k]);
  }
  std::shuffle(mixed.begin(), mixed.end(), std::mt19937(static_cast<unsigned>(rank())));
  const std::vector<dem::Grain> spread = spread_by_id(MPI_COMM_WORLD, mixed);
  EXPECT_TRUE(std::is_sorted(spread.begin(), spread.end(),
                             [](const dem::Grain& a, const dem::Grain& b) { return a.id < b.id; }));
  EXPECT_LE(spread.size(), whole_.grains.size() / static_cast<std::size_t>(ranks()) + 1) << "rank " << rank();
  std::vector<dem::Grain> sorted = whole_.grains;
  std::sort(sorted.begin(), sorted.end(), [](const dem::Grain& a, const dem::Grain& b) { return a.id < b.id; });
  const std::vector<dem::Grain> gathered = parallel::gather_on_root(MPI_COMM_WORLD, spread);
  if (rank() == 0) expect_same_grains(gathered, sorted);
}

}  // namespace
}  // namespace sedwave::forward::experiment
