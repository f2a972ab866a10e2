#pragma once
// An MPI task farm that fills a dispersion table point by point (docs/tables.md, "The task farm").
//
// Ranks form groups of ranks_per_point (MPI_Comm_split); each group computes one grid point at a
// time, collectively over the group communicator. Work is handed out dynamically by a one-sided
// counter on rank 0 (MPI_Fetch_and_op): a group leader that is free takes the next unfinished point,
// so fast and slow points balance themselves and no rank idles as a dedicated master. Rank 0 is the
// only writer: group leaders send each result to rank 0, which writes it with TableFile::write_point
// (journal + HDF5, crash-safe) as soon as it is free to receive it, i.e. between its own points.
// A killed run restarted with the same arguments resumes the file (TableFile::resume_or_create) and
// hands out only the points that are not finished.
//
// The farm knows no engine: the point function is injected, an engine's for real tables
// (experiment/time_domain_points.hpp, experiment/linear_points.hpp), a theory for fast tests of the
// farm itself.
//
// Units: dimensionless (table.hpp); wall times in seconds.
#include <mpi.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table {

/// Computes one grid point, collectively over `group` (every rank of the group calls it with the
/// same arguments; the result of the group's rank 0 is the one kept). Exceptions become failed
/// points; the farm measures wall_seconds itself.
using PointFunction = std::function<PointResult(MPI_Comm group, double omega_hat, double gamma_hat)>;

struct FarmSettings {
  int ranks_per_point = 1;
  std::ostream* log = nullptr;  ///< one progress line per finished point (rank 0), or nullptr
  /// Resuming: compute failed points again (an exception may have been transient, e.g. memory).
  /// Unresolved points are kept: the scene cannot resolve them, and would not on a second try.
  bool retry_failed = false;
  /// Resuming: accept a table whose packing hash or sedwave version differs from this run's.
  bool allow_changed_inputs = false;
};

struct FarmReport {
  std::size_t points = 0;           ///< grid points
  std::size_t already_finished = 0; ///< found finished in the file (resumed run)
  std::size_t computed = 0;         ///< computed by this run
  std::size_t ok = 0, unresolved = 0, failed = 0;  ///< of those computed by this run
  double wall_seconds = 0.0;        ///< of the whole farm, on rank 0
  double point_seconds = 0.0;       ///< sum of the computed points' wall times
};

/// Fills `table_path` (created, or resumed if it exists: same grid, scene and engine required).
/// Collective over `world`; the size of `world` must be a multiple of ranks_per_point. The report
/// is complete on rank 0 (other ranks: their own share).
FarmReport run_task_farm(MPI_Comm world, const std::filesystem::path& table_path, const TableGrid& grid,
                         const TableMetadata& metadata, const PointFunction& compute, const FarmSettings& settings);

/// A measurement as a table point: unresolved with `problem` when that is not empty, or when alpha
/// is not significantly positive (alpha < 2 sigma: the channel is too short to measure so weak an
/// attenuation, and storing the noise would mislead the interpolation); ok otherwise.
[[nodiscard]] PointResult point_from_measurement(const std::string& problem, double alpha, double sigma_alpha,
                                                 double c, double sigma_c, double wall_seconds);

}  // namespace sedwave::forward::table
