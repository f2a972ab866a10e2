#pragma once
// The grid file of `sedwave table` (TOML): which scene to run and at which (omega_hat, gamma_hat)
// points. Annotated example: data/scenes/table_small.toml; reference: docs/tables.md.
//
//   scene = "table_small_scene.toml"      # relative to this file
//   ranks_per_point = 1                    # MPI ranks that run one point together
//   [omega_hat]  from = 0.1  to = 1.0  points = 4       # log-spaced, or: values = [...]
//   [gamma_hat]  values = [0.05, 0.2]                     # or from/to/points, or restitution = [...]
//
// gamma_hat may be given as restitution coefficients e_n (list, strictly descending so gamma_hat
// ascends); they are converted with units.hpp gamma_hat_from_restitution (two equal grains) and the
// conversion is recorded in the table's metadata.
//
// Every key is checked: an unknown key, a wrong type or an impossible value is a GridFileError
// naming the file, line and key; nothing is silently ignored.
//
// Units: dimensionless (omega_hat, gamma_hat: docs/physics.md); e_n is dimensionless.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table {

/// Error in a grid file: "FILE:LINE: key 'a.b': why" (toml11's own message for syntax errors).
class GridFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TableGridFile {
  std::filesystem::path path;        ///< where it was read from
  std::string text;                  ///< the file verbatim (stored in the table's metadata)
  std::filesystem::path scene_path;  ///< the scene file, resolved against the grid file's folder
  TableGrid grid;
  /// The e_n the gamma_hat axis was converted from (empty when gamma_hat was given directly).
  std::vector<double> restitution;
  int ranks_per_point = 1;

  /// One line for the table's metadata: how each axis was specified.
  [[nodiscard]] std::string describe_axes() const;
};

/// Reads and validates a grid file. Throws GridFileError.
[[nodiscard]] TableGridFile read_grid_file(const std::filesystem::path& path);

/// Parses grid-file text; `origin` names it in errors and relative scene paths resolve from its folder.
[[nodiscard]] TableGridFile parse_grid_file(const std::string& text, const std::filesystem::path& origin);

}  // namespace sedwave::forward::table
