#include "sedwave/io/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sedwave::io {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::runtime_error("cannot " + what + " " + path.string() + ": " + std::strerror(errno));
}

/// Whether the descriptor still names the file at `path`: a holder removes the file before it
/// releases the lock, so a lock taken on a removed file guards nothing.
bool still_at(int descriptor, const std::filesystem::path& path) {
  struct stat held {}, named {};
  return ::fstat(descriptor, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
         held.st_ino == named.st_ino;
}

}  // namespace

FileLock::FileLock(std::filesystem::path path, const std::function<void()>& on_wait) : path_(std::move(path)) {
  bool told = false;
  for (;;) {
    descriptor_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (descriptor_ < 0) fail("create the lock file", path_);
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK) {
        ::close(descriptor_);
        fail("lock", path_);
      }
      if (!told && on_wait) on_wait();
      told = true;
      while (::flock(descriptor_, LOCK_EX) != 0) {
        if (errno != EINTR) {
          ::close(descriptor_);
          fail("lock", path_);
        }
      }
    }
    if (still_at(descriptor_, path_)) return;
    ::close(descriptor_);  // its holder removed it while we waited: lock the file now there
  }
}

FileLock::~FileLock() {
  ::unlink(path_.c_str());
  ::close(descriptor_);
}

}  // namespace sedwave::io
