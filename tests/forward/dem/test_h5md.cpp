// H5MD trajectories: the layout follows H5MD 1.1, frames read back bit for bit, and a restart's
// truncation drops the frames written after the checkpoint.
#include <hdf5.h>

#include <filesystem>
#include <map>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/h5md.hpp"

namespace sedwave::forward::dem {
namespace {

struct Snapshot {
  std::map<std::int64_t, Vec3> position, velocity;
};

Snapshot snapshot(const Engine& e) {
  Snapshot s;
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    s.position[e.grains().id[i]] = e.grains().position[i];
    s.velocity[e.grains().id[i]] = e.grains().velocity[i];
  }
  return s;
}

EngineSettings fcc_settings(Box box) {
  EngineSettings s;
  s.box = box;
  s.box.periodic[2] = false;  // one open axis, to check the boundary attribute
  s.contact["kn"] = 1000.0;
  s.contact["restitution"] = 0.8;
  return s;
}

void expect_frame_equals(const DumpFrame& f, const Snapshot& s) {
  ASSERT_EQ(f.positions.size(), s.position.size());
  for (const auto& [id, x] : s.position) {
    EXPECT_EQ(f.positions.at(id), x) << "grain " << id;
    EXPECT_EQ(f.velocities.at(id), s.velocity.at(id)) << "grain " << id;
  }
}

std::vector<hsize_t> dims_of(hid_t file, const char* name) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(set);
  return dims;
}

TEST(H5md, FramesReadBackBitExactInTheH5mdLayout) {
  const std::string path = testing::temp_path("h5md_frames.h5");
  Box box;
  const std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.3, 3, box);
  Engine engine(MPI_COMM_SELF, fcc_settings(box), grains);
  H5mdWriter writer(path);
  std::vector<Snapshot> written;
  writer.write(engine);
  written.push_back(snapshot(engine));
  engine.add_step_callback(25, [&](const Engine& e) {
    writer.write(e);
    written.push_back(snapshot(e));
  });
  engine.run(50);

  expect_frame_equals(read_h5md_frame(path, 0), written[0]);
  expect_frame_equals(read_h5md_frame(path, 25), written[1]);
  const DumpFrame last = read_h5md_frame(path);
  EXPECT_EQ(last.step, 50);
  expect_frame_equals(last, written[2]);
  EXPECT_TRUE(last.box.periodic[0] && last.box.periodic[1] && !last.box.periodic[2]);
  EXPECT_NEAR(last.box.hi.x, box.hi.x, 1e-12);

  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  for (const char* name : {"h5md/author", "h5md/creator", "particles/all/box/edges/value",
                           "particles/all/position/step", "particles/all/position/time",
                           "particles/all/velocity/step", "particles/all/species/value", "particles/all/id/value"})
    EXPECT_GT(H5Lexists(file, name, H5P_DEFAULT), 0) << name;
  const auto n = static_cast<hsize_t>(grains.size());
  EXPECT_EQ(dims_of(file, "particles/all/position/value"), (std::vector<hsize_t>{3, n, 3}));
  EXPECT_EQ(dims_of(file, "particles/all/species/value"), (std::vector<hsize_t>{3, n}));
  std::int32_t version[2] = {0, 0};
  const hid_t h5md = H5Gopen2(file, "h5md", H5P_DEFAULT);
  const hid_t attr = H5Aopen(h5md, "version", H5P_DEFAULT);
  H5Aread(attr, H5T_NATIVE_INT32, version);
  EXPECT_EQ(version[0], 1);
  EXPECT_EQ(version[1], 1);
  H5Aclose(attr);
  H5Gclose(h5md);
  H5Fclose(file);
  std::filesystem::remove(path);
}

TEST(H5md, TruncationThenAppendContinuesTheTrajectory) {
  const std::string path = testing::temp_path("h5md_truncate.h5");
  Box box;
  const std::vector<Grain> grains = testing::compressed_fcc(2, 0.01, 0.3, 4, box);
  Engine engine(MPI_COMM_SELF, fcc_settings(box), grains);
  {
    H5mdWriter writer(path);
    for (int k = 0; k < 4; ++k) {  // steps 0, 10, 20, 30
      if (k > 0) engine.run(10);
      writer.write(engine);
    }
  }
  EXPECT_EQ(truncate_h5md(path, 15), 2u);  // a checkpoint at step 15: frames 20 and 30 go
  EXPECT_EQ(read_h5md_frame(path).step, 10);
  H5mdWriter appender(path, true);
  appender.write(engine);
  EXPECT_EQ(read_h5md_frame(path).step, 30);
  expect_frame_equals(read_h5md_frame(path), snapshot(engine));
  EXPECT_THROW((void)read_h5md_frame(path, 20), std::runtime_error);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sedwave::forward::dem
