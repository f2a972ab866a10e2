#pragma once
// An exclusive lock between processes, held on a lock file beside what it guards (flock(2), which
// shared filesystems such as NFS v4 and Lustre mounted with `flock` honour across hosts).
#include <filesystem>
#include <functional>

namespace sedwave::io {

/// The lock file is created where absent and left in place (empty): removing it would let a process
/// that opened it before the removal lock a file no longer at the path, which attribute caches on
/// shared filesystems make impossible to rule out. The lock itself dies with its process, so a
/// killed run never leaves it held.
class FileLock {
 public:
  /// Takes the lock of `path`, waiting while another process holds it; `on_wait` is called once
  /// before waiting. Throws std::runtime_error naming `path` where it cannot be opened or locked.
  explicit FileLock(const std::filesystem::path& path, const std::function<void()>& on_wait = {});
  ~FileLock();  ///< releases the lock
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int descriptor_ = -1;
};

}  // namespace sedwave::io
