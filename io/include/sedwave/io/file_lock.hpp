#pragma once
// An exclusive lock between processes, held on a lock file beside what it guards (flock(2), which
// shared filesystems such as NFS v4 and Lustre mounted with `flock` honour across hosts).
#include <filesystem>
#include <functional>

namespace sedwave::io {

class FileLock {
 public:
  /// Takes the lock of `path` (the lock file, created if absent), waiting while another process
  /// holds it; `on_wait` is called once before waiting. Throws std::runtime_error naming `path`
  /// where the file cannot be created or locked.
  explicit FileLock(std::filesystem::path path, const std::function<void()>& on_wait = {});
  /// Removes the lock file and releases the lock: a process that was waiting finds the file gone
  /// and locks a new one, so no lock file outlives its holder.
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
};

}  // namespace sedwave::io
