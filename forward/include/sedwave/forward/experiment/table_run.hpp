#pragma once
// Filling a dispersion table from a scene (`sedwave table`, docs/tables.md): the engine's packings
// (one for the time-domain engine, one per ensemble member for the linear engines), its point
// function, and the table's metadata, handed to the task farm (table/task_farm.hpp), which knows
// no engine.
#include <mpi.h>

#include <filesystem>
#include <iosfwd>
#include <string>

#include "sedwave/forward/experiment/scene.hpp"
#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/table/task_farm.hpp"

namespace sedwave::forward::experiment {

/// Runs `scene` with `engine` instead of its own (an override from the command line; any engine,
/// the long-wavelength limit included). Throws std::invalid_argument naming the scene when that
/// engine cannot run the scene.
void use_table_engine(ChannelScene& scene, EngineKind engine);

struct TableRun {
  std::filesystem::path table;  ///< the table file, created or resumed
  /// Packing file (member k: member_path): reused where it exists, else the prepared packing is
  /// saved there so that a restart skips the preparation; empty: prepare, save nothing.
  std::string packing;
  EngineKind engine = EngineKind::time_domain;
  int member = -1;              ///< >= 0: this linear ensemble member alone (a member table)
  std::ostream* log = nullptr;       ///< preparation progress (rank 0), or nullptr
  std::ostream* warnings = nullptr;  ///< what the table cannot say itself (rank 0), or nullptr
};

/// The ranks that compute one point together: the grid's for the time-domain engine, 1 for the
/// linear ones (their solves are serial; every rank holds every member).
[[nodiscard]] int ranks_per_point(const table::TableGridFile& grid, EngineKind engine);

/// Fills (or resumes) run.table on `grid` from `scene` with `farm` (its ranks_per_point is
/// replaced by ranks_per_point(grid, run.engine)). Collective over MPI_COMM_WORLD.
[[nodiscard]] table::FarmReport fill_table(const table::TableGridFile& grid, const ChannelScene& scene,
                                           const TableRun& run, table::FarmSettings farm);

}  // namespace sedwave::forward::experiment
