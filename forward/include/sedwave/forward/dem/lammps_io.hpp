#pragma once
// LAMMPS interoperability: data files (atom_style sphere), text dumps (read and write).
//
// Data file: header lines "N atoms", "xlo xhi" etc., then "Atoms # sphere" with lines
//   id type diameter density x y z [ix iy iz]
// and optionally "Velocities" with lines "id vx vy vz wx wy wz". The atom type becomes
// Grain::group; the mass is density * pi d^3 / 6 (units.hpp: grain_mass).
// Dumps: "ITEM: TIMESTEP / NUMBER OF ATOMS / BOX BOUNDS / ATOMS id type radius x y z vx vy vz",
// which OVITO and ParaView read directly.
//
// Numbers are written with 17 significant digits, so a file read back gives the same doubles bit
// for bit (restarts from data files and comparisons of final states rely on it). Malformed input
// throws std::runtime_error naming the file and line: "packing.data:12: bad Atoms line ...".
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::dem {

class Engine;

struct LammpsData {
  Box box;  ///< periodic flags are left at the Box defaults (the data file does not state them)
  std::vector<Grain> grains;
};

/// Reads a data file on the ranks of `comm` together, no rank holding it whole (collective): rank 0
/// reads the header and tells the others; each rank parses the lines that start in its share of the
/// bytes after the header (line numbers counted per share and summed over the ranks before); each
/// atom and velocity line goes to rank id mod size, which joins them. Every rank returns the box and
/// its grains in file order; the engine then sends each grain to its slab's owner. A malformed file
/// fails on every rank with the message a serial read gives (its first error in file order).
[[nodiscard]] LammpsData read_lammps_data(MPI_Comm comm, const std::string& path);
/// Reads a data file on this rank alone (MPI_COMM_SELF); `keep` picks the grains returned.
[[nodiscard]] LammpsData read_lammps_data(const std::string& path,
                                          const std::function<bool(const Grain&)>& keep = {});
/// Writes a data file (atom_style sphere) with velocities, whose grains are spread over the ranks of
/// `comm` in file order (collective): rank 0 writes, taking one rank's grains at a time, so no rank
/// holds them all; `box` as rank 0 holds it. The atom type is Grain::group, and groups below 1 are
/// written as type 1 (LAMMPS types start at 1), so groups 0 and 1 merge: channel packings, whose
/// flow group is 0, go through experiment::write_packing_lammps_data, which shifts every group by one.
void write_lammps_data(MPI_Comm comm, const std::string& path, const Box& box, std::span<const Grain> grains);
/// The same on this rank alone (MPI_COMM_SELF), all grains given.
void write_lammps_data(const std::string& path, const Box& box, std::span<const Grain> grains);

struct DumpFrame {
  std::int64_t step = 0;
  Box box;  ///< bounds and periodic flags (pp / anything else) of the frame
  std::unordered_map<std::int64_t, Vec3> positions;   ///< by id
  std::unordered_map<std::int64_t, Vec3> velocities;  ///< by id; empty without vx vy vz columns
};
/// Reads the frame with the given step (default: the last) of a text dump with id, x, y, z
/// columns (or xs ys zs scaled columns), and vx vy vz when present.
[[nodiscard]] DumpFrame read_lammps_dump(const std::string& path, std::optional<std::int64_t> step = {});

/// Cuts a dump after its last complete frame with step <= last_step (serial). A restart calls it
/// before appending: frames written after the checkpoint by an interrupted run are written again,
/// and a frame cut short by SIGKILL is dropped. Returns the number of frames kept.
std::size_t truncate_lammps_dump(const std::string& path, std::int64_t last_step);

/// Appends LAMMPS-style text dump frames (collective: ranks append their grains in turn).
class LammpsDumpWriter {
 public:
  /// append = false: the first write replaces any existing file; true: frames are added to it
  /// (after truncate_lammps_dump on a restart).
  explicit LammpsDumpWriter(std::string path, bool append = false)
      : path_(std::move(path)), started_(append) {}
  void write(const Engine& engine);

 private:
  std::string path_;
  bool started_ = false;
};

}  // namespace sedwave::forward::dem
