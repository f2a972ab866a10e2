#pragma once
// Minimal RAII over the HDF5 C API, shared by the forward library's files (DEM checkpoints and
// trajectories, channel packings and runs, dispersion tables). Private header: not installed.
#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <ostream>
#include <string>
#include <vector>

#include "sedwave/io/atomic_file.hpp"

namespace sedwave::io {

/// "HDF5: cannot WHAT (WHY)", where WHY is the innermost entry of HDF5's error stack, the most
/// specific ("file signature not found" for a file that is not HDF5), which is then cleared: the
/// command turns HDF5's own printing of the stack off.
inline std::string failure_message(const std::string& what) {
  std::string why;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* entry, void* out) -> herr_t {
        if (n == 0 && entry->desc != nullptr) *static_cast<std::string*>(out) = entry->desc;
        return 0;
      },
      &why);
  H5Eclear2(H5E_DEFAULT);
  return "HDF5: cannot " + what + (why.empty() ? std::string() : " (" + why + ")");
}

/// Owns one hid_t and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close, const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error(failure_message(what));
  }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    std::swap(id_, o.id_);
    std::swap(close_, o.close_);
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0 && close_) close_(id_);
  }
  /// Closes now and throws if HDF5 reports a failure (the destructor cannot: a file whose last
  /// buffers fail to reach the disk must not be taken for a complete one).
  void close_checked(const std::string& what) {
    if (id_ < 0 || !close_) return;
    const herr_t status = close_(id_);
    id_ = -1;
    if (status < 0) throw std::runtime_error(failure_message(what));
  }
  [[nodiscard]] hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: handles are used as hid_t throughout

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error(failure_message(what));
}

template <typename T> hid_t native_type();
template <> inline hid_t native_type<double>() { return H5T_NATIVE_DOUBLE; }
template <> inline hid_t native_type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <> inline hid_t native_type<std::int32_t>() { return H5T_NATIVE_INT32; }

inline Handle create_file(const std::string& path) {
  io::require_seekable_output(path, "HDF5");
  return {H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create " + path};
}
inline Handle open_file(const std::string& path, bool writable = false) {
  if (writable) io::require_seekable_output(path, "HDF5");
  return {H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
          "open " + path};
}
inline void flush(hid_t file, const std::string& what) { check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + what); }

/// Turns HDF5's automatic error-stack printing off while alive (for probing files that may be damaged).
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

/// Writes a whole file: `fill(file)` builds it in memory (HDF5's core driver), and its bytes are
/// then written to a temporary sibling, fsynced and renamed over `path` (io::write_text_atomically).
/// A failure (a full disk, a kill) leaves whatever `path` held before, and an exception naming it.
/// HDF5 itself never writes to disk here: a file whose write or close failed stays open inside the
/// library and crashes it when it shuts down, so disk errors are met by plain stream writes instead.
template <class Fill>
void write_file_atomically(const std::filesystem::path& path, Fill&& fill) {
  io::require_seekable_output(path, "HDF5");  // before any work: a device or FIFO is refused
  std::vector<char> image;
  {
    Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access properties");
    check(H5Pset_fapl_core(access, std::size_t{1} << 20, false), "keep " + path.string() + " in memory");
    Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access), H5Fclose,
                "create " + path.string() + " in memory");
    fill(file);
    check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "complete " + path.string());
    const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
    if (size < 0) throw std::runtime_error(failure_message("size the image of " + path.string()));
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file.get(), image.data(), image.size()) != size)
      throw std::runtime_error(failure_message("copy the image of " + path.string()));
    file.close_checked("close " + path.string());
  }
  io::write_seekable_atomically(
      path, [&](std::ostream& out) { out.write(image.data(), static_cast<std::streamsize>(image.size())); }, "HDF5");
}
inline Handle create_group(hid_t parent, const std::string& name) {
  return {H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
          "create group " + name};
}
inline Handle open_group(hid_t parent, const std::string& name) {
  return {H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name};
}
inline Handle open_dataset(hid_t parent, const std::string& name) {
  return {H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name};
}
inline bool exists(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

/// Creates a dataset of shape {rows} (columns == 0) or {rows, columns}, to be filled by write_block
/// (or at once by write).
template <typename T>
Handle create_dataset(hid_t parent, const std::string& name, std::size_t rows, std::size_t columns = 0) {
  const std::array<hsize_t, 2> dims{rows, columns};
  Handle space(H5Screate_simple(columns ? 2 : 1, dims.data(), nullptr), H5Sclose, "dataspace " + name);
  return {H5Dcreate2(parent, name.c_str(), native_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
          "create dataset " + name};
}

/// Writes a dataset of shape {rows} (columns == 0) or {rows, columns}.
template <typename T>
void write(hid_t parent, const std::string& name, const T* data, std::size_t rows, std::size_t columns = 0) {
  Handle set = create_dataset<T>(parent, name, rows, columns);
  if (rows > 0) check(H5Dwrite(set, native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}

/// Number of rows of a dataset.
inline std::size_t rows(hid_t parent, const std::string& name) {
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle space(H5Dget_space(set), H5Sclose, "dataspace " + name);
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return static_cast<std::size_t>(dims[0]);
}

/// A dataset's extent along each axis.
inline std::vector<hsize_t> shape(hid_t dataset) {
  Handle space(H5Dget_space(dataset), H5Sclose, "get a dataspace");
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) throw std::runtime_error(failure_message("read a dataset's rank"));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

/// Reads rows [first, first + count) of a 1D or 2D dataset (columns: the second extent, 0 for 1D).
template <typename T>
std::vector<T> read_rows(hid_t parent, const std::string& name, std::size_t first, std::size_t count,
                         std::size_t columns = 0) {
  std::vector<T> out(count * (columns ? columns : 1));
  if (count == 0) return out;
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle file_space(H5Dget_space(set), H5Sclose, "dataspace " + name);
  const std::array<hsize_t, 2> start{first, 0};
  const std::array<hsize_t, 2> extent{count, columns};
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, extent.data(), nullptr),
        "select " + name);
  Handle memory(H5Screate_simple(columns ? 2 : 1, extent.data(), nullptr), H5Sclose, "memory space");
  check(H5Dread(set, native_type<T>(), memory, file_space, H5P_DEFAULT, out.data()), "read " + name);
  return out;
}

/// The whole of a one-dimensional dataset (a file from elsewhere may hold another shape: an error).
template <typename T>
std::vector<T> read_vector(hid_t parent, const std::string& name) {
  const Handle set = open_dataset(parent, name);
  const std::vector<hsize_t> dims = shape(set);
  if (dims.size() != 1) throw std::runtime_error("HDF5: dataset " + name + " is not one-dimensional");
  return read_rows<T>(parent, name, 0, static_cast<std::size_t>(dims[0]));
}

template <typename T>
void write_attribute(hid_t parent, const std::string& name, T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(parent, name.c_str(), native_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create attribute " + name);
  check(H5Awrite(attr, native_type<T>(), &value), "write attribute " + name);
}
template <typename T>
T read_attribute(hid_t parent, const std::string& name) {
  Handle attr(H5Aopen(parent, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  T value{};
  check(H5Aread(attr, native_type<T>(), &value), "read attribute " + name);
  return value;
}

inline bool has_attribute(hid_t object, const std::string& name) {
  const htri_t exists = H5Aexists(object, name.c_str());
  if (exists < 0) throw std::runtime_error(failure_message("look for attribute " + name));
  return exists > 0;
}

// ---- fixed-length strings ------------------------------------------------------------------------

/// How many bytes a fixed-length string takes on disk. Packing, run, checkpoint and trajectory files
/// store exactly the string's bytes (at least one); table files add a terminating NUL. Each file type
/// keeps its own, so that its files stay byte for byte what they were; read_string_attribute and
/// read_string_dataset read both, since they stop at the first NUL or at the stored size.
enum class StringBytes { exact, nul_terminated };

/// Fixed-length, NUL-padded string type of `bytes` bytes.
inline Handle string_type(std::size_t bytes) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy the string type");
  check(H5Tset_size(type, bytes), "size a string type");
  check(H5Tset_strpad(type, H5T_STR_NULLTERM), "pad a string type");
  return type;
}
inline std::size_t stored_bytes(const std::string& value, StringBytes bytes) {
  return bytes == StringBytes::exact ? std::max<std::size_t>(value.size(), 1) : value.size() + 1;
}
/// The text of a fixed-length string buffer: up to its first NUL, or all `bytes` of it.
inline std::string trimmed(const char* data, std::size_t bytes) {
  std::size_t length = 0;
  while (length < bytes && data[length] != '\0') ++length;
  return {data, length};
}
/// Throws unless `stored` (an attribute's or dataset's type) is a fixed-length string.
inline void check_fixed_string(hid_t stored, const std::string& what) {
  if (H5Tget_class(stored) != H5T_STRING || H5Tis_variable_str(stored) > 0) {
    throw std::runtime_error("HDF5: " + what + " is not a fixed-length string");
  }
}

inline void write_string_attribute(hid_t parent, const std::string& name, const std::string& value,
                                   StringBytes bytes = StringBytes::exact) {
  const Handle type = string_type(stored_bytes(value, bytes));
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create attribute " + name);
  check(H5Awrite(attr, type, value.c_str()), "write attribute " + name);
}
inline std::string read_string_attribute(hid_t parent, const std::string& name) {
  Handle attr(H5Aopen(parent, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Handle stored(H5Aget_type(attr), H5Tclose, "get the type of attribute " + name);
  check_fixed_string(stored, "attribute " + name);
  const std::size_t bytes = H5Tget_size(stored);
  std::vector<char> buffer(bytes + 1, '\0');
  check(H5Aread(attr, string_type(bytes), buffer.data()), "read attribute " + name);
  return trimmed(buffer.data(), bytes);
}

/// A stored type in words, for messages: "64-bit float", "32-bit signed integer", "variable-length
/// string" ...
inline std::string type_description(hid_t type) {
  const std::string bits = std::to_string(8 * H5Tget_size(type)) + "-bit ";
  switch (H5Tget_class(type)) {
    case H5T_FLOAT: return bits + "float";
    case H5T_INTEGER: return bits + (H5Tget_sign(type) == H5T_SGN_NONE ? "unsigned integer" : "signed integer");
    case H5T_STRING: return H5Tis_variable_str(type) > 0 ? "variable-length string" : "fixed-length string";
    case H5T_ENUM: return bits + "enumeration";
    case H5T_COMPOUND: return "compound";
    case H5T_ARRAY: return "array";
    case H5T_VLEN: return "variable-length sequence";
    case H5T_BITFIELD: return bits + "bitfield";
    case H5T_OPAQUE: return "opaque";
    case H5T_REFERENCE: return "reference";
    default: return "unknown type";
  }
}

/// What attribute `name` of `parent` holds, for a message that must name it: its text when it is a
/// scalar string of either kind ('text'), else its type ("a 32-bit signed integer"), or "absent".
inline std::string attribute_text(hid_t parent, const std::string& name) {
  if (H5Aexists(parent, name.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    return "absent";
  }
  Handle attr(H5Aopen(parent, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Handle stored(H5Aget_type(attr), H5Tclose, "get the type of attribute " + name);
  Handle space(H5Aget_space(attr), H5Sclose, "get the dataspace of attribute " + name);
  const bool scalar = H5Sget_simple_extent_npoints(space) == 1;
  if (H5Tget_class(stored) != H5T_STRING || !scalar) return "a " + type_description(stored);
  if (H5Tis_variable_str(stored) > 0) {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy the string type");
    check(H5Tset_size(type, H5T_VARIABLE), "size a string type");
    char* text = nullptr;
    check(H5Aread(attr, type, &text), "read attribute " + name);
    std::string value = text ? text : "";
    H5free_memory(text);
    return "'" + value + "' (a variable-length string)";
  }
  const std::size_t bytes = H5Tget_size(stored);
  std::vector<char> buffer(bytes + 1, '\0');
  check(H5Aread(attr, string_type(bytes), buffer.data()), "read attribute " + name);
  return "'" + trimmed(buffer.data(), bytes) + "'";
}

/// Throws std::runtime_error naming `what` (e.g. "FILE: dataset /results/alpha_hat") and its stored
/// type unless the dataset holds floating-point numbers: HDF5 would convert integers silently, and
/// an integer column is a file of another kind (scaled values, a sentinel where a NaN belongs).
inline void require_float_dataset(hid_t dataset, const std::string& what) {
  const Handle stored(H5Dget_type(dataset), H5Tclose, "get the type of " + what);
  if (H5Tget_class(stored) != H5T_FLOAT) {
    throw std::runtime_error(what + " holds " + type_description(stored) +
                             " values; it must hold floating-point numbers (sedwave writes 64-bit floats)");
  }
}

/// A scalar dataset holding one string (any length, including empty).
inline void write_string_dataset(hid_t parent, const std::string& name, const std::string& value,
                                 StringBytes bytes = StringBytes::exact) {
  const Handle type = string_type(stored_bytes(value, bytes));
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle set(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             "create dataset " + name);
  check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()), "write dataset " + name);
}
inline std::string read_string_dataset(hid_t parent, const std::string& name) {
  const Handle set = open_dataset(parent, name);
  Handle stored(H5Dget_type(set), H5Tclose, "get the type of dataset " + name);
  check_fixed_string(stored, "dataset " + name);
  const std::size_t bytes = H5Tget_size(stored);
  std::vector<char> buffer(bytes + 1, '\0');
  check(H5Dread(set, string_type(bytes), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), "read dataset " + name);
  return trimmed(buffer.data(), bytes);
}

// ---- extensible (time-series) datasets -----------------------------------------------------------

using Extent = std::vector<hsize_t>;

/// Creates a dataset of shape [0][inner...] that grows along its first axis (one row per frame).
/// Chunks hold one frame of at most 2^15 grains, or several frames of small rows (steps, boxes), so
/// that a chunk is neither tiny nor larger than a few MiB.
template <typename T>
void create_extensible(hid_t parent, const std::string& name, const Extent& inner) {
  hsize_t row = 1;
  for (hsize_t n : inner) row *= std::max<hsize_t>(n, 1);
  Extent dims{0}, max_dims{H5S_UNLIMITED}, chunk{std::max<hsize_t>(1, 512 / row)};
  for (std::size_t k = 0; k < inner.size(); ++k) {
    dims.push_back(inner[k]);
    max_dims.push_back(inner[k]);
    chunk.push_back(std::max<hsize_t>(1, k == 0 ? std::min<hsize_t>(inner[k], hsize_t{1} << 15) : inner[k]));
  }
  const int rank = static_cast<int>(dims.size());
  Handle space(H5Screate_simple(rank, dims.data(), max_dims.data()), H5Sclose, "dataspace " + name);
  Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
  check(H5Pset_chunk(properties, rank, chunk.data()), "chunk " + name);
  Handle set(H5Dcreate2(parent, name.c_str(), native_type<T>(), space, H5P_DEFAULT, properties, H5P_DEFAULT),
             H5Dclose, "create dataset " + name);
}

/// The extent of a dataset along every axis.
inline Extent extent(hid_t parent, const std::string& name) {
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle space(H5Dget_space(set), H5Sclose, "dataspace " + name);
  Extent dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

/// Sets the first extent (the number of frames) of an extensible dataset, growing or shrinking it.
inline void set_frames(hid_t parent, const std::string& name, hsize_t frames) {
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Extent dims = extent(parent, name);
  dims[0] = frames;
  check(H5Dset_extent(set, dims.data()), "resize " + name);
}

/// Writes (or reads) the block [start, start + count) of a dataset of any rank.
template <typename T>
void write_block(hid_t parent, const std::string& name, const Extent& start, const Extent& count, const T* data) {
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle file_space(H5Dget_space(set), H5Sclose, "dataspace " + name);
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select " + name);
  Handle memory(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose, "memory space");
  check(H5Dwrite(set, native_type<T>(), memory, file_space, H5P_DEFAULT, data), "write " + name);
}
template <typename T>
std::vector<T> read_block(hid_t parent, const std::string& name, const Extent& start, const Extent& count) {
  hsize_t total = 1;
  for (hsize_t n : count) total *= n;
  std::vector<T> out(static_cast<std::size_t>(total));
  if (total == 0) return out;
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle file_space(H5Dget_space(set), H5Sclose, "dataspace " + name);
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select " + name);
  Handle memory(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose, "memory space");
  check(H5Dread(set, native_type<T>(), memory, file_space, H5P_DEFAULT, out.data()), "read " + name);
  return out;
}

}  // namespace sedwave::io
