#pragma once
// The packings a scene's runs start from, for every command that runs a scene (`sedwave forward`,
// `sedwave table`): the loose column (generated from the scene, or imported from LAMMPS),
// compressed and relaxed, or a packing file written earlier; for the linear engine's ensembles,
// member k uses the scene's seed + k and its own file (member_path). A packing is spread over the
// ranks in id order (rank 0's grains first; a column prepared without tiling is all on rank 0):
// read, saved, fingerprinted and tiled with no rank holding it whole.
#include <mpi.h>

#include <iosfwd>
#include <string>
#include <vector>

#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/experiment/scene.hpp"

namespace sedwave::forward::experiment {

/// `grains` (spread over the ranks of `comm` in any way) spread in id order (collective): rank r
/// holds the r-th of equal ranges of ids between the smallest and the largest, sorted, so that the
/// ranks' grains in rank order are the packing sorted by id, as its file and fingerprint take them.
[[nodiscard]] std::vector<dem::Grain> spread_by_id(MPI_Comm comm, const std::vector<dem::Grain>& grains);

/// Ensemble member k's packing file: `path` itself for k = 0, else `path` with ".member<k>" inserted
/// before the extension (packing.h5 -> packing.member1.h5).
[[nodiscard]] std::string member_path(const std::string& path, int k);

/// Prepares member k (collective over MPI_COMM_WORLD; a tiled channel spread in id order, an untiled
/// column on rank 0): the linear
/// engine's Newton relaxation finishes frictionless packings. Imported LAMMPS packings have no
/// seed: only member 0 exists for them.
[[nodiscard]] channel::PreparedChannel prepare_member(const ChannelScene& scene, int k, int rank, std::ostream* log);

/// Where a member's packing comes from, and where a prepared one goes. Paths name member 0's file
/// (member_path gives member k's); empty: none.
struct PackingFiles {
  std::string read;  ///< read the member from here instead of preparing it
  std::string save;  ///< save a prepared member here (HDF5, and its LAMMPS twin .data)
  /// A resumable run's files: member k is read from `path` where its file exists, else prepared and
  /// saved there, so that a restart skips the preparation.
  [[nodiscard]] static PackingFiles reuse(const std::string& path) { return {path, path}; }
  /// Whether these are reuse()'s: read where the file exists, else prepare and save.
  [[nodiscard]] bool reuse() const { return !read.empty() && read == save; }
};

/// A member's packing and where it came from.
struct ScenePacking {
  /// Spread over MPI_COMM_WORLD: in id order (tiled), in file order (read), or on rank 0 (a column
  /// prepared whole).
  channel::PreparedChannel channel;
  bool prepared = false;             ///< prepared now (else read from a file)
  std::string provenance;            ///< in words, for a table's definitions
};

/// Member k's packing, read or prepared (collectively over MPI_COMM_WORLD, logging to `log`) and saved
/// as `files` say. While it prepares and saves a packing, rank 0 holds the lock of SAVE.lock beside
/// it (io::FileLock): another run saving to the same path waits for it, and another reusing it
/// (PackingFiles::reuse) then reads the saved file.
[[nodiscard]] ScenePacking scene_packing(const ChannelScene& scene, int k, const PackingFiles& files,
                                         std::ostream* log);

/// Copies the packing (spread over `world` in rank order) into every group of ranks_per_point ranks,
/// spread over the group's ranks: rank q of each group holds the grains of world ranks q, q + p,
/// q + 2p, ... (p = ranks_per_point). So with one group every rank keeps its own grains, and with
/// ranks_per_point = 1 every rank holds the whole packing, as the linear engines need; the
/// time-domain engine takes grains on any rank of its group. The box goes to every rank. Collective
/// over `world`.
void share_packing_with_groups(MPI_Comm world, channel::PreparedChannel& packing, int ranks_per_point);

}  // namespace sedwave::forward::experiment
