#pragma once
// A strict reader for one TOML table, shared by the scene, grid-file and site-file parsers.
// Typed reads with defaults; every mistake is an `Error` (the caller's exception type) reading
// "FILE:LINE: key 'a.b': why" (toml11 records where each value was read); keys nobody asked for
// are errors too, so a misspelt key never silently falls back to a default.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <toml.hpp>
#include <utility>

#include "sedwave/io/range.hpp"

namespace sedwave::io {

/// The file toml11 read `v` from, or `origin` when it does not know (text parsed from a string).
inline std::string file_of(const toml::value& v, const std::string& origin) {
  const std::string file = v.location().file_name();
  return file.empty() || file == "unknown file" ? origin : file;
}

/// "FILE:LINE" of value `v`.
inline std::string where(const toml::value& v, const std::string& origin) {
  return file_of(v, origin) + ":" + std::to_string(v.location().line());
}

/// Throws Error("FILE:LINE: key 'KEY': WHY") for value `v`.
template <class Error>
[[noreturn]] void fail(const toml::value& v, const std::string& key, const std::string& why, const std::string& origin) {
  throw Error(where(v, origin) + ": key '" + key + "': " + why);
}

/// The text `v` was written as in its file ("99999999999999999999", which toml11 reads as the
/// largest 64-bit integer), or "" when toml11 does not know it (a value built in code).
inline std::string written_text(const toml::value& v) {
  const toml::source_location at = v.location();
  if (at.column() < 1 || at.column() - 1 + at.region() > at.line_str().size()) return "";
  return at.line_str().substr(at.column() - 1, at.region());
}

/// Whether toml11 read `v` as an integer other than the one written (it saturates a decimal integer
/// beyond 64 bits at the type's limits).
inline bool integer_overflowed(const toml::value& v) {
  if (!v.is_integer()) return false;
  std::string digits;
  for (const char c : written_text(v)) {
    if (c != '_' && c != '+') digits += c;
  }
  const bool decimal = digits.find_first_of("xob") == std::string::npos;
  return decimal && !digits.empty() && digits != std::to_string(v.as_integer());
}

/// Throws Error("FILE:LINE: key 'KEY' = VALUE: accepted range RANGE") for value `v`, VALUE as written.
template <class Error>
[[noreturn]] void fail_range(const toml::value& v, const std::string& key, const Range& range, const std::string& origin) {
  const std::string text = written_text(v);
  const std::string value = v.is_integer() ? (text.empty() ? std::to_string(v.as_integer()) : text)
                            : v.is_floating() ? shortest(v.as_floating())
                                              : toml::format(v);
  throw Error(where(v, origin) + ": key '" + key + "' = " + value + ": accepted range " + range.describe());
}

/// A whole file as text (kept verbatim in outputs for provenance); `what` names it in the error.
template <class Error>
std::string read_text(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Arrays and inline tables nested deeper than this are refused before parsing: toml11 descends
/// one call per level, and a deep enough file would overflow the stack. No scene needs more than 2.
inline constexpr int kMaxTomlNesting = 64;
/// Lines longer than this are refused before parsing: toml11 scans a value's whole line for its
/// comments, so one line of n values costs n^2 (40 000 probes on one line: seconds). Arrays may
/// run over several lines, which parse in linear time.
inline constexpr std::size_t kMaxTomlLine = 65536;

/// What makes `text` unfit for toml11, as "LINE: why" (LINE 1-based), or "" when nothing does: arrays
/// and inline tables nested deeper than kMaxTomlNesting, or a line longer than kMaxTomlLine. A
/// linear scan that skips strings and comments; brackets in table headers count like any other.
inline std::string toml_shape_problem(const std::string& text) {
  std::size_t line = 1, line_start = 0;
  int depth = 0;
  const auto too_long = [&](std::size_t end) { return end - line_start > kMaxTomlLine; };
  const auto long_line = [&] {
    return std::to_string(line) + ": syntax error: a line longer than " + std::to_string(kMaxTomlLine) +
           " characters (break a long array over several lines: TOML allows newlines between its values)";
  };
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '\n') {
      if (too_long(k)) return long_line();
      ++line;
      line_start = k + 1;
    } else if (c == '#') {
      while (k + 1 < text.size() && text[k + 1] != '\n') ++k;
    } else if (c == '"' || c == '\'') {
      const bool multiline = text.compare(k, 3, std::string(3, c)) == 0;
      const std::string close = multiline ? std::string(3, c) : std::string(1, c);
      for (k += close.size(); k < text.size() && text.compare(k, close.size(), close) != 0; ++k) {
        if (text[k] == '\n') {
          if (too_long(k)) return long_line();
          ++line;
          line_start = k + 1;
        }
        if (c == '"' && text[k] == '\\') ++k;  // an escape: the next character never closes the string
      }
      k += close.size() - 1;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxTomlNesting) {
        return std::to_string(line) + ": syntax error: arrays or inline tables nested deeper than " +
               std::to_string(kMaxTomlNesting) + " levels";
      }
    } else if (c == ']' || c == '}') {
      depth = std::max(depth - 1, 0);
    }
  }
  return too_long(text.size()) ? long_line() : "";
}

/// Parses TOML text; a syntax error becomes Error("ORIGIN:LINE: syntax error: <toml11's message>").
template <class Error>
toml::value parse(const std::string& text, const std::string& origin) {
  if (const std::string problem = toml_shape_problem(text); !problem.empty()) throw Error(origin + ":" + problem);
  try {
    std::istringstream stream(text);
    return toml::parse(stream, origin);
  } catch (const toml::exception& e) {
    // toml11's message shows the offending lines; the prefix gives the usual FILE:LINE form.
    throw Error(origin + ":" + std::to_string(e.location().line()) + ": syntax error: " + e.what());
  }
}

template <class Error>
class Table {
 public:
  /// `prefix` names the table in messages ("" for the root); `origin` names the text in messages
  /// when toml11 does not know its file.
  Table(const toml::value& table, std::string prefix, std::string origin)
      : table_(table), prefix_(std::move(prefix)), origin_(std::move(origin)) {
    if (!table_.is_table()) fail<Error>(table_, prefix_, "must be a table", origin_);
  }

  /// Rejects keys outside `allowed` at once, before anything is read: "unknown key" says more about a
  /// misspelling than the "missing" error its correctly spelt twin would otherwise give.
  void allow_only(const std::set<std::string>& allowed) const {
    for (const auto& [key, v] : table_.as_table()) {
      if (!allowed.count(key)) fail<Error>(v, name(key), "unknown key (misspelt?)", origin_);
    }
  }
  /// Rejects keys that no read asked for.
  void finish() const {
    for (const auto& [key, v] : table_.as_table()) {
      if (!used_.count(key)) fail<Error>(v, name(key), "unknown key (misspelt?)", origin_);
    }
  }

  [[nodiscard]] bool has(const std::string& key) const { return table_.as_table().count(key) > 0; }
  [[nodiscard]] std::string name(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  [[nodiscard]] const std::string& origin() const { return origin_; }

  /// A required key.
  const toml::value& at(const std::string& key) {
    used_.insert(key);
    if (!has(key)) {
      throw Error(file_of(table_, origin_) + ":" + std::to_string(table_.location().line()) + ": key '" + name(key) +
                  "': missing (required)");
    }
    return table_.as_table().at(key);
  }

  double number(const std::string& key, double fallback, const Range& range = {}) {
    return has(key) ? number_value(at(key), name(key), range) : skip(key, fallback);
  }
  std::optional<double> optional_number(const std::string& key, const Range& range = {}) {
    if (!has(key)) return skip(key, std::optional<double>{});
    return number_value(at(key), name(key), range);
  }
  double positive(const std::string& key, double fallback, std::string unit = "") {
    return number(key, fallback, Range::positive(unit));
  }
  double required_positive(const std::string& key) { return number_value(at(key), name(key), Range::positive()); }
  /// An integer within `range` that also fits T (a value T cannot hold is an error, never truncated).
  template <typename T = std::int64_t>
  T integer(const std::string& key, T fallback, Range range = {}) {
    if (!has(key)) return skip(key, fallback);
    const toml::value& v = at(key);
    if (!v.is_integer()) fail<Error>(v, name(key), "must be an integer", origin_);
    range.low = std::max(range.low, static_cast<double>(std::numeric_limits<T>::min()));
    range.high = std::min(range.high, static_cast<double>(std::numeric_limits<T>::max()));
    const std::int64_t x = v.as_integer();
    const bool fits = !integer_overflowed(v) && std::in_range<T>(x) && range.contains(static_cast<double>(x));
    if (!fits) fail_range<Error>(v, name(key), range, origin_);
    return static_cast<T>(x);
  }
  std::string text(const std::string& key, const std::string& fallback) {
    if (!has(key)) return skip(key, fallback);
    const toml::value& v = at(key);
    if (!v.is_string()) fail<Error>(v, name(key), "must be a string", origin_);
    return v.as_string();
  }
  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return skip(key, fallback);
    const toml::value& v = at(key);
    if (!v.is_boolean()) fail<Error>(v, name(key), "must be true or false", origin_);
    return v.as_boolean();
  }
  std::string choice(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed) {
    const std::string s = text(key, fallback);
    if (!allowed.count(s)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail<Error>(table_.at(key), name(key), "must be one of " + list, origin_);
    }
    return s;
  }
  /// A sub-table (an empty one when absent).
  Table sub(const std::string& key) {
    static const toml::value empty = toml::table{};
    return Table(has(key) ? at(key) : skip(key, std::cref(empty)).get(), name(key), origin_);
  }

  /// A number, checked finite and within `range`.
  [[nodiscard]] double number_value(const toml::value& v, const std::string& key, const Range& range = {}) const {
    double x = 0.0;
    if (integer_overflowed(v)) {
      fail<Error>(v, key, written_text(v) + " does not fit a 64-bit integer (a number: write 1e20, not 100000000000000000000)",
                  origin_);
    } else if (v.is_integer()) {
      x = static_cast<double>(v.as_integer());
    } else if (v.is_floating()) {
      x = v.as_floating();
    } else {
      fail<Error>(v, key, "must be a number", origin_);
    }
    if (!std::isfinite(x)) fail<Error>(v, key, "must be finite", origin_);
    if (!range.contains(x)) fail_range<Error>(v, key, range, origin_);
    return x;
  }

  /// An error about one key's value, at its line (at the table's line when the key is absent and
  /// its default is what fails).
  [[noreturn]] void fail_key(const std::string& key, const std::string& why) const {
    if (has(key)) fail<Error>(table_.as_table().at(key), name(key), why, origin_);
    fail_table("'" + key + "' (default): " + why);
  }

  /// An error about the table as a whole (conflicting or missing keys).
  [[noreturn]] void fail_table(const std::string& why) const {
    throw Error(file_of(table_, origin_) + ":" + std::to_string(table_.location().line()) + ": [" + prefix_ + "]: " + why);
  }

 private:
  template <typename T>
  T skip(const std::string& key, T fallback) {
    used_.insert(key);
    return fallback;
  }

  const toml::value& table_;
  std::string prefix_;
  std::string origin_;
  std::set<std::string> used_;
};

}  // namespace sedwave::io
