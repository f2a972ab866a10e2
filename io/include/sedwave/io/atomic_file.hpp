#pragma once
// Outputs that never destroy what was there before: every file sedwave writes is first written to
// a temporary file beside its target, flushed to disk, checked for write errors, and only then
// renamed over the target (rename(2) within one directory is atomic). A run killed mid-write, or a
// full disk, leaves the previous file intact and an error, never a truncated file and exit 0.
//
// Symbolic links are followed first: the file a link names is replaced, never the link. Only a
// regular file (or nothing) is ever renamed over. A character device, a FIFO or an open descriptor
// (/dev/null, a named pipe, /dev/stdout) is written in place for text outputs and refused for
// HDF5 outputs, which must seek; a directory, a block device or a socket is refused.
//
// Temporary names are TARGET.tmp-HOST-PID-RANDOM, created with O_EXCL: unique across processes and
// hosts sharing a filesystem. Those left by a killed run are removed by the next write of the same
// target: on this host when their process is gone, from another host when older than a day.
//
// Also: outputs that would overwrite one of the run's inputs are refused before any work starts.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "sedwave/io/file_lock.hpp"

namespace sedwave::io {

/// What writing to a path means once symbolic links are followed.
enum class OutputKind {
  file,    ///< nothing there yet, or a regular file: written beside it and renamed over it
  stream,  ///< a character device, a FIFO or an open descriptor: written in place, never renamed over
};

/// A path ready for writing: `path` is the file symbolic links lead to (what gets replaced).
struct ResolvedOutput {
  std::filesystem::path path;
  OutputKind kind = OutputKind::file;
  std::string description;  ///< "a character device", "a FIFO", ... (for messages)
};

/// Follows symbolic links and classifies the target. Throws std::invalid_argument naming `target`
/// for a directory, a block device, a socket or a loop of links.
[[nodiscard]] ResolvedOutput resolve_output(const std::filesystem::path& target);

/// A temporary file that becomes `target` on commit(); removed if never committed.
class AtomicFile {
 public:
  /// Throws std::invalid_argument unless `target` (links followed) is a regular file or nothing.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Where to write (a sibling of the resolved target named TARGET.tmp-HOST-PID-RANDOM; it exists).
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }
  /// The file that commit() replaces: the target with symbolic links followed.
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// fsyncs the temporary file and renames it over the target. Throws std::runtime_error naming the
  /// target if either fails (the target is then untouched).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

/// All of a run's outputs or none: while one is alive, every AtomicFile::commit() in this process
/// fsyncs its temporary and keeps it; commit_all() then renames them all into place, one after the
/// other, and a run that fails before (the destructor without commit_all) removes them, leaving the
/// previous outputs as they were. Outputs written in place (devices, FIFOs) are not deferred.
class DeferredCommits {
 public:
  DeferredCommits();
  DeferredCommits(const DeferredCommits&) = delete;
  DeferredCommits& operator=(const DeferredCommits&) = delete;
  ~DeferredCommits();
  /// Renames every kept temporary over its target, in order, and ends the deferral: later commits
  /// rename at once. Throws std::runtime_error naming the first that fails.
  void commit_all();
};

/// An exclusive lock on an output directory (a FileLock on `.sedwave.lock` in it): two runs
/// writing to one --out would interleave their outputs. When another process holds it, says so on
/// stderr (naming `option` and the directory) and waits for it; released on destruction or process
/// exit (a killed run never leaves it held). Throws std::runtime_error if the lock cannot be taken.
class OutputLock {
 public:
  OutputLock(const std::filesystem::path& directory, const std::string& option);

 private:
  FileLock lock_;
};

/// An exclusive lock on one output file (a FileLock on `.NAME.lock` beside it), for a command whose
/// output is a single file: two runs writing it would each report success and leave the last one's.
/// Waits and says so as OutputLock does; its directory must exist.
class OutputFileLock {
 public:
  OutputFileLock(const std::filesystem::path& file, const std::string& option);

 private:
  FileLock lock_;
};

/// Writes a text file atomically: `write` fills the stream; any stream error (a full disk, say)
/// throws std::runtime_error naming the file, and the old file stays. A device, FIFO or open
/// descriptor is written in place.
void write_text_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

/// As write_text_atomically for a format readers must seek in (`format`, e.g. "HDF5"): a device,
/// FIFO or descriptor is refused with std::invalid_argument before `write` runs.
void write_seekable_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write,
                               const std::string& format);

/// Throws std::invalid_argument naming `target` unless it is a regular file or nothing (links
/// followed): for files written in place by a format that must seek (HDF5).
void require_seekable_output(const std::filesystem::path& target, const std::string& format);

/// Throws std::invalid_argument if any output names the same file as any input (by identity for
/// existing files, by normalised path otherwise). `what` names the command in the message.
void refuse_overwriting_inputs(const std::vector<std::filesystem::path>& outputs,
                               const std::vector<std::filesystem::path>& inputs, const std::string& what);

/// Whether an output may be a stream (a device, FIFO or descriptor) or must be a seekable file.
enum class OutputFormat { text, seekable };

/// Throws std::invalid_argument unless a file can be created in `path`'s directory (created if
/// missing) — checked before a long run, so a typo in --out does not cost the run. A stream is
/// accepted for text and refused for a seekable format; a directory is refused.
void require_writable_location(const std::filesystem::path& path, const std::string& option,
                               OutputFormat format = OutputFormat::text);

/// Flushes standard output and throws std::runtime_error if anything written to it was lost
/// (`sedwave theory > /dev/full` must not exit 0).
void flush_standard_output();

}  // namespace sedwave::io
