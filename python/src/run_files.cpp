// Run files and other HDF5 outputs (`sedwave forward`, `sedwave interface`, `sedwave dem`'s
// checkpoints and H5MD trajectories, packings) opened read-only as numpy arrays: every numeric dataset
// by its path, every attribute by its object's path. Plain HDF5 through the io layer, without the
// MPI engines that wrote them, so a notebook reads what a cluster run wrote.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "sedwave/io/hdf5.hpp"

namespace sedwave::python {
namespace {

/// Every object's path below the file's root, in name order.
std::vector<std::string> object_paths(hid_t file) {
  std::vector<std::string> paths;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(std::string("/") + name);
    return 0;
  };
  io::check(H5Lvisit(file, H5_INDEX_NAME, H5_ITER_INC, collect, &paths), "list the file's objects");
  return paths;
}

std::vector<py::ssize_t> shape_of(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank > 0 ? rank : 0));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return {dims.begin(), dims.end()};
}

/// A numeric dataset or attribute as an array: float64 for floating point, int64 for integers.
template <typename T, typename Read>
py::array numbers(const std::vector<py::ssize_t>& shape, Read read) {
  py::array_t<T> out(shape);
  read(io::native_type<T>(), out.mutable_data());
  return out;
}

py::object attribute_value(hid_t object, const std::string& name) {
  io::Handle attr(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  io::Handle type(H5Aget_type(attr), H5Tclose, "get the type of attribute " + name);
  io::Handle space(H5Aget_space(attr), H5Sclose, "get the dataspace of attribute " + name);
  const auto read = [&](hid_t memory, void* into) { io::check(H5Aread(attr, memory, into), "read attribute " + name); };
  switch (H5Tget_class(type)) {
    case H5T_STRING: return py::str(io::read_string_attribute(object, name));
    case H5T_FLOAT: return numbers<double>(shape_of(space), read);
    case H5T_INTEGER: return numbers<std::int64_t>(shape_of(space), read);
    default: return py::none();
  }
}

py::dict attributes_of(hid_t object) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  hsize_t at = 0;
  io::check(H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &at, collect, &names), "list attributes");
  py::dict out;
  for (const std::string& name : names) out[py::str(name)] = attribute_value(object, name);
  return out;
}

}  // namespace

void bind_run_files(py::module_& m) {
  m.def("read_run", [](const std::filesystem::path& path) {
    const io::QuietErrors quiet;
    io::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + path.string());
    py::dict datasets, attributes, skipped;
    attributes["/"] = attributes_of(file);
    for (const std::string& name : object_paths(file)) {
      io::Handle object(H5Oopen(file, name.c_str(), H5P_DEFAULT), H5Oclose, "open " + name);
      py::dict own = attributes_of(object);
      if (py::len(own) > 0) attributes[py::str(name)] = own;
      if (H5Iget_type(object) != H5I_DATASET) continue;
      io::Handle type(H5Dget_type(object), H5Tclose, "get the type of dataset " + name);
      io::Handle space(H5Dget_space(object), H5Sclose, "get the dataspace of dataset " + name);
      const auto read = [&](hid_t memory, void* into) {
        io::check(H5Dread(object, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, into), "read dataset " + name);
      };
      switch (H5Tget_class(type)) {
        case H5T_FLOAT: datasets[py::str(name)] = numbers<double>(shape_of(space), read); break;
        case H5T_INTEGER: datasets[py::str(name)] = numbers<std::int64_t>(shape_of(space), read); break;
        case H5T_STRING:
          if (H5Sget_simple_extent_npoints(space) == 1) {
            datasets[py::str(name)] = py::str(io::read_string_dataset(file, name));
            break;
          }
          [[fallthrough]];
        default: skipped[py::str(name)] = "not a number or a single string";
      }
    }
    py::dict out;
    out["datasets"] = datasets;
    out["attributes"] = attributes;
    out["skipped"] = skipped;
    return out;
  }, py::arg("path"), R"doc(
An HDF5 output of sedwave (a `sedwave forward` or `sedwave interface` run file, a DEM checkpoint or
trajectory, a packing), read only: {"datasets": {path: array}, "attributes": {object path: {name:
value}}, "skipped": {path: why}}. Numeric datasets come as float64 or int64 arrays of their stored
shape, in the units their attributes or the command's documentation state (SI for the interface,
dimensionless for the DEM's channel runs: docs/scenes.md, docs/interface.md); a one-element string
dataset as str.)doc");
}

}  // namespace sedwave::python
