#include "sedwave/forward/table/grid_file.hpp"

#include <charconv>
#include <cmath>
#include <toml.hpp>

#include "sedwave/io/toml_table.hpp"

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::table {
namespace {

using Keys = io::Table<GridFileError>;

[[noreturn]] void fail(const toml::value& v, const std::string& key, const std::string& why, const std::string& origin) {
  io::fail<GridFileError>(v, key, why, origin);
}

/// An explicit list: positive numbers, strictly ascending (descending when `descending`).
std::vector<double> number_list(const toml::value& v, const std::string& key, const Keys& keys, bool descending,
                                const io::Range& range = io::Range::positive()) {
  if (!v.is_array()) fail(v, key, "must be a list of numbers", keys.origin());
  const toml::array& array = v.as_array();
  if (array.empty()) fail(v, key, "must not be empty", keys.origin());
  std::vector<double> values;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string element = key + "[" + std::to_string(i) + "]";
    const double x = keys.number_value(array[i], element, range);
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
  Keys range(v, key, parent.origin());
  range.allow_only({"from", "to", "points"});
  const double from = range.required_positive("from");
  const double to = range.required_positive("to");
  if (!(to > from)) fail(range.at("to"), range.name("to"), "must be greater than 'from'", parent.origin());
  // A table of more points than this would take years to fill with any engine.
  const auto points = range.integer<std::size_t>("points", 0, io::Range::closed(2, 100000, "points"));
  if (points == 0) range.at("points");  // missing: throws naming the key
  return log_spaced(from, to, points);
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
  const toml::value root = io::parse<GridFileError>(text, origin_name);
  Keys top(root, "", origin_name);
  top.allow_only({"scene", "ranks_per_point", "omega_hat", "gamma_hat", "restitution"});
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

  file.ranks_per_point = top.integer("ranks_per_point", 1, io::Range::closed(1, 1e6, "ranks"));
  file.grid.omega_hat = axis(top.at("omega_hat"), "omega_hat", top);

  if (top.has("gamma_hat") == top.has("restitution")) {
    throw GridFileError(origin_name + ":" + std::to_string(root.location().line()) +
                        ": key 'gamma_hat': give exactly one of 'gamma_hat' or 'restitution'");
  }
  if (top.has("gamma_hat")) {
    file.grid.gamma_hat = axis(top.at("gamma_hat"), "gamma_hat", top);
  } else {
    // Descending e_n gives ascending gamma_hat; e_n = 1 would be gamma_hat = 0, outside a log grid.
    file.restitution = number_list(top.at("restitution"), "restitution", top, true, io::Range::open(0.0, 1.0));
    for (double e_n : file.restitution) file.grid.gamma_hat.push_back(gamma_hat_from_restitution(e_n));
  }
  file.grid.validate();
  return file;
}

TableGridFile read_grid_file(const std::filesystem::path& path) {
  return parse_grid_file(io::read_text<GridFileError>(path, "grid file"), path);
}

}  // namespace sedwave::forward::table
