#pragma once
// Files of the channel workflow (HDF5; every dataset and attribute carries its units):
//  * a packing file: the prepared, static packing (grains at full precision, box, preparation
//    report), reusable by later runs and tables; a LAMMPS data file is written beside it;
//  * a run file: scene text, packing statistics, layer time series and the measured results.
// Layouts are listed in docs/scenes.md. The packing's functions take a communicator over which the
// grains are spread, in file order (rank 0's first), and no rank holds them all: rank 0 writes a
// file taking the others' grains a chunk at a time, or every rank writes pieces (PackingPieces).
// Without one: this rank alone, all grains given.
#include <mpi.h>

#include <cstdint>
#include <filesystem>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/experiment/scene.hpp"

namespace sedwave::forward::experiment {

/// When a packing file is written in pieces (dem/pieces.hpp), and how large they are.
struct PackingPieces {
  /// Up to this many grains, one file, built in rank 0's memory (56 B per grain, twice while its
  /// image is copied out: 112 MiB at most) from every rank's grains in turn.
  std::int64_t whole_rows = std::int64_t{1} << 20;
  /// Beyond: every rank writes its grains in piece files of at most this many, PATH joining them.
  std::int64_t piece_rows = std::int64_t{1} << 18;
};

/// Writes PATH (HDF5) and PATH with extension .data (LAMMPS atom_style sphere, types = groups + 1);
/// collective. Each file is replaced atomically, the HDF5 file first; a failure on any rank throws on
/// every rank, leaving the old file where it struck (a failed twin: the new .h5 beside the old
/// .data; a failed .h5 in pieces: the new pieces, removed by the next write).
void write_packing(MPI_Comm comm, const std::filesystem::path& path, const channel::PreparedChannel& packing,
                   const std::string& scene_text, PackingPieces pieces = {});
void write_packing(const std::filesystem::path& path, const channel::PreparedChannel& packing,
                   const std::string& scene_text);
/// Writes the packing as a LAMMPS data file (atom_style sphere): type 1 flow grains, 2 the lower
/// (driven) wall, 3 the upper wall; collective.
void write_packing_lammps_data(MPI_Comm comm, const std::filesystem::path& path,
                               const channel::PreparedChannel& packing);
void write_packing_lammps_data(const std::filesystem::path& path, const channel::PreparedChannel& packing);
/// Reads a packing written by write_packing (grains, box, report statistics); collective: each rank
/// reads an equal share of the rows, in file order. Refused, naming it, where a piece is missing.
[[nodiscard]] channel::PreparedChannel read_packing(MPI_Comm comm, const std::filesystem::path& path);
[[nodiscard]] channel::PreparedChannel read_packing(const std::filesystem::path& path);
/// A hash (io::Fingerprint, 16 hex digits) of a packing's grains (in rank order) and box, bit for
/// bit: the same for a packing as prepared and as read back from its file, on any number of ranks;
/// different for any other packing. Collective; the hash on every rank.
[[nodiscard]] std::string packing_fingerprint(MPI_Comm comm, const channel::PreparedChannel& packing);
[[nodiscard]] std::string packing_fingerprint(const channel::PreparedChannel& packing);

/// Writes the run file, atomically (temporary file + rename).
void write_run_file(const std::filesystem::path& path, const ChannelScene& scene,
                    const channel::PreparationReport& preparation, const channel::AcousticResult& result);

}  // namespace sedwave::forward::experiment
