#pragma once
// Files that no rank writes whole: every rank writes its own rows in piece files of its own,
// PATH.piece-TOKEN-RANK-PART (the same groups and datasets as PATH, at most a given number of rows
// each), and PATH's row datasets are HDF5 virtual datasets that join the pieces in rank order, so
// any HDF5 reader sees one file (the pieces must stay beside it). Parallel HDF5 is not needed, and
// every file is still written whole in memory and renamed into place: the pieces first under a
// fresh TOKEN, then PATH, which is what switches readers to the new content; pieces of other tokens
// are removed after that. A kill at any moment leaves the old file or the new one whole. Two
// processes writing one PATH at once are not guarded against (the loser's pieces are removed).
// Used by DEM checkpoints (grains and contact history) and by channel packing files (grains).
#include <hdf5.h>
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::dem {

/// One piece file: a part of one rank's rows, `rows[kind]` of each kind of row (grains, records).
struct Piece {
  int rank = 0;
  std::int64_t part = 0;
  std::vector<std::int64_t> rows;
};

/// The pieces of every rank in file order (rank by rank, part by part), from each kind's rows per
/// rank (`rows[kind][rank]`): at most `piece_rows` rows of every kind per piece, at least one piece
/// per rank.
[[nodiscard]] std::vector<Piece> piece_layout(const std::vector<std::vector<std::int64_t>>& rows,
                                              std::int64_t piece_rows);

/// A token no earlier file at the same path used (16 hex digits, the same on every rank; collective).
[[nodiscard]] std::string fresh_piece_token(MPI_Comm comm);

/// The piece's file name (no folder): PATH's name + ".piece-TOKEN-RANK-PART".
[[nodiscard]] std::string piece_name(const std::filesystem::path& path, const std::string& token, const Piece& piece);

/// One dataset of rows: its group and name, element type, columns (0: one-dimensional), and which
/// kind of row (index into Piece::rows) it holds.
struct RowDataset {
  const char* group;
  const char* name;
  hid_t type;
  std::size_t columns;
  std::size_t kind;
};

/// The columns of /grains that every file of grains holds, packings and checkpoints alike: id, group,
/// body, radius, mass and position (rows of kind 0). A function: the H5T_NATIVE_* ids exist once
/// HDF5 is open.
[[nodiscard]] std::vector<RowDataset> grain_datasets();

/// Rows [first, first + count) of grain_datasets() under the group `grains`, as grains (their other
/// fields zero).
[[nodiscard]] std::vector<Grain> read_grain_rows(hid_t grains, std::size_t first, std::size_t count);

/// The virtual dataset `d.group/d.name` under `file` (the file at `path`) that joins the pieces'
/// datasets of the same name in order. Piece names are stored relative: HDF5 looks for them beside
/// the file.
void join_pieces(hid_t file, const RowDataset& d, const std::vector<Piece>& pieces, const std::filesystem::path& path,
                 const std::string& token);

/// Throws std::runtime_error (starting with `what`) unless every piece that `dataset` maps (a
/// virtual one; an ordinary one has none) is beside the file at `path`: HDF5 reads a missing
/// source as fill values, so a file copied without its pieces would give grains of zero mass and
/// radius without a word.
void require_pieces(hid_t dataset, const std::filesystem::path& path, const std::string& what);

/// Removes the pieces of earlier files at `path` (those not of `token`; all of them for "").
void remove_stale_pieces(const std::filesystem::path& path, const std::string& token);

}  // namespace sedwave::forward::dem
