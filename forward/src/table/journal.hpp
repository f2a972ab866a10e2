#pragma once
// Private: the append-only text journal beside a table file. One line per finished point,
//   i_gamma i_omega omega_hat gamma_hat status alpha_hat c_hat sigma_alpha_hat sigma_c_hat wall_seconds reason
// numbers in shortest round-trip form (std::to_chars), so replaying restores every value bit for bit.
// Each line goes out in one write() followed by fsync(); a line without its newline is the remnant of
// a write that was interrupted, so readers ignore it.
#include <filesystem>
#include <vector>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table {

struct JournalEntry {
  GridIndex index;
  double omega_hat = 0.0;  ///< the grid values, so replay can tell a journal of another grid
  double gamma_hat = 0.0;
  PointResult result;
};

class Journal {
 public:
  /// Opens `path` for appending; creates it with a header line if it does not exist. Holds an
  /// exclusive lock on it while alive (the table's writer lock): throws std::runtime_error if
  /// another writer has it.
  explicit Journal(std::filesystem::path path);
  Journal(Journal&& other) noexcept;
  Journal& operator=(Journal&& other) noexcept;
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;
  ~Journal();

  /// Appends one entry durably (write + fsync); throws std::runtime_error on failure.
  void append(const JournalEntry& entry);

  /// Complete entries of the journal at `path` in file order (empty if there is none). Throws
  /// std::runtime_error naming the line for a complete line that does not parse.
  [[nodiscard]] static std::vector<JournalEntry> read(const std::filesystem::path& path);

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
};

}  // namespace sedwave::forward::table
