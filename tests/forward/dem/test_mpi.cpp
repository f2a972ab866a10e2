// Multi-rank tests (run with mpirun -np 4): the same scene on 1, 2 and 4 ranks gives the same
// trajectories to round-off, with migration, contact history, periodic images through ghosts and
// load balancing all active.
#include <algorithm>
#include <tuple>
#include <filesystem>
#include <map>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/dem/h5md.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

std::vector<Grain> tall_column(int nx, int nz, double overlap, Box& box, std::uint64_t seed) {
  const double a = std::sqrt(2.0) * (1.0 - overlap);
  const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 0.5);
  std::vector<Grain> grains;
  for (int ix = 0; ix < nx; ++ix)
    for (int iy = 0; iy < nx; ++iy)
      for (int iz = 0; iz < nz; ++iz)
        for (const Vec3& b : basis) {
          Grain g = testing::make_grain(static_cast<std::int64_t>(grains.size()) + 1,
                                        a * Vec3{ix + b.x + 0.25, iy + b.y + 0.25, iz + b.z + 0.25},
                                        0.5 * (1.0 + 0.02 * normal(rng)));
          g.velocity = {normal(rng), normal(rng), normal(rng)};
          grains.push_back(g);
        }
  box.lo = {0, 0, 0};
  box.hi = a * Vec3{double(nx), double(nx), double(nz)};
  return grains;
}

/// A pore fluid whose film and drag are comparable with the contacts' dashpots; buoyancy under the
/// open box's gravity. Its cut-off widens the ghost layer and the neighbour list.
FluidSpec test_fluid() {
  FluidSpec f;
  f.viscosity = 0.05;
  f.density = 0.5;
  f.roughness = 1e-3;
  f.cutoff = 0.1;
  f.drag = DragLaw::stokes;
  return f;
}

EngineSettings scene_settings(bool periodic_z, const Box& box, bool newton = false, bool fluid = false) {
  EngineSettings s;
  if (fluid) s.fluid = test_fluid();
  s.newton = newton;
  s.box = box;
  s.box.periodic = {true, true, periodic_z};
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.8;
  s.contact.tangential = "spring_history";
  s.contact["kt"] = 2.0 / 7.0 * 1000.0;
  s.contact["friction"] = 0.4;
  s.contact.rolling = "constant_torque";
  s.contact["rolling_friction"] = 0.05;
  s.balance.every_rebuilds = 2;
  if (!periodic_z) s.gravity = {0, 0, -0.5};
  return s;
}

/// Runs the scene on `comm` and returns all grains by id on the communicator's rank 0.
std::map<std::int64_t, Grain> run_on(MPI_Comm comm, bool periodic_z, bool newton, std::int64_t steps,
                                     std::size_t* history_records, bool fluid = false) {
  Box box;
  std::vector<Grain> all = tall_column(2, 12, 0.01, box, 42);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // The scene is given on rank 0 only: the engine distributes it.
  std::vector<Grain> mine = rank == 0 ? all : std::vector<Grain>{};
  std::vector<RigidBody> bodies;
  if (!periodic_z) {
    for (Grain& g : mine)
      if (g.position.z < 0.6) g.body = 1;
    bodies.emplace_back("floor", Wiggle{2, 0.01, 0.5});
  }
  Engine engine(comm, scene_settings(periodic_z, box, newton, fluid), mine, bodies);
  engine.run(steps);
  const std::size_t records = engine.contact_history().size();
  std::size_t total_records = 0;
  MPI_Reduce(&records, &total_records, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, comm);
  if (history_records) *history_records = total_records;
  const std::vector<Grain> gathered = gather_grains(engine);
  std::map<std::int64_t, Grain> out;
  for (const Grain& g : gathered) out[g.id] = g;
  return out;
}


/// (periodic z, newton on, pore fluid): the same trajectories on 1, 2 and 4 ranks, and with newton
/// on and off.
class RankEquivalence : public ::testing::TestWithParam<std::tuple<bool, bool, bool>> {};

TEST_P(RankEquivalence, SameTrajectoriesOnOneTwoAndFourRanks) {
  const auto [periodic_z, newton, fluid] = GetParam();
  int world_rank = 0, world_size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  ASSERT_EQ(world_size, 4) << "run under mpirun -np 4";
  constexpr std::int64_t steps = 400;

  std::size_t records1 = 0, records2 = 0, records4 = 0, records_other = 0;
  const auto four = run_on(MPI_COMM_WORLD, periodic_z, newton, steps, &records4, fluid);
  MPI_Comm pairs;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank / 2, world_rank, &pairs);
  const auto two = run_on(pairs, periodic_z, newton, steps, &records2, fluid);
  MPI_Comm_free(&pairs);
  std::map<std::int64_t, Grain> one, other_newton;
  if (world_rank == 0) {
    one = run_on(MPI_COMM_SELF, periodic_z, newton, steps, &records1, fluid);
    other_newton = run_on(MPI_COMM_SELF, periodic_z, !newton, steps, &records_other, fluid);
  }
  if (world_rank != 0) return;

  Box box;
  tall_column(2, 12, 0.01, box, 42);
  box.periodic = {true, true, periodic_z};
  ASSERT_EQ(one.size(), 192u);
  ASSERT_EQ(two.size(), one.size());
  ASSERT_EQ(four.size(), one.size());
  const double d2 = testing::max_difference(one, two, box), d4 = testing::max_difference(one, four, box);
  const double d_newton = testing::max_difference(one, other_newton, box);
  std::printf("[ info ] periodic_z=%d newton=%d fluid=%d: max |1-rank - 2-rank| = %.3g, |1-rank - 4-rank| = %.3g, "
              "|newton on - off| = %.3g; history records %zu/%zu/%zu\n",
              int(periodic_z), int(newton), int(fluid), d2, d4, d_newton, records1, records2, records4);
  EXPECT_LT(d2, testing::kRankTolerance);
  EXPECT_LT(d4, testing::kRankTolerance);
  EXPECT_LT(d_newton, testing::kRankTolerance);
  EXPECT_GT(records1, 0u);
  if (newton) {  // each contact is held by one side only, whatever the decomposition
    EXPECT_EQ(records2, records1);
    EXPECT_EQ(records4, records1);
  }
}

INSTANTIATE_TEST_SUITE_P(BoundariesAndNewton, RankEquivalence,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Values(false)));
// The lubricated force loop of a rotating model, drag and buoyancy, across ranks and periodic faces.
INSTANTIATE_TEST_SUITE_P(PoreFluid, RankEquivalence,
                         ::testing::Values(std::tuple{true, true, true}, std::tuple{false, false, true}));

// Trajectory writers on 4 ranks (each rank writes its own grains in turn): every grain appears once
// with exactly the state the ranks hold.
TEST(Trajectories, FourRanksWriteEveryGrainOnceBitExact) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::string h5md = testing::temp_path("dem_mpi_trajectory.h5", MPI_COMM_WORLD);
  const std::string dump = testing::temp_path("dem_mpi_trajectory.dump", MPI_COMM_WORLD);
  Box box;
  std::vector<Grain> all = tall_column(2, 12, 0.01, box, 7);
  std::vector<Grain> mine = rank == 0 ? all : std::vector<Grain>{};
  Engine engine(MPI_COMM_WORLD, scene_settings(true, box, true), mine);
  engine.run(100);  // grains migrate; the slabs are rebalanced
  H5mdWriter h5md_writer(h5md);
  LammpsDumpWriter dump_writer(dump);
  h5md_writer.write(engine);
  dump_writer.write(engine);
  const std::vector<Grain> gathered = gather_grains(engine);
  if (rank != 0) return;
  const DumpFrame from_h5md = read_h5md_frame(h5md);
  const DumpFrame from_dump = read_lammps_dump(dump);
  ASSERT_EQ(gathered.size(), all.size());
  ASSERT_EQ(from_h5md.positions.size(), all.size());
  ASSERT_EQ(from_dump.positions.size(), all.size());
  for (const Grain& g : gathered) {
    EXPECT_EQ(from_h5md.positions.at(g.id), g.position);
    EXPECT_EQ(from_h5md.velocities.at(g.id), g.velocity);
    EXPECT_EQ(from_dump.positions.at(g.id), g.position);
    EXPECT_EQ(from_dump.velocities.at(g.id), g.velocity);
  }
  std::filesystem::remove(h5md);
  std::filesystem::remove(dump);
}

// A checkpoint written on 2 ranks restarts on 3 (each reading its block of grains and of history
// records, which travel to the ranks holding their grains) and continues as the 2-rank run does,
// to the rank-equivalence tolerance; a lost or misrouted friction history would break it.
TEST(Checkpoint, TwoRankCheckpointContinuesOnThreeRanks) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GE(size, 3) << "run under mpirun -np 4";
  const std::string path = testing::temp_path("dem_mpi_two_to_three.h5", MPI_COMM_WORLD);
  constexpr std::int64_t steps = 200;
  Box box;
  const std::vector<Grain> all = tall_column(2, 12, 0.01, box, 11);
  const EngineSettings settings = scene_settings(true, box, true);
  const std::vector<Grain> none;

  std::map<std::int64_t, Grain> straight, restarted;
  std::size_t records_at_checkpoint = 0;
  {
    const parallel::SubCommunicator two(MPI_COMM_WORLD, rank < 2);
    if (two.get() != MPI_COMM_NULL) {
      Engine engine(two.get(), settings, rank == 0 ? all : none);
      engine.run(steps);
      records_at_checkpoint = parallel::sum(two.get(), engine.contact_history().size());
      engine.write_checkpoint(path);
      engine.run(steps);
      for (const Grain& g : gather_grains(engine)) straight[g.id] = g;
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  {
    const parallel::SubCommunicator three(MPI_COMM_WORLD, rank < 3);
    if (three.get() != MPI_COMM_NULL) {
      Engine engine(three.get(), settings, rank == 0 ? all : none);
      engine.restore_checkpoint(path);
      EXPECT_EQ(engine.step_count(), steps);
      EXPECT_GT(engine.n_local(), 0u) << "rank " << rank << " read no grains";
      engine.run(steps);
      for (const Grain& g : gather_grains(engine)) restarted[g.id] = g;
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank != 0) return;
  EXPECT_GT(records_at_checkpoint, 0u);  // friction history to carry over
  ASSERT_EQ(straight.size(), all.size());
  ASSERT_EQ(restarted.size(), all.size());
  EXPECT_LT(testing::max_difference(straight, restarted, box), testing::kRankTolerance);
  std::filesystem::remove(path);
}

// A trajectory file that cannot be opened (its path is a directory): rank 0's turn fails, and
// every rank throws the same error rather than waiting for a token that never comes.
TEST(Trajectories, AnUnwritableFileFailsOnEveryRankWithOneMessage) {
  const std::string directory = testing::temp_path("dem_mpi_unwritable", MPI_COMM_WORLD);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::filesystem::create_directories(directory);
  MPI_Barrier(MPI_COMM_WORLD);
  Box box;
  std::vector<Grain> all = tall_column(2, 12, 0.01, box, 7);
  Engine engine(MPI_COMM_WORLD, scene_settings(true, box, true), rank == 0 ? all : std::vector<Grain>{});
  H5mdWriter h5md_writer(directory);
  LammpsDumpWriter dump_writer(directory);
  const auto message_of = [](const auto& write) {
    try {
      write();
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const std::string& message : {message_of([&] { dump_writer.write(engine); }),
                                     message_of([&] { h5md_writer.write(engine); })}) {
    EXPECT_NE(message.find(directory), std::string::npos) << message;
    std::string from_rank_0 = message;
    parallel::broadcast(MPI_COMM_WORLD, from_rank_0);
    EXPECT_EQ(message, from_rank_0);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace sedwave::forward::dem
