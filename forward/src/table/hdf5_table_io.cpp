#include "hdf5_table_io.hpp"

#include <array>
#include <cstring>
#include <limits>

#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table::h5 {
namespace {

Handle dataspace(std::size_t rows, std::size_t columns) {
  const std::array<hsize_t, 2> dims{rows, columns};
  return {H5Screate_simple(2, dims.data(), nullptr), H5Sclose, "create a dataspace"};
}

/// Fixed-length, NUL-terminated string type of `bytes` bytes.
Handle string_type(std::size_t bytes) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy the string type");
  check(H5Tset_size(type.get(), bytes), "size a string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "pad a string type");
  return type;
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

std::string trimmed(const char* data, std::size_t bytes) { return {data, strnlen(data, bytes)}; }

std::vector<hsize_t> dimensions(const Handle& dataset) {
  Handle space(H5Dget_space(dataset.get()), H5Sclose, "get a dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error("HDF5: cannot read a dataset's rank");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

std::size_t element_count(const Handle& dataset) {
  std::size_t count = 1;
  for (const hsize_t d : dimensions(dataset)) count *= static_cast<std::size_t>(d);
  return count;
}

template <typename T>
std::vector<T> read_all(const Handle& dataset, const Handle& type, const std::string& what) {
  std::vector<T> values(element_count(dataset));
  check(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "read " + what);
  return values;
}

}  // namespace

Handle open_file(const std::string& path, bool writable) {
  return {H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + path};
}

void flush(const Handle& file) { check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush the table file"); }

Handle create_group(const Handle& parent, const std::string& name) {
  return {H5Gcreate2(parent.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
          "create group " + name};
}

Handle open_group(const Handle& parent, const std::string& name) {
  return {H5Gopen2(parent.get(), name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name};
}

Handle open_dataset(const Handle& parent, const std::string& name) {
  return {H5Dopen2(parent.get(), name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name};
}

void write_string_attribute(const Handle& object, const std::string& name, const std::string& value) {
  const Handle type = string_type(value.size() + 1);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  const Handle attribute(H5Acreate2(object.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         H5Aclose, "create attribute " + name);
  check(H5Awrite(attribute.get(), type.get(), value.c_str()), "write attribute " + name);
}

std::vector<hsize_t> dataset_shape(const Handle& dataset) { return dimensions(dataset); }

bool has_attribute(const Handle& object, const std::string& name) {
  const htri_t exists = H5Aexists(object.get(), name.c_str());
  if (exists < 0) throw std::runtime_error("HDF5: cannot look for attribute " + name);
  return exists > 0;
}

std::string read_string_attribute(const Handle& object, const std::string& name) {
  const Handle attribute(H5Aopen(object.get(), name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  const Handle stored(H5Aget_type(attribute.get()), H5Tclose, "get the type of attribute " + name);
  if (H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) > 0) {
    throw std::runtime_error("HDF5: attribute " + name + " is not a fixed-length string");
  }
  const std::size_t bytes = H5Tget_size(stored.get());
  const Handle type = string_type(bytes);
  std::vector<char> buffer(bytes + 1, '\0');
  check(H5Aread(attribute.get(), type.get(), buffer.data()), "read attribute " + name);
  return trimmed(buffer.data(), bytes);
}

void write_int_attribute(const Handle& object, const std::string& name, int value) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  const Handle attribute(H5Acreate2(object.get(), name.c_str(), H5T_NATIVE_INT, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         H5Aclose, "create attribute " + name);
  check(H5Awrite(attribute.get(), H5T_NATIVE_INT, &value), "write attribute " + name);
}

int read_int_attribute(const Handle& object, const std::string& name) {
  const Handle attribute(H5Aopen(object.get(), name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  int value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_INT, &value), "read attribute " + name);
  return value;
}

void write_string_dataset(const Handle& parent, const std::string& name, const std::string& value) {
  const Handle type = string_type(value.size() + 1);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  const Handle dataset(H5Dcreate2(parent.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                  H5P_DEFAULT),
                       H5Dclose, "create dataset " + name);
  check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()), "write dataset " + name);
}

std::string read_string_dataset(const Handle& parent, const std::string& name) {
  const Handle dataset = open_dataset(parent, name);
  const Handle stored(H5Dget_type(dataset.get()), H5Tclose, "get the type of dataset " + name);
  if (H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) > 0) {
    throw std::runtime_error("HDF5: dataset " + name + " is not a fixed-length string");
  }
  const std::size_t bytes = H5Tget_size(stored.get());
  const Handle type = string_type(bytes);
  std::vector<char> buffer(bytes + 1, '\0');
  check(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), "read dataset " + name);
  return trimmed(buffer.data(), bytes);
}

void write_vector(const Handle& parent, const std::string& name, const std::vector<double>& values) {
  const std::array<hsize_t, 1> dims{values.size()};
  const Handle space(H5Screate_simple(1, dims.data(), nullptr), H5Sclose, "create a dataspace");
  const Handle dataset(H5Dcreate2(parent.get(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                  H5P_DEFAULT),
                       H5Dclose, "create dataset " + name);
  check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
        "write dataset " + name);
}

std::vector<double> read_vector(const Handle& parent, const std::string& name) {
  const Handle dataset = open_dataset(parent, name);
  if (dimensions(dataset).size() != 1) throw std::runtime_error("HDF5: dataset " + name + " is not one-dimensional");
  return read_all<double>(dataset, memory_type(CellType::float64), name);
}

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
