#include "sedwave/forward/table/grid_file.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <toml.hpp>

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::table {
namespace {

/// "FILE:LINE: key 'KEY': WHY" for value `v` (toml11 records where each value was read).
[[noreturn]] void fail(const toml::value& v, const std::string& key, const std::string& why,
                       const std::string& origin) {
  const toml::source_location loc = v.location();
  const std::string file = loc.file_name().empty() || loc.file_name() == "unknown file" ? origin : loc.file_name();
  throw GridFileError(file + ":" + std::to_string(loc.line()) + ": key '" + key + "': " + why);
}

/// Reads one table's keys; keys it does not know are errors (a misspelt key must not be silently
/// ignored).
class Keys {
 public:
  /// Rejects any key not in `allowed` at once, before reading any: "unknown key" says more about a
  /// misspelling than the "missing" error its correctly spelt twin would otherwise give.
  Keys(const toml::value& table, std::string prefix, std::string origin, const std::set<std::string>& allowed)
      : table_(table), prefix_(std::move(prefix)), origin_(std::move(origin)) {
    for (const auto& [key, v] : table_.as_table()) {
      if (!allowed.count(key)) fail(v, name(key), "unknown key (misspelt?)", origin_);
    }
  }

  [[nodiscard]] bool has(const std::string& key) const { return table_.as_table().count(key) > 0; }
  [[nodiscard]] std::string name(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

  const toml::value& at(const std::string& key) {
    if (!has(key)) {
      throw GridFileError(origin_ + ":" + std::to_string(table_.location().line()) + ": key '" + name(key) +
                          "': missing (required)");
    }
    return table_.as_table().at(key);
  }

  [[nodiscard]] double positive_number(const std::string& key) {
    const toml::value& v = at(key);
    return positive(v, name(key));
  }

  [[nodiscard]] double positive(const toml::value& v, const std::string& key) const {
    double x = 0.0;
    if (v.is_integer()) x = static_cast<double>(v.as_integer());
    else if (v.is_floating()) x = v.as_floating();
    else fail(v, key, "must be a number", origin_);
    if (!std::isfinite(x) || !(x > 0.0)) fail(v, key, "must be positive and finite", origin_);
    return x;
  }

  [[nodiscard]] std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t minimum) {
    if (!has(key)) return fallback;
    const toml::value& v = at(key);
    if (!v.is_integer()) fail(v, name(key), "must be an integer", origin_);
    if (v.as_integer() < minimum) fail(v, name(key), "must be at least " + std::to_string(minimum), origin_);
    return v.as_integer();
  }

  [[nodiscard]] const std::string& origin() const { return origin_; }

 private:
  const toml::value& table_;
  std::string prefix_;
  std::string origin_;
};

/// An explicit list: positive numbers, strictly ascending (descending when `descending`).
std::vector<double> number_list(const toml::value& v, const std::string& key, const Keys& keys, bool descending,
                                double upper_bound_exclusive = INFINITY) {
  if (!v.is_array()) fail(v, key, "must be a list of numbers", keys.origin());
  const toml::array& array = v.as_array();
  if (array.empty()) fail(v, key, "must not be empty", keys.origin());
  std::vector<double> values;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string element = key + "[" + std::to_string(i) + "]";
    const double x = keys.positive(array[i], element);
    if (!(x < upper_bound_exclusive)) {
      std::ostringstream bound;
      bound << "must be below " << upper_bound_exclusive;
      fail(array[i], element, bound.str(), keys.origin());
    }
    if (!values.empty() && (descending ? !(x < values.back()) : !(x > values.back()))) {
      fail(array[i], element, descending ? "must be strictly descending" : "must be strictly ascending", keys.origin());
    }
    values.push_back(x);
  }
  return values;
}

/// An axis: an explicit list [a, b, ...] or a table { from, to, points } (log-spaced).
std::vector<double> axis(const toml::value& v, const std::string& key, const Keys& parent) {
  if (v.is_array()) return number_list(v, key, parent, false);
  if (!v.is_table()) fail(v, key, "must be a list of values or a table { from, to, points }", parent.origin());
  Keys range(v, key, parent.origin(), {"from", "to", "points"});
  const double from = range.positive_number("from");
  const double to = range.positive_number("to");
  if (!(to > from)) fail(range.at("to"), range.name("to"), "must be greater than 'from'", parent.origin());
  const std::int64_t points = range.integer("points", 0, 2);
  if (points == 0) range.at("points");  // missing: throws naming the key
  return log_spaced(from, to, static_cast<std::size_t>(points));
}

/// Shortest round-trip form: the metadata shows 0.9, not 0.90000000000000002, yet loses no bit.
std::string format_list(const std::vector<double>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, values[i]).ptr;
    text += (i ? ", " : "") + std::string(buffer, end);
  }
  return text;
}

}  // namespace

std::string TableGridFile::describe_axes() const {
  std::string line = "table grid: omega_hat = [" + format_list(grid.omega_hat) + "]; gamma_hat = [" +
                     format_list(grid.gamma_hat) + "]";
  if (!restitution.empty()) {
    line += " converted from restitution e_n = [" + format_list(restitution) +
            "] by gamma_hat = sqrt(2) zeta(e_n), zeta = -ln e_n / sqrt(pi^2 + ln^2 e_n) "
            "(Hooke collision of two equal grains, units.hpp gamma_hat_from_restitution)";
  }
  line += "; ranks_per_point = " + std::to_string(ranks_per_point);
  return line;
}

TableGridFile parse_grid_file(const std::string& text, const std::filesystem::path& origin) {
  const std::string origin_name = origin.string();
  toml::value root;
  try {
    std::istringstream stream(text);
    root = toml::parse(stream, origin_name);
  } catch (const toml::exception& e) {
    // toml11's message shows the offending lines; the prefix gives the usual FILE:LINE form.
    throw GridFileError(origin_name + ":" + std::to_string(e.location().line()) + ": syntax error: " + e.what());
  }
  Keys top(root, "", origin_name, {"scene", "ranks_per_point", "omega_hat", "gamma_hat", "restitution"});
  TableGridFile file;
  file.path = origin;
  file.text = text;

  const toml::value& scene = top.at("scene");
  if (!scene.is_string() || scene.as_string().str.empty()) fail(scene, "scene", "must be a file name", origin_name);
  file.scene_path = origin.parent_path() / std::string(scene.as_string().str);
  if (!std::filesystem::is_regular_file(file.scene_path)) {
    fail(scene, "scene", "no such file: " + file.scene_path.string() + " (paths are relative to the grid file)",
         origin_name);
  }

  file.ranks_per_point = static_cast<int>(top.integer("ranks_per_point", 1, 1));
  file.grid.omega_hat = axis(top.at("omega_hat"), "omega_hat", top);

  if (top.has("gamma_hat") == top.has("restitution")) {
    throw GridFileError(origin_name + ":" + std::to_string(root.location().line()) +
                        ": key 'gamma_hat': give exactly one of 'gamma_hat' or 'restitution'");
  }
  if (top.has("gamma_hat")) {
    file.grid.gamma_hat = axis(top.at("gamma_hat"), "gamma_hat", top);
  } else {
    // Descending e_n gives ascending gamma_hat; e_n = 1 would be gamma_hat = 0, outside a log grid.
    file.restitution = number_list(top.at("restitution"), "restitution", top, true, 1.0);
    for (double e_n : file.restitution) file.grid.gamma_hat.push_back(gamma_hat_from_restitution(e_n));
  }
  file.grid.validate();
  return file;
}

TableGridFile read_grid_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw GridFileError(path.string() + ": cannot open grid file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_grid_file(text.str(), path);
}

}  // namespace sedwave::forward::table
