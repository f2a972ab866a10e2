// LAMMPS files: data files and dumps read back bit for bit what was written; malformed input is
// refused with the file and line named; a dump cut short by SIGKILL is truncated to whole frames.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"

namespace sedwave::forward::dem {
namespace {

std::string temp_file(const std::string& name) {
  return testing::temp_path("lammps_io_" + name);
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// Grains with arbitrary doubles (no short decimal forms), types 1 to 3.
std::vector<Grain> random_grains(std::size_t n, Box& box) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  box.lo = {-0.1 * u(rng), -0.2 * u(rng), -0.3 * u(rng)};
  box.hi = {10.0 + u(rng), 10.0 + u(rng), 30.0 + u(rng)};
  std::vector<Grain> grains;
  for (std::size_t i = 0; i < n; ++i) {
    Grain g = testing::make_grain(static_cast<std::int64_t>(3 * i + 1),
                                  {10.0 * u(rng), 10.0 * u(rng), 30.0 * u(rng)}, 0.4 + 0.2 * u(rng),
                                  1.0 + u(rng));
    g.group = static_cast<std::int32_t>(1 + i % 3);
    g.velocity = {u(rng) - 0.5, 1e-7 * u(rng), -3e5 * u(rng)};
    g.angular_velocity = {u(rng), -u(rng), 1e-300 * u(rng) * (i % 2 == 0 ? 1.0 : 1e-20)};  // subnormal too
    grains.push_back(g);
  }
  return grains;
}

/// Expects `f` to throw std::runtime_error whose message contains `where`.
template <typename F>
void expect_error_at(F f, const std::string& where) {
  try {
    f();
    ADD_FAILURE() << "no error, expected one at " << where;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << "message: " << e.what();
  }
}

TEST(LammpsData, RoundTripIsBitExact) {
  Box box;
  const std::vector<Grain> grains = random_grains(50, box);
  const std::string path = temp_file("round_trip.data");
  write_lammps_data(path, box, grains);
  const LammpsData back = read_lammps_data(path);
  EXPECT_EQ(back.box.lo, box.lo);
  EXPECT_EQ(back.box.hi, box.hi);
  ASSERT_EQ(back.grains.size(), grains.size());
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const Grain& a = grains[i];
    const Grain& b = back.grains[i];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.group, b.group);
    EXPECT_EQ(a.radius, b.radius);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.velocity, b.velocity);
    EXPECT_EQ(a.angular_velocity, b.angular_velocity);
    // The file stores a density: mass -> density -> mass is exact to the last bit or two.
    EXPECT_NEAR(a.mass, b.mass, 4e-16 * a.mass);
  }
  // The filter keeps a share (as each rank does) with its velocities.
  const LammpsData odd = read_lammps_data(path, [](const Grain& g) { return g.group == 2; });
  ASSERT_EQ(odd.grains.size(), 17u);
  EXPECT_EQ(odd.grains[0].velocity, grains[1].velocity);
  std::filesystem::remove(path);
}

TEST(LammpsData, MalformedInputNamesFileAndLine) {
  const std::string path = temp_file("bad.data");
  const std::string header = "title\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n";
  write_text(path, header + "Atoms # sphere\n\n1 1 1.0 1.0 0.5 0.5 0.5\n2 1 1.0 1.0 0.5 0.5 zero\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":12: bad coordinate 'zero'");
  write_text(path, header + "Atoms # sphere\n\n1 1 1.0 1.0 0.5 0.5\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":11: bad Atoms line");
  write_text(path, header + "Atoms # atomic\n\n1 1 0.5 0.5 0.5\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":9: atom_style atomic is not supported");
  write_text(path, header + "Atoms # sphere\n\n1 1 1.0 1.0 0.5 0.5 0.5\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, "header announces 2 atoms, found 1");
  write_text(path, "title\n\n2 atoms\n0 1.5x xlo xhi\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":4: bad xhi '1.5x'");
  expect_error_at([] { (void)read_lammps_data("/nonexistent/packing.data"); }, "/nonexistent/packing.data: cannot open");
  const std::string one = "title\n\n1 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n";
  write_text(path, one + "Atoms # sphere\n\n1 1 1.0 1.0 0.5 0.5 0.5\n\nVelocities\n\n7 0 0 0 0 0 0\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":15: Velocities entry for atom id 7, which is not in the Atoms");
  write_text(path, header + "Atoms # sphere\n\n1 1 1.0 1.0 0.5 0.5 0.5\n1 1 1.0 1.0 0.5 0.5 0.7\n");
  // A duplicate is refused even when the first copy went to another rank.
  expect_error_at([&] { (void)read_lammps_data(path, [](const Grain&) { return false; }); }, path + ":12: duplicate atom id 1");
  write_text(path, "title\n\n1 atoms\n1 0 xlo xhi\n");
  expect_error_at([&] { (void)read_lammps_data(path); }, path + ":4: xlo 1 and xhi 0: the box must have finite, positive extent");
  std::filesystem::remove(path);
}

/// A small engine whose grains carry arbitrary doubles.
Engine small_engine(std::vector<Grain>& grains) {
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.9;
  Box box;
  grains = random_grains(30, box);
  s.box.lo = box.lo;
  s.box.hi = box.hi;
  return Engine(MPI_COMM_SELF, s, grains);
}

TEST(LammpsDump, RoundTripIsBitExact) {
  std::vector<Grain> grains;
  Engine engine = small_engine(grains);
  const std::string path = temp_file("round_trip.dump");
  LammpsDumpWriter writer(path);
  writer.write(engine);
  const GrainArrays first = engine.grains();
  engine.run(20);
  writer.write(engine);

  const DumpFrame frame0 = read_lammps_dump(path, 0);
  const DumpFrame last = read_lammps_dump(path);
  EXPECT_EQ(frame0.step, 0);
  EXPECT_EQ(last.step, 20);
  EXPECT_EQ(last.box.lo, engine.domain().box().lo);
  EXPECT_EQ(last.box.hi, engine.domain().box().hi);
  ASSERT_EQ(last.positions.size(), grains.size());
  for (std::size_t i = 0; i < engine.n_local(); ++i) {
    EXPECT_EQ(frame0.positions.at(first.id[i]), first.position[i]);
    EXPECT_EQ(last.positions.at(engine.grains().id[i]), engine.grains().position[i]);
    EXPECT_EQ(last.velocities.at(engine.grains().id[i]), engine.grains().velocity[i]);
  }
  expect_error_at([&] { (void)read_lammps_dump(path, 7); }, path + ": no frame with step 7");
  std::filesystem::remove(path);
}

TEST(LammpsDump, ScaledCoordinatesAreMappedToTheBox) {
  const std::string path = temp_file("scaled.dump");
  write_text(path,
             "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp ff\n0 2\n-1 1\n10 20\n"
             "ITEM: ATOMS id type xs ys zs\n7 1 0.25 0.5 0.1\n");
  const DumpFrame f = read_lammps_dump(path);
  EXPECT_EQ(f.step, 5);
  EXPECT_EQ(f.positions.at(7), (Vec3{0.5, 0.0, 11.0}));
  EXPECT_TRUE(f.velocities.empty());
  EXPECT_TRUE(f.box.periodic[0] && f.box.periodic[1] && !f.box.periodic[2]);
  std::filesystem::remove(path);
}

TEST(LammpsDump, MalformedInputNamesFileAndLine) {
  const std::string path = temp_file("bad.dump");
  const std::string head = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n";
  write_text(path, head + "ITEM: ATOMS id type x y z\n1 1 0.1 0.2 0.3\n2 1 0.1 0.2 nan?\n");
  expect_error_at([&] { (void)read_lammps_dump(path); }, path + ":11: bad coordinate 'nan?'");
  write_text(path, head + "ITEM: ATOMS id type x y z\n1 1 0.1 0.2 0.3\n");
  expect_error_at([&] { (void)read_lammps_dump(path); }, path + ":10: unexpected end of file, expected an atom line");
  write_text(path, head + "ITEM: ATOMS id type q\n1 1 0.1\n2 1 0.2\n");
  expect_error_at([&] { (void)read_lammps_dump(path); }, path + ":9: the dump needs id and x y z");
  write_text(path, "ITEM: TIMESTEP\nfive\n");
  expect_error_at([&] { (void)read_lammps_dump(path); }, path + ":2: bad time step 'five'");
  std::filesystem::remove(path);
}

TEST(LammpsDump, TruncationKeepsWholeFramesUpToTheCheckpoint) {
  std::vector<Grain> grains;
  Engine engine = small_engine(grains);
  const std::string path = temp_file("truncate.dump");
  LammpsDumpWriter writer(path);
  for (int k = 0; k < 4; ++k) {  // frames at steps 0, 10, 20, 30
    if (k > 0) engine.run(10);
    writer.write(engine);
  }
  const auto size_with = [&](std::int64_t step) {
    // Byte length of the file up to the end of the frame with this step.
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto next = text.find("ITEM: TIMESTEP\n" + std::to_string(step + 10) + "\n");
    return next == std::string::npos ? text.size() : next;
  };
  const std::uintmax_t through_20 = size_with(20);

  // Steps after the checkpoint (25) are dropped.
  EXPECT_EQ(truncate_lammps_dump(path, 25), 3u);
  EXPECT_EQ(std::filesystem::file_size(path), through_20);
  EXPECT_EQ(read_lammps_dump(path).step, 20);

  // A frame cut short (here in the middle of a number) is dropped whatever its step.
  std::ofstream(path, std::ios::app) << "ITEM: TIMESTEP\n30\nITEM: NUMBER OF ATOMS\n30\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
                                        "ITEM: ATOMS id type radius x y z vx vy vz\n1 1 0.5 0.12";
  EXPECT_EQ(truncate_lammps_dump(path, 1000), 3u);
  EXPECT_EQ(std::filesystem::file_size(path), through_20);

  // Appending continues the file as if it had never been cut.
  LammpsDumpWriter appender(path, true);
  appender.write(engine);
  EXPECT_EQ(read_lammps_dump(path).step, 30);
  EXPECT_EQ(read_lammps_dump(path, 20).step, 20);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sedwave::forward::dem
