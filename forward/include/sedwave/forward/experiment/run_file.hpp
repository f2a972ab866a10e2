#pragma once
// Files of the channel workflow (HDF5; every dataset and attribute carries its units):
//  * a packing file: the prepared, static packing (grains at full precision, box, preparation
//    report), reusable by later runs and tables; a LAMMPS data file is written beside it;
//  * a run file: scene text, packing statistics, layer time series and the measured results.
// Layouts are listed in docs/scenes.md. Serial: call on the rank that holds the grains (rank 0).
#include <filesystem>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/experiment/scene.hpp"

namespace sedwave::forward::experiment {

/// Writes PATH (HDF5) and PATH with extension .data (LAMMPS atom_style sphere, types = groups + 1).
void write_packing(const std::filesystem::path& path, const channel::PreparedChannel& packing,
                   const std::string& scene_text);
/// Writes the packing as a LAMMPS data file (atom_style sphere): type 1 flow grains, 2 the lower
/// (driven) wall, 3 the upper wall.
void write_packing_lammps_data(const std::filesystem::path& path, const channel::PreparedChannel& packing);
/// Reads a packing written by write_packing (grains, box, report statistics).
[[nodiscard]] channel::PreparedChannel read_packing(const std::filesystem::path& path);
/// A hash (io::Fingerprint, 16 hex digits) of a packing's grains and box, bit for bit: the same for
/// a packing as prepared and as read back from its file, different for any other packing.
[[nodiscard]] std::string packing_fingerprint(const channel::PreparedChannel& packing);

/// Writes the run file, atomically (temporary file + rename).
void write_run_file(const std::filesystem::path& path, const ChannelScene& scene,
                    const channel::PreparationReport& preparation, const channel::AcousticResult& result);

}  // namespace sedwave::forward::experiment
