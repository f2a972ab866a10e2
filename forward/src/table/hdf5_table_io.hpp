#pragma once
// Private: the table file's own HDF5 datasets (the [gamma][omega] result matrices, written cell by
// cell), on top of the shared HDF5 layer (../io/hdf5.hpp), whose names this namespace also offers so
// that the table code reads as one vocabulary.
#include <hdf5.h>

#include "../io/hdf5.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sedwave::forward::table::h5 {

using forward::h5::create_group;
using forward::h5::flush;
using forward::h5::Handle;
using forward::h5::has_attribute;
using forward::h5::open_dataset;
using forward::h5::open_file;
using forward::h5::open_group;
using forward::h5::QuietErrors;
using forward::h5::read_attribute;
using forward::h5::read_string_attribute;
using forward::h5::read_string_dataset;
using forward::h5::read_vector;
using forward::h5::shape;
using forward::h5::StringBytes;
using forward::h5::write;
using forward::h5::write_attribute;
using forward::h5::write_string_attribute;
using forward::h5::write_string_dataset;

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
