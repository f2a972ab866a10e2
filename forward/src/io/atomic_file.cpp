#include "sedwave/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <system_error>

namespace sedwave::io {
namespace fs = std::filesystem;
namespace {

std::string system_error_text() { return std::strerror(errno); }

/// Same file: by identity when both exist, else by their normalised absolute paths.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(fs::absolute(a), ec) == fs::weakly_canonical(fs::absolute(b), ec);
}

}  // namespace

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  temporary_ = target_;
  temporary_ += ".tmp-" + std::to_string(::getpid());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  const int fd = ::open(temporary_.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error("cannot write " + target_.string() + ": " + system_error_text());
  const bool synced = ::fsync(fd) == 0;
  const std::string why = synced ? "" : system_error_text();
  ::close(fd);
  if (!synced) throw std::runtime_error("cannot write " + target_.string() + ": " + why);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    throw std::runtime_error("cannot write " + target_.string() + ": " + system_error_text());
  }
  committed_ = true;
}

void write_text_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(target);
  {
    std::ofstream out(file.temporary());
    if (!out) throw std::runtime_error("cannot write " + target.string() + ": " + system_error_text());
    out << std::setprecision(17);
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + target.string() + " (disk full or write error)");
    out.close();
    if (out.fail()) throw std::runtime_error("cannot write " + target.string() + " (disk full or write error)");
  }
  file.commit();
}

void refuse_overwriting_inputs(const std::vector<fs::path>& outputs, const std::vector<fs::path>& inputs,
                               const std::string& what) {
  for (const fs::path& out : outputs) {
    for (const fs::path& in : inputs) {
      if (same_file(out, in)) {
        throw std::invalid_argument(what + ": output " + out.string() + " would overwrite the input " + in.string() +
                                    "; choose another output path");
      }
    }
  }
}

void require_writable_location(const fs::path& path, const std::string& option) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::invalid_argument(option + " " + path.string() + ": cannot create directory " + dir.string() + ": " + ec.message());
  const fs::path probe = dir / (".sedwave-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw std::invalid_argument(option + " " + path.string() + ": cannot write in " + dir.string() + ": " + system_error_text());
  ::close(fd);
  fs::remove(probe, ec);
  if (fs::is_directory(path, ec)) throw std::invalid_argument(option + " " + path.string() + " is a directory; give a file name");
}

void flush_standard_output() {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    throw std::runtime_error(std::string("cannot write to standard output: ") + system_error_text());
  }
}

}  // namespace sedwave::io
