#pragma once
// LAMMPS interoperability: data files (atom_style sphere), text dumps (read and write).
//
// Data file: header lines "N atoms", "xlo xhi" etc., then "Atoms # sphere" with lines
//   id type diameter density x y z [ix iy iz]
// and optionally "Velocities" with lines "id vx vy vz wx wy wz". The atom type becomes
// Grain::group; the mass is density * pi d^3 / 6 (units.hpp: grain_mass).
// Dumps: "ITEM: TIMESTEP / NUMBER OF ATOMS / BOX BOUNDS / ATOMS id type radius x y z vx vy vz",
// which OVITO and ParaView read directly.
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

/// Reads a data file. `keep` filters grains while reading (e.g. each rank its own share), so no
/// rank needs to hold all grains.
[[nodiscard]] LammpsData read_lammps_data(const std::string& path,
                                          const std::function<bool(const Grain&)>& keep = {});
/// Writes a data file (atom_style sphere) with velocities; serial (one rank, all grains given).
void write_lammps_data(const std::string& path, const Box& box, std::span<const Grain> grains);

struct DumpFrame {
  std::int64_t step = 0;
  Box box;
  std::unordered_map<std::int64_t, Vec3> positions;  ///< by id
};
/// Reads the frame with the given step (default: the last) of a text dump with id, x, y, z
/// columns (or xs ys zs scaled columns).
[[nodiscard]] DumpFrame read_lammps_dump(const std::string& path, std::optional<std::int64_t> step = {});

/// Appends LAMMPS-style text dump frames (collective: ranks append their grains in turn).
class LammpsDumpWriter {
 public:
  explicit LammpsDumpWriter(std::string path) : path_(std::move(path)) {}
  void write(const Engine& engine);

 private:
  std::string path_;
  bool started_ = false;
};

}  // namespace sedwave::forward::dem
