#include "sedwave/io/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sedwave::io {

FileLock::FileLock(const std::filesystem::path& path, const std::function<void()>& on_wait) {
  // Read-only and world-writable before the umask: flock needs no write access, and another user
  // sharing the folder can then open the file and wait for the lock instead of failing.
  descriptor_ = ::open(path.c_str(), O_RDONLY | O_CREAT | O_CLOEXEC, 0666);
  if (descriptor_ < 0) throw std::runtime_error("cannot open the lock file " + path.string() + ": " + std::strerror(errno));
  int status = ::flock(descriptor_, LOCK_EX | LOCK_NB);
  int error = errno;
  if (status != 0 && error == EWOULDBLOCK) {
    try {
      if (on_wait) on_wait();
    } catch (...) {
      ::close(descriptor_);
      throw;
    }
    do {
      status = ::flock(descriptor_, LOCK_EX);
      error = errno;
    } while (status != 0 && error == EINTR);
  }
  if (status != 0) {
    ::close(descriptor_);
    throw std::runtime_error("cannot lock " + path.string() + ": " + std::strerror(error));
  }
}

FileLock::~FileLock() { ::close(descriptor_); }

}  // namespace sedwave::io
