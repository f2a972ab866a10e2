// A LAMMPS data file read by 2, 3 and 4 ranks together, each parsing its share of the bytes, gives
// exactly the grains of a serial read; a malformed file fails on every rank with the serial read's
// message, whose line number is counted across the ranks' shares (run with mpirun -np 4).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr std::size_t kDataFileGrains = 240;

/// Grains with arbitrary doubles, ids out of order, types 1 to 3.
std::vector<Grain> random_grains(Box& box) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  box.lo = {-u(rng), -u(rng), -u(rng)};
  box.hi = {8.0 + u(rng), 8.0 + u(rng), 40.0 + u(rng)};
  std::vector<Grain> grains;
  for (std::size_t i = 0; i < kDataFileGrains; ++i) {
    Grain g = testing::make_grain(static_cast<std::int64_t>((7 * i) % kDataFileGrains) * 5 + 2,
                                  {8.0 * u(rng), 8.0 * u(rng), 40.0 * u(rng)}, 0.4 + 0.2 * u(rng), 1.0 + u(rng));
    g.group = static_cast<std::int32_t>(1 + i % 3);
    g.velocity = {u(rng) - 0.5, 1e-7 * u(rng), -3e5 * u(rng)};
    g.angular_velocity = {u(rng), -u(rng), 1e-3 * u(rng)};
    grains.push_back(g);
  }
  return grains;
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void write_lines(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const std::string& line : lines) out << line << '\n';
}

/// The line numbers (from 1) of write_lammps_data's layout: atom k, velocity k.
std::size_t atom_line(std::size_t k) { return 11 + k; }
std::size_t velocity_line(std::size_t k) { return 14 + kDataFileGrains + k; }

/// The file written by rank 0, with its velocity lines in reverse order and one atom's velocity
/// given twice (the later line wins), so that atoms and velocities meet from different ranks.
std::string packing_file(const std::vector<Grain>& grains, const Box& box) {
  const std::string path = testing::temp_path("lammps_ranges.data", MPI_COMM_WORLD);
  if (parallel::rank(MPI_COMM_WORLD) == 0) {
    write_lammps_data(path, box, grains);
    std::vector<std::string> lines = lines_of(path);
    const auto first = lines.begin() + static_cast<std::ptrdiff_t>(velocity_line(0) - 1);
    std::reverse(first, first + kDataFileGrains);
    std::string repeated = lines[velocity_line(3) - 1];
    repeated = repeated.substr(0, repeated.find(' ')) + " 1 2 3 4 5 6";
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(velocity_line(kDataFileGrains - 2) - 1), repeated);
    write_lines(path, lines);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

std::vector<Grain> sorted_by_id(std::vector<Grain> grains) {
  std::sort(grains.begin(), grains.end(), [](const Grain& a, const Grain& b) { return a.id < b.id; });
  return grains;
}

void expect_same(const Grain& a, const Grain& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.group, b.group);
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity, b.velocity) << "grain " << a.id;
  EXPECT_EQ(a.angular_velocity, b.angular_velocity) << "grain " << a.id;
}

/// The message of the error `read` throws ("" if none).
template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(LammpsDataRanges, TwoThreeAndFourRanksReadExactlyTheSerialGrains) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  ASSERT_EQ(parallel::size(MPI_COMM_WORLD), 4) << "run under mpirun -np 4";
  Box box;
  const std::string path = packing_file(random_grains(box), box);
  const LammpsData serial = read_lammps_data(path);
  const std::vector<Grain> expected = sorted_by_id(serial.grains);
  ASSERT_EQ(expected.size(), kDataFileGrains);
  for (int ranks : {2, 3, 4}) {
    const parallel::SubCommunicator sub(MPI_COMM_WORLD, rank < ranks);
    if (sub.get() == MPI_COMM_NULL) continue;
    LammpsData data;  // an error must not leave ranks apart (the next loop is collective)
    EXPECT_EQ(error_of([&] { data = read_lammps_data(sub.get(), path); }), "") << ranks << " ranks";
    EXPECT_EQ(data.box.lo, serial.box.lo);
    EXPECT_EQ(data.box.hi, serial.box.hi);
    // No rank holds the packing whole: each joins the ids congruent to its rank.
    EXPECT_LT(data.grains.size(), kDataFileGrains) << ranks << " ranks, rank " << rank;
    for (const Grain& g : data.grains) EXPECT_EQ(g.id % ranks, rank) << "grain " << g.id;
    const std::vector<Grain> all = sorted_by_id(parallel::gather_on_root(sub.get(), data.grains));
    if (rank != 0) continue;
    EXPECT_EQ(all.size(), expected.size()) << ranks << " ranks";
    for (std::size_t k = 0; k < std::min(all.size(), expected.size()); ++k) expect_same(all[k], expected[k]);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove(path);
}

// Each malformation sits late in the Atoms or the Velocities section, beyond rank 0's share of the
// bytes (the Atoms ones on 3 ranks, the Velocities ones on 2 and 3), so that its line number is a sum
// of the line counts of the shares before; the message on every rank is the serial one.
TEST(LammpsDataRanges, MalformedLinesAreNamedAsASerialReadNamesThem) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  ASSERT_EQ(parallel::size(MPI_COMM_WORLD), 4) << "run under mpirun -np 4";
  Box box;
  const std::vector<Grain> grains = random_grains(box);
  const std::string clean = packing_file(grains, box);
  const std::vector<std::string> lines = lines_of(clean);
  const std::string path = testing::temp_path("lammps_ranges_bad.data", MPI_COMM_WORLD);
  struct Case {
    std::size_t line;           ///< the line changed (from 1)
    std::string text;           ///< its new text
    std::string expected;       ///< what the message says after "path:line: "
  };
  const std::string first_id = std::to_string(grains.front().id);
  const std::vector<Case> cases = {
      {atom_line(kDataFileGrains - 3), "9999 1 1.0 1.0 0.5 0.5 zero", "bad coordinate 'zero'"},
      {atom_line(kDataFileGrains - 1), first_id + " 2 1.0 1.0 0.5 0.5 0.5", "duplicate atom id " + first_id},
      {atom_line(kDataFileGrains - 2), "1 1 1.0 1.0 0.5 0.5", "bad Atoms line"},
      {velocity_line(kDataFileGrains - 4), "123456 0 0 0 0 0 0", "Velocities entry for atom id 123456, which is not in the Atoms"},
      {velocity_line(kDataFileGrains - 6), "7 0 0 0 0 0", "bad Velocities line"},
  };
  for (const Case& c : cases) {
    if (rank == 0) {
      std::vector<std::string> changed = lines;
      changed[c.line - 1] = c.text;
      write_lines(path, changed);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    const std::string serial = error_of([&] { (void)read_lammps_data(path); });
    EXPECT_EQ(serial.find(path + ":" + std::to_string(c.line) + ": " + c.expected), 0u) << serial;
    for (int ranks : {2, 3}) {
      const parallel::SubCommunicator sub(MPI_COMM_WORLD, rank < ranks);
      if (sub.get() == MPI_COMM_NULL) continue;
      EXPECT_EQ(error_of([&] { (void)read_lammps_data(sub.get(), path); }), serial) << ranks << " ranks, rank " << rank;
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  // Two malformed lines in different ranks' shares: the first in the file is named.
  if (rank == 0) {
    std::vector<std::string> changed = lines;
    changed[atom_line(1) - 1] = "5 1 1.0 -1.0 0.5 0.5 0.5";
    changed[velocity_line(kDataFileGrains - 1) - 1] = "7 0 0";
    write_lines(path, changed);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string message = error_of([&] { (void)read_lammps_data(MPI_COMM_WORLD, path); });
  EXPECT_EQ(message.find(path + ":" + std::to_string(atom_line(1)) + ": diameter and density must be positive"), 0u)
      << message;
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    std::filesystem::remove(path);
    std::filesystem::remove(clean);
  }
}

// Files of 1 to 12 grains on 2, 3 and 4 ranks: the edges of the shares fall on every kind of line
// (keywords, blank lines, the header's end, atoms, velocities), and every read equals the serial one.
TEST(LammpsDataRanges, ShareEdgesOnEveryKindOfLine) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  Box box;
  const std::vector<Grain> grains = random_grains(box);
  const std::string path = testing::temp_path("lammps_ranges_edges.data", MPI_COMM_WORLD);
  for (std::size_t n = 1; n <= 12; ++n) {
    if (rank == 0) write_lammps_data(path, box, std::span(grains).first(n));
    MPI_Barrier(MPI_COMM_WORLD);
    const std::vector<Grain> expected = sorted_by_id(read_lammps_data(path).grains);
    for (int ranks : {2, 3, 4}) {
      const parallel::SubCommunicator sub(MPI_COMM_WORLD, rank < ranks);
      if (sub.get() == MPI_COMM_NULL) continue;
      LammpsData data;
      EXPECT_EQ(error_of([&] { data = read_lammps_data(sub.get(), path); }), "") << n << " grains, " << ranks << " ranks";
      const std::vector<Grain> all = sorted_by_id(parallel::gather_on_root(sub.get(), data.grains));
      if (rank != 0) continue;
      EXPECT_EQ(all.size(), n) << ranks << " ranks";
      for (std::size_t k = 0; k < std::min(all.size(), expected.size()); ++k) expect_same(all[k], expected[k]);
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  if (rank == 0) std::filesystem::remove(path);
}

// More ranks than lines: the empty shares still agree, and a header that announces more atoms than
// the file holds fails on every rank.
TEST(LammpsDataRanges, ATinyFileOnFourRanks) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  const std::string path = testing::temp_path("lammps_ranges_tiny.data", MPI_COMM_WORLD);
  const std::string header = "title\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n";
  if (rank == 0) std::ofstream(path) << header << "Atoms # sphere\n\n4 1 1.0 1.0 0.5 0.5 0.5\n1 1 1.0 1.0 0.2 0.5 0.5";
  MPI_Barrier(MPI_COMM_WORLD);
  LammpsData data;
  EXPECT_EQ(error_of([&] { data = read_lammps_data(MPI_COMM_WORLD, path); }), "");
  const std::vector<Grain> all = sorted_by_id(parallel::gather_on_root(MPI_COMM_WORLD, data.grains));
  if (rank == 0 && all.size() == 2) {
    EXPECT_EQ(all[0].id, 1);
    EXPECT_EQ(all[0].position.x, 0.2);  // the last line has no newline: still read
    EXPECT_EQ(all[1].id, 4);
  }
  if (rank == 0) {
    EXPECT_EQ(all.size(), 2u);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::ofstream(path) << header << "Atoms # sphere\n\n4 1 1.0 1.0 0.5 0.5 0.5\n";
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string message = error_of([&] { (void)read_lammps_data(MPI_COMM_WORLD, path); });
  EXPECT_EQ(message, path + ": header announces 2 atoms, found 1");
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove(path);
}

}  // namespace
}  // namespace sedwave::forward::dem
