#include "hdf5_table_io.hpp"

#include <array>
#include <limits>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table::h5 {
namespace {

using io::check;
using io::string_type;
using io::trimmed;

Handle dataspace(std::size_t rows, std::size_t columns) {
  const std::array<hsize_t, 2> dims{rows, columns};
  return {H5Screate_simple(2, dims.data(), nullptr), H5Sclose, "create a dataspace"};
}

/// int8 enumeration whose names are PointStatus's, so h5dump and h5py show them.
Handle status_type() {
  Handle type(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose, "create the status enum type");
  for (const PointStatus s : {PointStatus::missing, PointStatus::ok, PointStatus::unresolved, PointStatus::failed}) {
    const auto code = static_cast<std::int8_t>(s);
    check(H5Tenum_insert(type.get(), std::string(to_string(s)).c_str(), &code), "define the status enum");
  }
  return type;
}

Handle memory_type(CellType type) {
  switch (type) {
    case CellType::float64: return {H5Tcopy(H5T_NATIVE_DOUBLE), H5Tclose, "copy the double type"};
    case CellType::status: return status_type();
    case CellType::text: return string_type(kTextCellBytes);
  }
  throw std::logic_error("unknown cell type");
}

std::size_t element_count(const Handle& dataset) {
  std::size_t count = 1;
  for (const hsize_t d : shape(dataset)) count *= static_cast<std::size_t>(d);
  return count;
}

template <typename T>
std::vector<T> read_all(const Handle& dataset, const Handle& type, const std::string& what) {
  std::vector<T> values(element_count(dataset));
  check(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "read " + what);
  return values;
}

}  // namespace

Handle create_matrix(const Handle& parent, const std::string& name, CellType type, std::size_t rows,
                     std::size_t columns) {
  const Handle file_type = memory_type(type);
  const Handle space = dataspace(rows, columns);
  const Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create dataset properties");
  check(H5Pset_layout(properties.get(), H5D_CONTIGUOUS), "choose a contiguous layout");
  check(H5Pset_alloc_time(properties.get(), H5D_ALLOC_TIME_EARLY), "allocate at creation");
  check(H5Pset_fill_time(properties.get(), H5D_FILL_TIME_ALLOC), "fill at allocation");
  if (type == CellType::float64) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    check(H5Pset_fill_value(properties.get(), H5T_NATIVE_DOUBLE, &nan), "set a NaN fill value");
  }  // status and text fill with zero bytes: 'missing' and the empty string
  return {H5Dcreate2(parent.get(), name.c_str(), file_type.get(), space.get(), H5P_DEFAULT, properties.get(),
                     H5P_DEFAULT),
          H5Dclose, "create dataset " + name};
}

void write_cell(const Handle& dataset, CellType type, std::size_t row, std::size_t column, const void* value) {
  const Handle file_space(H5Dget_space(dataset.get()), H5Sclose, "get a dataspace");
  const std::array<hsize_t, 2> start{row, column};
  const std::array<hsize_t, 2> count{1, 1};
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select a table cell");
  const Handle memory_space = dataspace(1, 1);
  const Handle type_handle = memory_type(type);
  check(H5Dwrite(dataset.get(), type_handle.get(), memory_space.get(), file_space.get(), H5P_DEFAULT, value),
        "write a table cell");
}

std::vector<double> read_float64_matrix(const Handle& dataset) {
  return read_all<double>(dataset, memory_type(CellType::float64), "a float64 matrix");
}

std::vector<std::int8_t> read_status_matrix(const Handle& dataset) {
  return read_all<std::int8_t>(dataset, memory_type(CellType::status), "the status matrix");
}

std::vector<std::string> read_text_matrix(const Handle& dataset) {
  const std::vector<char> raw = [&] {
    std::vector<char> bytes(element_count(dataset) * kTextCellBytes);
    const Handle type = memory_type(CellType::text);
    check(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), "read a text matrix");
    return bytes;
  }();
  std::vector<std::string> cells(raw.size() / kTextCellBytes);
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = trimmed(raw.data() + i * kTextCellBytes, kTextCellBytes);
  return cells;
}

}  // namespace sedwave::forward::table::h5
