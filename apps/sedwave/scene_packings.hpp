#pragma once
// The packings a scene's runs start from, shared by `sedwave forward` and `sedwave table`: the loose
// column (generated from the scene, or imported from LAMMPS), compressed and relaxed; for the linear
// engine's ensembles, member k uses the scene's seed + k.
#include <iosfwd>
#include <string>

#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/channel/scene.hpp"

namespace sedwave::app {

/// Ensemble member k's packing file: `path` itself for k = 0, else `path` with ".member<k>" inserted
/// before the extension (packing.h5 -> packing.member1.h5).
[[nodiscard]] std::string member_path(const std::string& path, int k);

/// Prepares member k (collective over MPI_COMM_WORLD; the result is on rank 0). Imported LAMMPS
/// packings have no seed: only member 0 exists for them.
[[nodiscard]] forward::channel::PreparedChannel prepare_member(const forward::channel::ChannelScene& scene, int k,
                                                               int rank, std::ostream* log);

}  // namespace sedwave::app
