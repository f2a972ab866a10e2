#pragma once
// Reading back the posterior samples `sedwave invert --method posterior` writes
// (posterior_samples.csv: a comment line, the parameter names, then one draw per row, SI units), for
// whatever is derived from a posterior afterwards (a band of the reflection coefficient).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sedwave::inversion {

struct SamplesTable {
  std::vector<std::string> names;  ///< the free parameters, in column order
  Eigen::MatrixXd draws;           ///< one row per draw, SI
};

/// Throws std::invalid_argument naming the file, line and field for a malformed file (a missing
/// header, a row of the wrong length, a value that is not a finite number) or one without draws.
[[nodiscard]] SamplesTable read_samples_csv(const std::filesystem::path& path);

/// `count` row indices spread evenly over `rows` (all of them when count >= rows).
[[nodiscard]] std::vector<Eigen::Index> evenly_spread_rows(Eigen::Index rows, Eigen::Index count);

}  // namespace sedwave::inversion
