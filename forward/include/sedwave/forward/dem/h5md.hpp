#pragma once
// H5MD trajectories ("HDF5 for molecular data", https://www.nongnu.org/h5md/, version 1.1): one
// binary file holding every frame, read by OVITO, MDAnalysis, VMD (plugin) and h5py.
//
// Layout (N grains, n frames; every time-dependent element has step [n], time [n], value; the
// step and time datasets are shared by hard links, as H5MD allows):
//   /h5md                    version = {1, 1}; author/name, creator/name, creator/version
//   /particles/all/box       dimension = 3, boundary = "periodic" | "none" per axis
//        edges/value [n][3]  box lengths; offset/value [n][3]: the lower corner
//   /particles/all/position/value [n][N][3], velocity/value [n][N][3]
//   /particles/all/id/value [n][N] (int64), species/value [n][N] (int32, the LAMMPS atom type),
//   /particles/all/radius/value [n][N] (not an H5MD name: grains need it to be drawn)
// Row k of a frame is not the same grain in every frame (ranks write their own grains in turn, so
// no rank holds them all): match rows through id.
//
// HDF5 files are not journaled: a process killed while it writes a frame can leave the file
// unreadable. The writer opens the file only while it writes a frame, which keeps that window short.
#include <cstdint>
#include <optional>
#include <string>

#include "sedwave/forward/dem/lammps_io.hpp"

namespace sedwave::forward::dem {

class Engine;

/// Appends H5MD frames (collective; use as a step callback).
class H5mdWriter {
 public:
  /// append = false: the first write creates (replaces) the file; true: frames are added to an
  /// existing trajectory (after truncate_h5md on a restart).
  explicit H5mdWriter(std::string path, bool append = false) : path_(std::move(path)), started_(append) {}
  void write(const Engine& engine);

 private:
  std::string path_;
  bool started_ = false;
};

/// Drops the frames after the last one with step <= last_step (serial); returns the frames kept.
/// A restart calls it so the trajectory continues as an uninterrupted run would have written it.
std::size_t truncate_h5md(const std::string& path, std::int64_t last_step);

/// Reads the frame with the given step (default: the last): box, positions and velocities by id.
[[nodiscard]] DumpFrame read_h5md_frame(const std::string& path, std::optional<std::int64_t> step = {});

}  // namespace sedwave::forward::dem
