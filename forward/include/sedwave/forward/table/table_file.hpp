#pragma once
// Dispersion tables on disk (format: docs/tables.md). A task farm writes each point as soon as it is
// finished and a restarted run asks which points are done:
//
//   auto file = TableFile::resume_or_create("table.h5", grid, metadata);
//   for (GridIndex p : still_to_do(file.finished_points())) file.write_point(p, compute(p));
//
// Crash safety. HDF5 1.10 without SWMR gives no guarantee for a file whose writer dies mid-write, so
// the file is not the only record: write_point first appends the point to a text journal beside it
// (TableFile::journal_path: one line per point, written with a single write() and fsync()ed), and
// only then writes it into the HDF5 file (values, then status, each followed by H5Fflush). Opening
// replays the journal into the file. Hence every point whose write_point returned survives a
// SIGKILL (and, being fsynced, a power cut); a point interrupted mid-call is either fully present or
// absent. The HDF5 file is created complete under a temporary name and renamed into place, and later
// writes touch only raw data preallocated at creation, so a crash cannot leave it half-created, and
// if it is damaged anyway resume_or_create moves it aside and rebuilds it from the journal.
//
// Not thread-safe, and one writer per file (HDF5 locks the file while it is open for writing).
//
// Units: as table.hpp (dimensionless; wall times in seconds).
#include <filesystem>
#include <memory>
#include <vector>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table {

/// Throws std::runtime_error naming `path` and what it is if a file there exists and is not a
/// dispersion table at all (not HDF5, or HDF5 whose 'format' attribute names something else): a
/// mistyped path, never to be rebuilt over. A table, damaged or not, or no file passes.
void require_table_or_nothing(const std::filesystem::path& path);

class TableFile {
 public:
  /// A new table with every point missing. Throws std::runtime_error if `path` or its journal
  /// already exists (finished points are never overwritten by accident: use resume_or_create).
  [[nodiscard]] static TableFile create(const std::filesystem::path& path, const TableGrid& grid,
                                        TableMetadata metadata);
  /// An existing table, for writing more points; replays the journal first.
  [[nodiscard]] static TableFile open(const std::filesystem::path& path);
  /// For a restarted run: open() if the file exists (it must hold the same grid, scene and engine,
  /// and unless `allow_changed_inputs` the same packing hash and sedwave version), create()
  /// otherwise. A journal from the killed run is replayed either way; an HDF5 file that cannot be
  /// read is renamed to PATH.corrupt and rebuilt from grid, metadata and journal.
  [[nodiscard]] static TableFile resume_or_create(const std::filesystem::path& path, const TableGrid& grid,
                                                  const TableMetadata& metadata, bool allow_changed_inputs = false);

  TableFile(TableFile&&) noexcept;
  TableFile& operator=(TableFile&&) noexcept;
  TableFile(const TableFile&) = delete;
  TableFile& operator=(const TableFile&) = delete;
  ~TableFile();

  /// Records one finished point (journal, then HDF5). A point may be written again (e.g. a retry
  /// of a failed one); the last write wins. Writing PointStatus::missing is an error.
  void write_point(GridIndex index, const PointResult& result);
  /// Points whose status is not missing, in row-major order.
  [[nodiscard]] std::vector<GridIndex> finished_points() const;
  /// Everything written so far (an in-memory mirror of the file).
  [[nodiscard]] const DispersionTable& table() const;
  [[nodiscard]] const std::filesystem::path& path() const;

  /// PATH.journal: the append-only record of finished points.
  [[nodiscard]] static std::filesystem::path journal_path(const std::filesystem::path& table_path);

 private:
  struct State;
  explicit TableFile(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// Reads a table (read-only), including points that are in its journal but not yet in the file.
[[nodiscard]] DispersionTable read_table(const std::filesystem::path& path);

/// Writes a complete table in one go (create + every finished point).
void write_table(const std::filesystem::path& path, const DispersionTable& table);

}  // namespace sedwave::forward::table
