// Checkpoints across rank counts (run with mpirun -np 4): written in pieces by 2 ranks, restored on
// 3 and then on 1, the run ends where an uninterrupted 1-rank run ends, to the rank-equivalence
// tolerance; each rank reads only its rows, contact history reaches the ranks holding its grains, and
// a new checkpoint removes the old one's pieces.
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/io/hdf5.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr std::size_t kGrains = 4 * 4 * 4 * 4;  // compressed_fcc(4, ...)

struct Scene {
  EngineSettings settings;
  std::vector<Grain> grains;  // on rank 0 of the engine's communicator
};

/// A frictional periodic crystal (contact history kept), 4 cells high: three slabs of 1.9 d.
Scene crystal(MPI_Comm comm, const std::string& checkpoint, std::int64_t every) {
  Scene s;
  s.settings.contact["kn"] = 1000.0;
  s.settings.contact["restitution"] = 0.7;
  s.settings.contact.tangential = "spring_history";
  s.settings.contact["kt"] = 2.0 / 7.0 * 1000.0;
  s.settings.contact["friction"] = 0.5;
  s.settings.checkpoint = {checkpoint, every};
  s.settings.checkpoint.piece_rows = 50;  // several pieces per rank
  std::vector<Grain> all = testing::compressed_fcc(4, 0.01, 0.3, 11, s.settings.box);
  if (parallel::rank(comm) == 0) s.grains = all;
  return s;
}

std::map<std::int64_t, Grain> by_id(const Engine& engine) {
  std::map<std::int64_t, Grain> out;
  for (const Grain& g : gather_grains(engine)) out[g.id] = g;
  return out;
}


/// The tokens of the pieces beside `path` (files named PATH.piece-TOKEN-RANK-PART), with their counts.
std::map<std::string, int> pieces_of(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string prefix = p.filename().string() + ".piece-";
  std::map<std::string, int> tokens;
  for (const auto& entry : std::filesystem::directory_iterator(p.parent_path())) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(prefix)) ++tokens[name.substr(prefix.size(), 16)];
  }
  return tokens;
}

/// After a restore on another rank count, each contact-history record of the checkpoint is held by
/// exactly the ranks holding its grains (each rank read only a share of the records).
void expect_history_with_holders(MPI_Comm comm, const Engine& engine, const std::string& path) {
  std::set<std::int64_t> mine;
  for (std::size_t i = 0; i < engine.n_local(); ++i) mine.insert(engine.grains().id[i]);
  std::vector<std::int64_t> file_a, file_b;
  {
    const io::Handle file = io::open_file(path);
    const io::Handle h = io::open_group(file, "history");
    const std::size_t m = io::rows(h, "a");
    file_a = io::read_rows<std::int64_t>(h, "a", 0, m);
    file_b = io::read_rows<std::int64_t>(h, "b", 0, m);
  }
  ASSERT_FALSE(file_a.empty()) << "no friction history to carry over";
  // A pair across two ranks may have been written by both: pairs are compared, not records.
  std::set<std::pair<std::int64_t, std::int64_t>> expected, held;
  for (std::size_t k = 0; k < file_a.size(); ++k)
    if (mine.contains(file_a[k]) || mine.contains(file_b[k])) expected.insert({file_a[k], file_b[k]});
  for (const HistoryEntry& e : engine.contact_history()) held.insert({e.a, e.b});
  EXPECT_EQ(held, expected) << "rank " << parallel::rank(comm);
  EXPECT_FALSE(held.empty()) << "rank " << parallel::rank(comm);
}

TEST(CheckpointAcrossRanks, WrittenOnTwoRanksRestoredOnThreeAndOne) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  ASSERT_EQ(parallel::size(MPI_COMM_WORLD), 4) << "run under mpirun -np 4";
  const std::string path = testing::temp_path("dem_mpi_checkpoint.h5", MPI_COMM_WORLD);

  // Written by 2 ranks at step 150; the 80 steps after it are lost, as under SIGKILL.
  {
    const parallel::SubCommunicator two(MPI_COMM_WORLD, rank < 2);
    if (rank < 2) {
      const Scene s = crystal(two.get(), path, 150);
      Engine engine(two.get(), s.settings, s.grains);
      engine.run(230);
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  std::map<std::string, int> written_by_two;
  if (rank == 0) {
    written_by_two = pieces_of(path);
    ASSERT_EQ(written_by_two.size(), 1u);
    EXPECT_GE(written_by_two.begin()->second, 6) << "128 grains per rank in pieces of 50";
  }

  // Restored on 3 ranks: each reads a third of the rows; a checkpoint at step 300 replaces the pieces.
  std::map<std::int64_t, Grain> on_three;
  {
    const parallel::SubCommunicator three(MPI_COMM_WORLD, rank < 3);
    if (rank < 3) {
      const Scene s = crystal(three.get(), path, 150);
      Engine engine(three.get(), s.settings, s.grains);
      engine.restore_checkpoint(path);
      EXPECT_EQ(engine.step_count(), 150);
      expect_history_with_holders(three.get(), engine, path);
      const std::int64_t held = static_cast<std::int64_t>(engine.n_local());
      EXPECT_EQ(parallel::sum(three.get(), held), static_cast<std::int64_t>(kGrains));
      EXPECT_LT(held, static_cast<std::int64_t>(kGrains) / 2) << "rank " << rank << " holds more than its share";
      engine.run(250);
      EXPECT_FALSE(engine.contact_history().empty());
      on_three = by_id(engine);
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank != 0) return;
  // The 2-rank pieces went when the 3-rank checkpoint was in place.
  const std::map<std::string, int> written_by_three = pieces_of(path);
  ASSERT_EQ(written_by_three.size(), 1u);
  EXPECT_NE(written_by_three.begin()->first, written_by_two.begin()->first);

  // Restored on 1 rank from the 3 ranks' pieces, through the virtual datasets.
  const Scene s = crystal(MPI_COMM_SELF, path, 0);
  Engine restored(MPI_COMM_SELF, s.settings, s.grains);
  restored.restore_checkpoint(path);
  EXPECT_EQ(restored.step_count(), 300);
  restored.run(100);
  Engine straight(MPI_COMM_SELF, s.settings, s.grains);
  straight.run(400);

  const auto reference = by_id(straight);
  ASSERT_EQ(reference.size(), kGrains);
  ASSERT_EQ(on_three.size(), kGrains);
  const double d3 = testing::max_difference(reference, on_three, s.settings.box);
  const double d1 = testing::max_difference(reference, by_id(restored), s.settings.box);
  std::printf("[ info ] 2 ranks -> 3 ranks: max difference to 1 rank %.3g; 3 ranks -> 1 rank: %.3g\n", d3, d1);
  EXPECT_LT(d3, testing::kRankTolerance);
  EXPECT_LT(d1, testing::kRankTolerance);

  // One rank below piece_rows writes an ordinary file and removes the pieces.
  Scene small = crystal(MPI_COMM_SELF, path, 10);
  small.settings.checkpoint.piece_rows = kGrains * 100;
  Engine serial(MPI_COMM_SELF, small.settings, s.grains);
  serial.run(10);
  EXPECT_TRUE(pieces_of(path).empty());
  std::filesystem::remove(path);
}

TEST(CheckpointAcrossRanks, AMissingPieceIsRefusedOnEveryRank) {
  // HDF5 reads a missing piece of a virtual dataset as zeros: a checkpoint copied without its pieces
  // must be refused, by every rank (none left waiting in a collective), not restored as zero grains.
  const int rank = parallel::rank(MPI_COMM_WORLD);
  const std::string path = testing::temp_path("dem_mpi_checkpoint_missing.h5", MPI_COMM_WORLD);
  const parallel::SubCommunicator two(MPI_COMM_WORLD, rank < 2);
  if (rank < 2) {
    const Scene s = crystal(two.get(), path, 20);
    Engine engine(two.get(), s.settings, s.grains);
    engine.run(20);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    const std::filesystem::path p(path);
    std::filesystem::path last;  // a piece of rank 1's
    for (const auto& entry : std::filesystem::directory_iterator(p.parent_path())) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with(p.filename().string() + ".piece-") && name.ends_with("-1-0")) last = entry.path();
    }
    ASSERT_FALSE(last.empty());
    std::filesystem::remove(last);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank < 2) {
    const Scene s = crystal(two.get(), path, 0);
    Engine engine(two.get(), s.settings, s.grains);
    try {
      engine.restore_checkpoint(path);
      ADD_FAILURE() << "rank " << rank << " restored a checkpoint that lacks a piece";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("lacks its piece"), std::string::npos) << e.what();
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    const std::filesystem::path p(path);
    for (const auto& entry : std::filesystem::directory_iterator(p.parent_path())) {
      if (entry.path().filename().string().starts_with(p.filename().string())) std::filesystem::remove(entry.path());
    }
  }
}

}  // namespace
}  // namespace sedwave::forward::dem
