#pragma once
// A strict reader for one TOML table, shared by the scene and grid-file parsers (private header).
// Typed reads with defaults; every mistake is an `Error` (the caller's exception type) reading
// "FILE:LINE: key 'a.b': why" (toml11 records where each value was read); keys nobody asked for
// are errors too, so a misspelt key never silently falls back to a default.
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

namespace sedwave::forward::toml_io {

/// The file toml11 read `v` from, or `origin` when it does not know (text parsed from a string).
inline std::string file_of(const toml::value& v, const std::string& origin) {
  const std::string file = v.location().file_name();
  return file.empty() || file == "unknown file" ? origin : file;
}

/// Throws Error("FILE:LINE: key 'KEY': WHY") for value `v`.
template <class Error>
[[noreturn]] void fail(const toml::value& v, const std::string& key, const std::string& why, const std::string& origin) {
  throw Error(file_of(v, origin) + ":" + std::to_string(v.location().line()) + ": key '" + key + "': " + why);
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

/// Parses TOML text; a syntax error becomes Error("ORIGIN:LINE: syntax error: <toml11's message>").
template <class Error>
toml::value parse(const std::string& text, const std::string& origin) {
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

  double number(const std::string& key, double fallback) { return has(key) ? number_value(at(key), name(key)) : skip(key, fallback); }
  std::optional<double> optional_number(const std::string& key) {
    if (!has(key)) return skip(key, std::optional<double>{});
    return number_value(at(key), name(key));
  }
  double positive(const std::string& key, double fallback) { return has(key) ? positive_value(at(key), name(key)) : skip(key, fallback); }
  double required_positive(const std::string& key) { return positive_value(at(key), name(key)); }
  std::int64_t integer(const std::string& key, std::int64_t fallback,
                       std::int64_t minimum = std::numeric_limits<std::int64_t>::min()) {
    if (!has(key)) return skip(key, fallback);
    const toml::value& v = at(key);
    if (!v.is_integer()) fail<Error>(v, name(key), "must be an integer", origin_);
    if (v.as_integer() < minimum) fail<Error>(v, name(key), "must be at least " + std::to_string(minimum), origin_);
    return v.as_integer();
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

  /// A number, checked finite.
  [[nodiscard]] double number_value(const toml::value& v, const std::string& key) const {
    double x = 0.0;
    if (v.is_integer()) {
      x = static_cast<double>(v.as_integer());
    } else if (v.is_floating()) {
      x = v.as_floating();
    } else {
      fail<Error>(v, key, "must be a number", origin_);
    }
    if (!std::isfinite(x)) fail<Error>(v, key, "must be finite", origin_);
    return x;
  }
  [[nodiscard]] double positive_value(const toml::value& v, const std::string& key) const {
    const double x = number_value(v, key);
    if (!(x > 0.0)) fail<Error>(v, key, "must be positive and finite", origin_);
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

}  // namespace sedwave::forward::toml_io
