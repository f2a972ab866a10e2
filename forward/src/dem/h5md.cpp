// H5MD trajectory writer and reader (layout in h5md.hpp).
#include "sedwave/forward/dem/h5md.hpp"

#include <mpi.h>

#include <array>
#include <cstdlib>

#include "sedwave/io/hdf5.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr const char* kParticles = "particles/all";
/// Time-dependent elements of the particle group; the first owns the shared step and time series.
constexpr std::array<const char*, 7> kElements = {"position", "velocity", "id",  "species",
                                                  "radius",   "box/edges", "box/offset"};

/// A fixed-length string array attribute (H5MD's box boundary).
void write_strings_attribute(hid_t parent, const std::string& name, const std::array<std::string, 3>& values) {
  constexpr std::size_t kWidth = 9;  // "periodic" and its terminating zero
  io::Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  io::check(H5Tset_size(type, kWidth), "string size");
  const hsize_t n = values.size();
  io::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "attribute space");
  io::Handle attr(H5Acreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                  "create attribute " + name);
  std::string buffer(kWidth * values.size(), '\0');
  for (std::size_t k = 0; k < values.size(); ++k) buffer.replace(k * kWidth, values[k].size(), values[k]);
  io::check(H5Awrite(attr, type, buffer.data()), "write attribute " + name);
}

std::array<bool, 3> read_boundary(hid_t box) {
  io::Handle attr(H5Aopen(box, "boundary", H5P_DEFAULT), H5Aclose, "open attribute boundary");
  io::Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
  const std::size_t width = H5Tget_size(type);
  std::string buffer(3 * width, '\0');
  io::check(H5Aread(attr, type, buffer.data()), "read attribute boundary");
  return {buffer.compare(0, 8, "periodic") == 0, buffer.compare(width, 8, "periodic") == 0,
          buffer.compare(2 * width, 8, "periodic") == 0};
}

void create_layout(const std::string& path, const Engine& engine) {
  const auto n = static_cast<hsize_t>(engine.n_global());
  io::Handle file = io::create_file(path);
  {
    io::Handle h5md = io::create_group(file, "h5md");
    const std::array<std::int32_t, 2> version{1, 1};
    const hsize_t two = 2;
    io::Handle space(H5Screate_simple(1, &two, nullptr), H5Sclose, "version space");
    io::Handle attr(H5Acreate2(h5md, "version", H5T_NATIVE_INT32, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                    "create attribute version");
    io::check(H5Awrite(attr, H5T_NATIVE_INT32, version.data()), "write attribute version");
    io::Handle author = io::create_group(h5md, "author");
    const char* user = std::getenv("USER");
    io::write_string_attribute(author, "name", user ? user : "unknown");
    io::Handle creator = io::create_group(h5md, "creator");
    io::write_string_attribute(creator, "name", "sedwave");
    io::write_string_attribute(creator, "version", "dem engine");
  }
  io::Handle particles = io::create_group(file, "particles");
  io::Handle all = io::create_group(particles, "all");
  {
    io::Handle box = io::create_group(all, "box");
    io::write_attribute(box, "dimension", std::int32_t{3});
    std::array<std::string, 3> boundary;
    for (std::size_t a = 0; a < 3; ++a) boundary[a] = engine.domain().box().periodic[a] ? "periodic" : "none";
    write_strings_attribute(box, "boundary", boundary);
  }
  for (const char* element : kElements) io::create_group(all, element);
  io::create_extensible<std::int64_t>(all, "position/step", {});
  io::create_extensible<double>(all, "position/time", {});
  for (const char* element : kElements) {
    const std::string e = element;
    if (e != "position") {
      io::check(H5Lcreate_hard(all, "position/step", all, (e + "/step").c_str(), H5P_DEFAULT, H5P_DEFAULT), "link step");
      io::check(H5Lcreate_hard(all, "position/time", all, (e + "/time").c_str(), H5P_DEFAULT, H5P_DEFAULT), "link time");
    }
  }
  io::create_extensible<double>(all, "position/value", {n, 3});
  io::create_extensible<double>(all, "velocity/value", {n, 3});
  io::create_extensible<std::int64_t>(all, "id/value", {n});
  io::create_extensible<std::int32_t>(all, "species/value", {n});
  io::create_extensible<double>(all, "radius/value", {n});
  io::create_extensible<double>(all, "box/edges/value", {3});
  io::create_extensible<double>(all, "box/offset/value", {3});
}

/// Sets the number of frames of every series (the shared step and time once).
void set_frames(hid_t all, hsize_t frames) {
  io::set_frames(all, "position/step", frames);
  io::set_frames(all, "position/time", frames);
  for (const char* element : kElements) io::set_frames(all, std::string(element) + "/value", frames);
}

/// Rank 0's part of a frame: a new row in every series, with step, time and box.
void begin_frame(hid_t all, const Engine& engine) {
  const hsize_t frame = io::extent(all, "position/step")[0];
  set_frames(all, frame + 1);
  const std::int64_t step = engine.step_count();
  const double time = engine.time();
  io::write_block(all, "position/step", {frame}, {1}, &step);
  io::write_block(all, "position/time", {frame}, {1}, &time);
  const Box& box = engine.domain().box();
  const std::array<double, 3> edges{box.length(0), box.length(1), box.length(2)};
  io::write_block(all, "box/edges/value", {frame, 0}, {1, 3}, edges.data());
  io::write_block(all, "box/offset/value", {frame, 0}, {1, 3}, &box.lo.x);
}

/// This rank's grains into rows [first_row, first_row + n_local) of the last frame.
void write_rows(hid_t all, const Engine& engine, hsize_t first_row) {
  const GrainArrays& g = engine.grains();
  const hsize_t count = g.n_local();
  if (count == 0) return;
  const hsize_t frame = io::extent(all, "position/step")[0] - 1;
  // Vec3 is three contiguous doubles, so the arrays are written as they are.
  io::write_block(all, "position/value", {frame, first_row, 0}, {1, count, 3}, &g.position[0].x);
  io::write_block(all, "velocity/value", {frame, first_row, 0}, {1, count, 3}, &g.velocity[0].x);
  io::write_block(all, "id/value", {frame, first_row}, {1, count}, g.id.data());
  io::write_block(all, "species/value", {frame, first_row}, {1, count}, g.group.data());
  io::write_block(all, "radius/value", {frame, first_row}, {1, count}, g.radius.data());
}

}  // namespace

void H5mdWriter::write(const Engine& engine) {
  const Domain& domain = engine.domain();
  const MPI_Comm comm = domain.comm();
  const auto first_row = parallel::exclusive_prefix_sum(comm, static_cast<std::int64_t>(engine.n_local()));

  // Ranks write in turn, so no rank ever holds all grains; rank 0 goes first and adds the frame's
  // row to every series.
  try {
    parallel::in_turn(comm, [&] {
      if (domain.rank() == 0 && !started_) create_layout(path_, engine);
      io::Handle file = io::open_file(path_, true);
      io::Handle all = io::open_group(file, kParticles);
      if (domain.rank() == 0) begin_frame(all, engine);
      write_rows(all, engine, static_cast<hsize_t>(first_row));
    });
  } catch (const parallel::AgreedFailure& e) {  // every rank has it
    throw parallel::AgreedFailure(e, "H5MD trajectory " + path_ + ": " + e.what());
  }
  started_ = true;
}

std::size_t truncate_h5md(const std::string& path, std::int64_t last_step) {
  io::Handle file = io::open_file(path, true);
  io::Handle all = io::open_group(file, kParticles);
  const hsize_t frames = io::extent(all, "position/step")[0];
  const auto steps = io::read_block<std::int64_t>(all, "position/step", {0}, {frames});
  std::size_t kept = 0;
  while (kept < steps.size() && steps[kept] <= last_step) ++kept;
  set_frames(all, kept);
  return kept;
}

DumpFrame read_h5md_frame(const std::string& path, std::optional<std::int64_t> step) {
  io::Handle file = io::open_file(path);
  io::Handle all = io::open_group(file, kParticles);
  const hsize_t frames = io::extent(all, "position/step")[0];
  const auto steps = io::read_block<std::int64_t>(all, "position/step", {0}, {frames});
  hsize_t frame = frames;
  for (hsize_t k = 0; k < frames; ++k)
    if (!step || steps[k] == *step) frame = k;
  if (frame == frames)
    throw std::runtime_error(path + ": " + (step ? "no frame with step " + std::to_string(*step) : "no frame"));
  const hsize_t n = io::extent(all, "position/value")[1];
  DumpFrame f;
  f.step = steps[frame];
  io::Handle box = io::open_group(all, "box");
  f.box.periodic = read_boundary(box);
  const auto edges = io::read_block<double>(all, "box/edges/value", {frame, 0}, {1, 3});
  const auto offset = io::read_block<double>(all, "box/offset/value", {frame, 0}, {1, 3});
  for (int a = 0; a < 3; ++a) {
    const auto k = static_cast<std::size_t>(a);
    f.box.lo[a] = offset[k];
    f.box.hi[a] = offset[k] + edges[k];
  }
  const auto id = io::read_block<std::int64_t>(all, "id/value", {frame, 0}, {1, n});
  const auto x = io::read_block<double>(all, "position/value", {frame, 0, 0}, {1, n, 3});
  const auto v = io::read_block<double>(all, "velocity/value", {frame, 0, 0}, {1, n, 3});
  for (std::size_t k = 0; k < id.size(); ++k) {
    f.positions[id[k]] = {x[3 * k], x[3 * k + 1], x[3 * k + 2]};
    f.velocities[id[k]] = {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
  }
  return f;
}

}  // namespace sedwave::forward::dem
