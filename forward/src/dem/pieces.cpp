#include "sedwave/forward/dem/pieces.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <span>
#include <stdexcept>

#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/io/hdf5.hpp"

namespace sedwave::forward::dem {
namespace {

/// A file name as H5Pset_virtual takes it: '%' starts a format there, so a literal one is "%%".
std::string vds_file_name(const std::string& name) {
  std::string out;
  for (const char c : name) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

}  // namespace

std::vector<Piece> piece_layout(const std::vector<std::vector<std::int64_t>>& rows, std::int64_t piece_rows) {
  std::vector<Piece> out;
  const std::size_t ranks = rows.empty() ? 0 : rows.front().size();
  for (std::size_t r = 0; r < ranks; ++r) {
    std::int64_t most = 0;
    for (const std::vector<std::int64_t>& kind : rows) most = std::max(most, kind[r]);
    const std::int64_t parts = std::max<std::int64_t>(1, (most + piece_rows - 1) / piece_rows);
    for (std::int64_t k = 0; k < parts; ++k) {
      Piece p{static_cast<int>(r), k, {}};
      for (const std::vector<std::int64_t>& kind : rows)
        p.rows.push_back(std::clamp<std::int64_t>(kind[r] - k * piece_rows, 0, piece_rows));
      out.push_back(std::move(p));
    }
  }
  return out;
}

std::string fresh_piece_token(MPI_Comm comm) {
  std::uint64_t bits = 0;
  if (parallel::rank(comm) == 0) bits = (std::uint64_t{std::random_device{}()} << 32) ^ std::random_device{}();
  parallel::broadcast(comm, std::span(&bits, 1));
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
  return text;
}

std::string piece_name(const std::filesystem::path& path, const std::string& token, const Piece& piece) {
  return path.filename().string() + ".piece-" + token + "-" + std::to_string(piece.rank) + "-" +
         std::to_string(piece.part);
}

void join_pieces(hid_t file, const RowDataset& d, const std::vector<Piece>& pieces, const std::filesystem::path& path,
                 const std::string& token) {
  const auto rows = [&](const Piece& p) { return static_cast<hsize_t>(p.rows.at(d.kind)); };
  hsize_t total = 0;
  for (const Piece& p : pieces) total += rows(p);
  const int dims = d.columns ? 2 : 1;
  const std::array<hsize_t, 2> extent{total, d.columns};
  io::Handle space(H5Screate_simple(dims, extent.data(), nullptr), H5Sclose, "dataspace " + std::string(d.name));
  io::Handle create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create dataset properties");
  // Appended, not concatenated: GCC 12 warns falsely (-Wrestrict) on "/" + std::string.
  std::string source = "/";
  source.append(d.group).append("/").append(d.name);
  hsize_t first = 0;
  for (const Piece& p : pieces) {
    if (rows(p) == 0) continue;
    const std::array<hsize_t, 2> start{first, 0}, count{rows(p), d.columns};
    io::check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
              "select rows of " + source);
    io::Handle piece(H5Screate_simple(dims, count.data(), nullptr), H5Sclose, "dataspace of a piece");
    const std::string name = piece_name(path, token, p);
    io::check(H5Pset_virtual(create, space, vds_file_name(name).c_str(), source.c_str(), piece),
              "map " + name + source);
    first += count[0];
  }
  io::check(H5Sselect_all(space), "select " + source);
  io::Handle group = io::exists(file, d.group) ? io::open_group(file, d.group) : io::create_group(file, d.group);
  io::Handle set(H5Dcreate2(group, d.name, d.type, space, H5P_DEFAULT, create, H5P_DEFAULT), H5Dclose,
                 "create dataset " + source);
}

void require_pieces(hid_t dataset, const std::filesystem::path& path, const std::string& what) {
  io::Handle create(H5Dget_create_plist(dataset), H5Pclose, "dataset creation properties of " + path.string());
  if (H5Pget_layout(create) != H5D_VIRTUAL) return;
  std::size_t mappings = 0;
  io::check(H5Pget_virtual_count(create, &mappings), "count the pieces of " + path.string());
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  for (std::size_t k = 0; k < mappings; ++k) {
    const ssize_t length = H5Pget_virtual_filename(create, k, nullptr, 0);
    if (length < 0) throw std::runtime_error(what + ": cannot read the piece names of " + path.string());
    std::string stored(static_cast<std::size_t>(length) + 1, '\0');
    H5Pget_virtual_filename(create, k, stored.data(), stored.size());
    stored.resize(static_cast<std::size_t>(length));
    std::string name;  // undo vds_file_name
    for (std::size_t i = 0; i < stored.size(); ++i) {
      name += stored[i];
      if (stored[i] == '%' && i + 1 < stored.size() && stored[i + 1] == '%') ++i;
    }
    if (!std::filesystem::exists(folder / name)) {
      throw std::runtime_error(what + ": " + path.string() + " lacks its piece " + (folder / name).string() +
                               " (a file written in pieces is the file and its .piece-* files together; copy them "
                               "together)");
    }
  }
}

void remove_stale_pieces(const std::filesystem::path& path, const std::string& token) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::string prefix = path.filename().string() + ".piece-";
  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ignored)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(prefix) && !name.starts_with(prefix + token + "-")) std::filesystem::remove(entry.path(), ignored);
  }
}

std::vector<RowDataset> grain_datasets() {
  return {{"grains", "id", H5T_NATIVE_INT64, 0, 0},     {"grains", "group", H5T_NATIVE_INT32, 0, 0},
          {"grains", "body", H5T_NATIVE_INT32, 0, 0},   {"grains", "radius", H5T_NATIVE_DOUBLE, 0, 0},
          {"grains", "mass", H5T_NATIVE_DOUBLE, 0, 0}, {"grains", "position", H5T_NATIVE_DOUBLE, 3, 0}};
}

std::vector<Grain> read_grain_rows(hid_t grains, std::size_t first, std::size_t count) {
  const auto id = io::read_rows<std::int64_t>(grains, "id", first, count);
  const auto group = io::read_rows<std::int32_t>(grains, "group", first, count);
  const auto body = io::read_rows<std::int32_t>(grains, "body", first, count);
  const auto radius = io::read_rows<double>(grains, "radius", first, count);
  const auto mass = io::read_rows<double>(grains, "mass", first, count);
  const auto position = io::read_rows<double>(grains, "position", first, count, 3);
  std::vector<Grain> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    Grain& g = out[k];
    g.id = id[k];
    g.group = group[k];
    g.body = body[k];
    g.radius = radius[k];
    g.mass = mass[k];
    g.position = {position[3 * k], position[3 * k + 1], position[3 * k + 2]};
  }
  return out;
}

}  // namespace sedwave::forward::dem
