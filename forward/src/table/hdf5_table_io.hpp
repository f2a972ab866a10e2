#pragma once
// Private: the few HDF5 C API operations the table file needs, each behind a function that owns its
// handles (RAII) and throws std::runtime_error naming what failed.
#include <hdf5.h>

#include "../io/hdf5.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sedwave::forward::table::h5 {

using forward::h5::check;
using forward::h5::Handle;

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

Handle open_file(const std::string& path, bool writable);
void flush(const Handle& file);
Handle create_group(const Handle& parent, const std::string& name);
Handle open_group(const Handle& parent, const std::string& name);
Handle open_dataset(const Handle& parent, const std::string& name);

void write_string_attribute(const Handle& object, const std::string& name, const std::string& value);
[[nodiscard]] bool has_attribute(const Handle& object, const std::string& name);
/// A dataset's extent along each axis.
std::vector<hsize_t> dataset_shape(const Handle& dataset);
std::string read_string_attribute(const Handle& object, const std::string& name);
void write_int_attribute(const Handle& object, const std::string& name, int value);
[[nodiscard]] int read_int_attribute(const Handle& object, const std::string& name);

/// Scalar dataset holding one string (any length, including empty).
void write_string_dataset(const Handle& parent, const std::string& name, const std::string& value);
[[nodiscard]] std::string read_string_dataset(const Handle& parent, const std::string& name);

void write_vector(const Handle& parent, const std::string& name, const std::vector<double>& values);
[[nodiscard]] std::vector<double> read_vector(const Handle& parent, const std::string& name);

/// The kinds of 2D [rows][columns] dataset a table holds.
enum class CellType { float64, status, text };

/// Width of a fixed-length text cell including its terminating NUL.
inline constexpr std::size_t kTextCellBytes = 160;

/// A 2D dataset, contiguous and allocated (filled with NaN / 0 / empty) at creation, so that writing
/// a cell later only overwrites raw data and never changes the file's metadata.
Handle create_matrix(const Handle& parent, const std::string& name, CellType type, std::size_t rows,
                     std::size_t columns);

/// Writes one cell.
void write_cell(const Handle& dataset, CellType type, std::size_t row, std::size_t column, const void* value);

[[nodiscard]] std::vector<double> read_float64_matrix(const Handle& dataset);
[[nodiscard]] std::vector<std::int8_t> read_status_matrix(const Handle& dataset);
[[nodiscard]] std::vector<std::string> read_text_matrix(const Handle& dataset);

}  // namespace sedwave::forward::table::h5
