#include "journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace sedwave::forward::table {
namespace {

constexpr std::string_view kHeader =
    "# sedwave table journal v1: i_gamma i_omega omega_hat gamma_hat status alpha_hat c_hat sigma_alpha_hat "
    "sigma_c_hat wall_seconds reason\n";
constexpr std::size_t kNumberFields = 10;

std::string system_error(const std::string& what, const std::filesystem::path& path) {
  return what + " " + path.string() + ": " + std::strerror(errno);
}

void append_number(std::string& line, double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  line.append(buffer, end);
  line += ' ';
}

std::string format(const JournalEntry& e) {
  std::string line = std::to_string(e.index.i_gamma) + ' ' + std::to_string(e.index.i_omega) + ' ';
  append_number(line, e.omega_hat);
  append_number(line, e.gamma_hat);
  line += to_string(e.result.status);
  line += ' ';
  for (const double v : {e.result.alpha_hat, e.result.c_hat, e.result.sigma_alpha_hat, e.result.sigma_c_hat,
                         e.result.wall_seconds}) {
    append_number(line, v);
  }
  for (const char ch : e.result.reason) line += (ch == '\n' || ch == '\r') ? ' ' : ch;
  line += '\n';
  return line;
}

PointStatus parse_status(std::string_view text) {
  for (const PointStatus s : {PointStatus::missing, PointStatus::ok, PointStatus::unresolved, PointStatus::failed}) {
    if (text == to_string(s)) return s;
  }
  throw std::invalid_argument("unknown status '" + std::string(text) + "'");
}

template <typename T>
T parse_number(std::string_view text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument("not a number: '" + std::string(text) + "'");
  }
  return value;
}

JournalEntry parse(std::string_view line) {
  std::vector<std::string_view> fields;
  while (fields.size() < kNumberFields) {
    const std::size_t space = line.find(' ');
    if (space == std::string_view::npos) throw std::invalid_argument("too few fields");
    fields.push_back(line.substr(0, space));
    line.remove_prefix(space + 1);
  }
  JournalEntry e;
  e.index = {parse_number<std::size_t>(fields[0]), parse_number<std::size_t>(fields[1])};
  e.omega_hat = parse_number<double>(fields[2]);
  e.gamma_hat = parse_number<double>(fields[3]);
  e.result.status = parse_status(fields[4]);
  e.result.alpha_hat = parse_number<double>(fields[5]);
  e.result.c_hat = parse_number<double>(fields[6]);
  e.result.sigma_alpha_hat = parse_number<double>(fields[7]);
  e.result.sigma_c_hat = parse_number<double>(fields[8]);
  e.result.wall_seconds = parse_number<double>(fields[9]);
  e.result.reason = std::string(line);
  return e;
}

void write_fully(int descriptor, std::string_view data, const std::filesystem::path& path) {
  while (!data.empty()) {
    const ssize_t written = ::write(descriptor, data.data(), data.size());
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) throw std::runtime_error(system_error("cannot append to journal", path));
    data.remove_prefix(static_cast<std::size_t>(written));
  }
}

}  // namespace

Journal::Journal(std::filesystem::path path) : path_(std::move(path)) {
  const bool is_new = !std::filesystem::exists(path_);
  descriptor_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0) throw std::runtime_error(system_error("cannot open journal", path_));
  if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
    const std::string message = system_error("another process is writing this table: cannot lock journal", path_);
    ::close(descriptor_);
    throw std::runtime_error(message);
  }
  if (is_new) write_fully(descriptor_, kHeader, path_);
}

Journal::Journal(Journal&& other) noexcept
    : path_(std::move(other.path_)), descriptor_(std::exchange(other.descriptor_, -1)) {}

Journal& Journal::operator=(Journal&& other) noexcept {
  std::swap(path_, other.path_);
  std::swap(descriptor_, other.descriptor_);
  return *this;
}

Journal::~Journal() {
  if (descriptor_ >= 0) ::close(descriptor_);
}

void Journal::append(const JournalEntry& entry) {
  // One write() per line: an interrupted append leaves at most one partial last line, which has
  // no newline and is ignored on reading. fsync makes the line outlive a power cut too.
  write_fully(descriptor_, format(entry), path_);
  if (::fsync(descriptor_) != 0) throw std::runtime_error(system_error("cannot fsync journal", path_));
}

std::vector<JournalEntry> Journal::read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<JournalEntry> entries;
  std::size_t start = 0;
  for (std::size_t line_number = 1;; ++line_number) {
    const std::size_t newline = text.find('\n', start);
    if (newline == std::string::npos) break;  // no newline: an interrupted append, ignored
    const std::string_view line(text.data() + start, newline - start);
    start = newline + 1;
    if (line.empty() || line.front() == '#') continue;
    try {
      entries.push_back(parse(line));
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": " + error.what());
    }
  }
  return entries;
}

}  // namespace sedwave::forward::table
