#pragma once
// Private: the table file's own HDF5 datasets (the [gamma][omega] result matrices, written cell by
// cell), on top of the shared HDF5 layer (../io/hdf5.hpp), whose names this namespace also offers so
// that the table code reads as one vocabulary.
#include <hdf5.h>

#include "sedwave/io/hdf5.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace sedwave::forward::table::h5 {

using io::attribute_text;
using io::create_group;
using io::flush;
using io::Handle;
using io::has_attribute;
using io::open_dataset;
using io::open_file;
using io::open_group;
using io::QuietErrors;
using io::read_attribute;
using io::read_string_attribute;
using io::read_string_dataset;
using io::read_vector;
using io::require_float_dataset;
using io::shape;
using io::StringBytes;
using io::write;
using io::write_attribute;
using io::write_string_attribute;
using io::write_string_dataset;

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
