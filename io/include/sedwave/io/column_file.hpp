#pragma once
// Named columns of numbers with their units, as one HDF5 file: for results that other tools read
// (posterior draws, for instance), each column a dataset with a `unit` and a `meaning` attribute.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace sedwave::io {

struct NamedColumn {
  std::string name;     ///< the dataset's name: letters, digits, '_', '.' (no '/', no leading '.')
  std::string unit;     ///< SI unit, "1" if dimensionless
  std::string meaning;  ///< one line
  std::vector<double> values;
};

/// Writes each column as the dataset /NAME of shape {blocks, values / blocks} (row-major: block b
/// holds values [b n, (b + 1) n)), or {values} when blocks is 1, with string attributes `unit` and
/// `meaning`; and the root attributes `attributes` (name, text). Atomic: a failure leaves what the
/// path held before. Throws std::invalid_argument for a bad name or sizes that do not divide.
void write_columns_hdf5(const std::filesystem::path& path,
                        const std::vector<std::pair<std::string, std::string>>& attributes,
                        const std::vector<NamedColumn>& columns, std::size_t blocks = 1);

}  // namespace sedwave::io
