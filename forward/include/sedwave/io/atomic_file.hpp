#pragma once
// Outputs that never destroy what was there before: every file sedwave writes is first written to
// a temporary file beside its target, flushed to disk, checked for write errors, and only then
// renamed over the target (rename(2) within one directory is atomic). A run killed mid-write, or a
// full disk, leaves the previous file intact and an error, never a truncated file and exit 0.
//
// Also: outputs that would overwrite one of the run's inputs are refused before any work starts.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace sedwave::io {

/// A temporary file that becomes `target` on commit(); removed if never committed.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Where to write (a sibling of the target named TARGET.tmp-PID).
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// fsyncs the temporary file and renames it over the target. Throws std::runtime_error naming the
  /// target if either fails (the target is then untouched).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

/// Writes a text file atomically: `write` fills the stream; any stream error (a full disk, say)
/// throws std::runtime_error naming the file, and the old file stays.
void write_text_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

/// Throws std::invalid_argument if any output names the same file as any input (by identity for
/// existing files, by normalised path otherwise). `what` names the command in the message.
void refuse_overwriting_inputs(const std::vector<std::filesystem::path>& outputs,
                               const std::vector<std::filesystem::path>& inputs, const std::string& what);

/// Throws std::invalid_argument unless a file can be created in `path`'s directory (created if
/// missing) — checked before a long run, so a typo in --out does not cost the run.
void require_writable_location(const std::filesystem::path& path, const std::string& option);

/// Flushes standard output and throws std::runtime_error if anything written to it was lost
/// (`sedwave theory > /dev/full` must not exit 0).
void flush_standard_output();

}  // namespace sedwave::io
