#include "sedwave/io/column_file.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "sedwave/io/hdf5.hpp"

namespace sedwave::io {
namespace {

/// Letters, digits, '_' and '.' (a layer's parameter: l1.thickness), not starting with '.' (HDF5
/// reads "." as the group itself).
void require_dataset_name(const std::string& name) {
  const bool plain = !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_' || c == '.';
  });
  if (!plain) {
    throw std::invalid_argument("column name '" + name + "': use letters, digits, '_' and '.' only, starting with no '.'");
  }
}

}  // namespace

void write_columns_hdf5(const std::filesystem::path& path,
                        const std::vector<std::pair<std::string, std::string>>& attributes,
                        const std::vector<NamedColumn>& columns, std::size_t blocks) {
  for (const NamedColumn& column : columns) {
    require_dataset_name(column.name);
    if (blocks == 0 || column.values.size() % blocks != 0) {
      throw std::invalid_argument("column " + column.name + ": " + std::to_string(column.values.size()) +
                                  " values do not split into " + std::to_string(blocks) + " equal blocks");
    }
  }
  io::write_file_atomically(path, [&](hid_t file) {
    for (const auto& [name, text] : attributes) io::write_string_attribute(file, name, text);
    for (const NamedColumn& column : columns) {
      const std::size_t rows = blocks == 1 ? column.values.size() : blocks;
      const std::size_t inner = blocks == 1 ? 0 : column.values.size() / blocks;
      io::write(file, column.name, column.values.data(), rows, inner);
      io::Handle set(H5Dopen2(file, column.name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + column.name);
      io::write_string_attribute(set, "unit", column.unit);
      io::write_string_attribute(set, "meaning", column.meaning);
    }
  });
}

}  // namespace sedwave::io
