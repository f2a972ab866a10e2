#include "sedwave/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <random>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

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

/// Whether `p` lies in /proc, where links such as /proc/self/fd/1 name open descriptors ("pipe:[…]")
/// rather than paths.
bool inside_proc(const fs::path& p) {
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(fs::absolute(p).parent_path(), ec);
  if (ec) return false;
  const auto first = ++dir.begin();
  return first != dir.end() && *first == "proc";
}

/// The path symbolic links lead to (the link's own target for a dangling one: writing creates it).
/// Sets `descriptor` when the chain reaches a link in /proc (/dev/stdout, /dev/fd/N).
fs::path follow_links(const fs::path& target, bool& descriptor) {
  fs::path p = target;
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(p, ec)) return p;
    if (inside_proc(p)) {
      descriptor = true;
      return p;
    }
    if (hops == 40) throw std::invalid_argument(target.string() + ": too many levels of symbolic links");
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) throw std::invalid_argument("cannot read the symbolic link " + p.string() + ": " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
}

std::string this_host() {
  char name[HOST_NAME_MAX + 1] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "host";
  std::string host;
  for (const char* c = name; *c; ++c) {
    const bool plain = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '.';
    host += plain ? *c : '_';  // '-' separates the fields of a temporary name
  }
  return host.empty() ? "host" : host;
}

/// A temporary of `target` named TARGET.tmp-HOST-PID-RANDOM (or TARGET.tmp-PID, the older form):
/// its host and process, or nothing if `name` is not one.
struct TemporaryOwner {
  std::string host;  ///< empty for the older form (always this host)
  long pid = 0;
};
bool parse_temporary(const std::string& name, const std::string& prefix, TemporaryOwner& owner) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return false;
  const std::string rest = name.substr(prefix.size());
  const auto all_digits = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos && s.size() < 10;
  };
  if (all_digits(rest)) {
    owner = {"", std::stol(rest)};
    return true;
  }
  const std::size_t random_dash = rest.rfind('-');
  if (random_dash == std::string::npos || random_dash == 0) return false;
  const std::size_t pid_dash = rest.rfind('-', random_dash - 1);
  if (pid_dash == std::string::npos || pid_dash == 0) return false;
  const std::string pid = rest.substr(pid_dash + 1, random_dash - pid_dash - 1);
  if (!all_digits(pid) || rest.size() - random_dash - 1 != 8) return false;
  owner = {rest.substr(0, pid_dash), std::stol(pid)};
  return true;
}

/// Removes temporaries of `target` that no running write can still own: on this host, those whose
/// process has ended; from another host (a shared filesystem), those untouched for a day (no write
/// takes that long, and their process cannot be asked).
void remove_stale_temporaries(const fs::path& target, const std::string& host) {
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    TemporaryOwner owner;
    if (!parse_temporary(it->path().filename().string(), prefix, owner)) continue;
    std::error_code status_ec;
    if (!fs::is_regular_file(fs::symlink_status(it->path(), status_ec))) continue;
    bool stale = false;
    if (owner.host.empty() || owner.host == host) {
      stale = owner.pid != ::getpid() && ::kill(static_cast<pid_t>(owner.pid), 0) != 0 && errno == ESRCH;
    } else {
      const auto age = fs::file_time_type::clock::now() - fs::last_write_time(it->path(), status_ec);
      stale = !status_ec && age > std::chrono::hours(24);
    }
    if (stale) fs::remove(it->path(), status_ec);
  }
}

/// Creates a new, empty temporary beside `target` (O_EXCL: never an existing file, never shared).
fs::path create_temporary(const fs::path& target) {
  static const std::string host = this_host();
  remove_stale_temporaries(target, host);
  std::random_device entropy;
  std::mt19937_64 random(entropy() ^ (static_cast<std::uint64_t>(::getpid()) << 32));
  for (int attempt = 0; attempt < 100; ++attempt) {
    char suffix[9];
    std::snprintf(suffix, sizeof suffix, "%08x", static_cast<unsigned>(random() & 0xffffffffU));
    fs::path temporary = target;
    temporary += ".tmp-" + host + "-" + std::to_string(::getpid()) + "-" + suffix;
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return temporary;
    }
    if (errno != EEXIST) throw std::runtime_error("cannot write " + target.string() + ": " + system_error_text());
  }
  throw std::runtime_error("cannot write " + target.string() + ": no unused temporary name beside it");
}

/// Writes `bytes` to a stream target (a device, FIFO or descriptor) in place.
void write_in_place(const fs::path& target, const std::string& bytes) {
  // O_APPEND: a descriptor that is a regular file (`--out /dev/stdout >> log`) keeps what it has.
  const int fd = ::open(target.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot write " + target.string() + ": " + system_error_text());
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? system_error_text() : "nothing written";
      ::close(fd);
      throw std::runtime_error("cannot write " + target.string() + ": " + why);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw std::runtime_error("cannot write " + target.string() + ": " + system_error_text());
}

std::string render(const std::function<void(std::ostream&)>& write) {
  std::ostringstream text;
  text << std::setprecision(17);
  write(text);
  return std::move(text).str();
}

std::invalid_argument unseekable(const fs::path& target, const ResolvedOutput& resolved, const std::string& format) {
  return std::invalid_argument("cannot write " + format + " to " + target.string() + ": it is " + resolved.description +
                               ", and " + format + " files must be seekable; give a regular file");
}

/// The temporaries a live DeferredCommits keeps, in the order they were committed.
struct Deferred {
  std::mutex mutex;
  bool active = false;
  std::vector<std::pair<fs::path, fs::path>> kept;  ///< (temporary, target)
};
Deferred& deferred() {
  static Deferred d;
  return d;
}

void rename_into_place(const fs::path& temporary, const fs::path& target) {
  // Checked again just before the rename: something may have been put at the target meanwhile.
  struct stat st {};
  if (::lstat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    throw std::runtime_error("cannot write " + target.string() + ": it is no longer a regular file");
  }
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    throw std::runtime_error("cannot write " + target.string() + ": " + system_error_text());
  }
}

}  // namespace

DeferredCommits::DeferredCommits() {
  const std::lock_guard<std::mutex> lock(deferred().mutex);
  if (deferred().active) throw std::logic_error("DeferredCommits: one is already alive");
  deferred().active = true;
  deferred().kept.clear();
}

DeferredCommits::~DeferredCommits() {
  const std::lock_guard<std::mutex> lock(deferred().mutex);
  for (const auto& [temporary, target] : deferred().kept) {
    std::error_code ec;
    fs::remove(temporary, ec);
  }
  deferred().kept.clear();
  deferred().active = false;
}

void DeferredCommits::commit_all() {
  const std::lock_guard<std::mutex> lock(deferred().mutex);
  auto& kept = deferred().kept;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    rename_into_place(kept[i].first, kept[i].second);
    kept[i].first.clear();  // renamed: nothing to remove
  }
  kept.clear();
  deferred().active = false;  // what the run writes after (its plots, from these files) lands at once
}

namespace {

/// The lock on `lock_file`, said on stderr while waiting for it; `output` (what `option` names) in messages.
FileLock output_lock(const fs::path& lock_file, const fs::path& output, const std::string& option) {
  try {
    return FileLock(lock_file, [&] {
      std::fprintf(stderr, "sedwave: %s %s: another sedwave run is writing there; waiting for it to finish\n",
                   option.c_str(), output.c_str());
    });
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(option + " " + output.string() + ": " + e.what());
  }
}

FileLock directory_lock(const fs::path& directory, const std::string& option) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  return output_lock(directory / ".sedwave.lock", directory, option);
}

fs::path lock_beside(const fs::path& file) {
  std::string name = ".";  // appended, not concatenated: GCC 12 warns falsely (-Wrestrict) on "." + std::string
  name.append(file.filename().string()).append(".lock");
  fs::path lock = file;
  return lock.replace_filename(name);
}

}  // namespace

OutputLock::OutputLock(const fs::path& directory, const std::string& option) : lock_(directory_lock(directory, option)) {}

OutputFileLock::OutputFileLock(const fs::path& file, const std::string& option)
    : lock_(output_lock(lock_beside(file), file, option)) {}

ResolvedOutput resolve_output(const fs::path& target) {
  bool descriptor = false;
  const fs::path resolved = follow_links(target, descriptor);
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) {
    // ENOTDIR (a parent that is a file): left to the directory check, which names that parent.
    if ((errno == ENOENT || errno == ENOTDIR) && !descriptor) return {resolved, OutputKind::file, "a new file"};
    throw std::invalid_argument("cannot write " + target.string() + ": " + system_error_text());
  }
  if (S_ISDIR(st.st_mode)) throw std::invalid_argument(target.string() + " is a directory; give a file name");
  if (S_ISBLK(st.st_mode)) {
    throw std::invalid_argument("cannot write " + target.string() + ": it is a block device (sedwave writes regular "
                                "files, character devices and FIFOs only)");
  }
  if (S_ISSOCK(st.st_mode)) throw std::invalid_argument("cannot write " + target.string() + ": it is a socket");
  if (descriptor) return {target, OutputKind::stream, "an open descriptor"};
  if (S_ISCHR(st.st_mode)) return {target, OutputKind::stream, "a character device"};
  if (S_ISFIFO(st.st_mode)) return {target, OutputKind::stream, "a FIFO"};
  return {resolved, OutputKind::file, "a regular file"};
}

AtomicFile::AtomicFile(fs::path target) {
  const ResolvedOutput resolved = resolve_output(target);
  if (resolved.kind != OutputKind::file) {
    throw std::invalid_argument("cannot replace " + target.string() + ": it is " + resolved.description +
                                " (only a regular file is ever replaced)");
  }
  target_ = resolved.path;
  temporary_ = create_temporary(target_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot write " + target_.string() + ": " + system_error_text());
  const bool synced = ::fsync(fd) == 0;
  const std::string why = synced ? "" : system_error_text();
  ::close(fd);
  if (!synced) throw std::runtime_error("cannot write " + target_.string() + ": " + why);
  {
    const std::lock_guard<std::mutex> lock(deferred().mutex);
    if (deferred().active) {
      deferred().kept.emplace_back(temporary_, target_);  // renamed, or removed, with the others
      committed_ = true;
      return;
    }
  }
  rename_into_place(temporary_, target_);
  committed_ = true;
}

namespace {
void replace_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(target);
  {
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
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
}  // namespace

void write_text_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  const ResolvedOutput resolved = resolve_output(target);
  if (resolved.kind == OutputKind::stream) {
    write_in_place(resolved.path, render(write));
    return;
  }
  replace_atomically(target, write);
}

void write_seekable_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write,
                               const std::string& format) {
  require_seekable_output(target, format);
  replace_atomically(target, write);
}

void require_seekable_output(const fs::path& target, const std::string& format) {
  const ResolvedOutput resolved = resolve_output(target);
  if (resolved.kind != OutputKind::file) throw unseekable(target, resolved, format);
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

void require_writable_location(const fs::path& path, const std::string& option, OutputFormat format) {
  // "run/" names a directory even before it exists: refused now, not after the run has created it.
  if (!path.has_filename())
    throw std::invalid_argument(option + " " + path.string() + ": names a directory; give a file name");
  ResolvedOutput resolved;
  try {
    resolved = resolve_output(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(option + " " + e.what());
  }
  if (resolved.kind == OutputKind::stream) {
    if (format == OutputFormat::seekable) {
      throw std::invalid_argument(option + ": " + unseekable(path, resolved, "HDF5").what());
    }
    return;  // written in place: nothing is created beside it
  }
  const fs::path& file = resolved.path;
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::invalid_argument(option + " " + path.string() + ": cannot create directory " + dir.string() + ": " + ec.message());
  try {
    fs::remove(create_temporary(dir / ".sedwave-write-test"), ec);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(option + " " + path.string() + ": cannot write in " + dir.string() + " (" +
                                e.what() + ")");
  }
}

void flush_standard_output() {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    throw std::runtime_error(std::string("cannot write to standard output: ") + system_error_text());
  }
}

}  // namespace sedwave::io
