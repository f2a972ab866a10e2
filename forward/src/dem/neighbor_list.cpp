#include "sedwave/forward/dem/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sedwave::forward::dem {
namespace {

/// A uniform grid of cubic-ish cells over a bounding box.
struct CellGrid {
  Vec3 lo;
  std::array<int, 3> n{1, 1, 1};
  Vec3 inv_size;

  CellGrid(std::span<const Vec3> points, double min_cell, std::size_t max_cells) {
    Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity()};
    lo = -hi;
    for (const Vec3& p : points)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    if (points.empty()) lo = hi = Vec3{};
    double cell = min_cell;
    for (;;) {
      std::size_t total = 1;
      for (int a = 0; a < 3; ++a) {
        const double extent = hi[a] - lo[a];
        n[a] = std::max(1, static_cast<int>(std::min(extent / cell, 1e6)));
        inv_size[a] = n[a] / std::max(extent, 1e-300);
        total *= static_cast<std::size_t>(n[a]);
      }
      if (total <= max_cells) break;
      cell *= 1.26;  // a sparse cloud: coarser cells (still >= the cutoff) bound the memory
    }
  }
  [[nodiscard]] std::size_t size() const { return std::size_t(n[0]) * n[1] * n[2]; }
  [[nodiscard]] int coordinate(const Vec3& p, int a) const {
    return std::clamp(static_cast<int>((p[a] - lo[a]) * inv_size[a]), 0, n[a] - 1);
  }
  // z-major order: cells along x are adjacent in memory, then y, then z (the long channel axis).
  [[nodiscard]] std::size_t index(int ix, int iy, int iz) const {
    return (std::size_t(iz) * n[1] + iy) * n[0] + ix;
  }
  [[nodiscard]] std::size_t index(const Vec3& p) const {
    return index(coordinate(p, 0), coordinate(p, 1), coordinate(p, 2));
  }
};

}  // namespace

void NeighborList::build(const GrainArrays& g, double skin, double max_radius, bool newton,
                         std::span<const GhostSource> ghost_sources, double interaction_gap) {
  skin_ = skin;
  newton_ = newton;
  const std::size_t n_local = g.n_local();
  const std::size_t n_total = g.n_total();
  const double listed_gap = skin + interaction_gap;
  const double cutoff = 2.0 * max_radius + listed_gap;
  const CellGrid grid(std::span(g.position.data(), n_total), cutoff, 4 * n_total + 64);

  // Counting sort of all grains (local and ghost) into cells.
  cell_start_.assign(grid.size() + 1, 0);
  cell_of_.resize(n_total);
  for (std::size_t i = 0; i < n_total; ++i) {
    cell_of_[i] = static_cast<std::uint32_t>(grid.index(g.position[i]));
    ++cell_start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < grid.size(); ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(n_total);
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n_total; ++i) cell_items_[fill[cell_of_[i]]++] = static_cast<std::int32_t>(i);
  }

  row_begin_.assign(n_local + 1, 0);
  ghost_begin_.assign(n_local, 0);
  remote_begin_.assign(n_local, 0);
  remote_rows_.clear();
  partners_.clear();
  partners_.reserve(8 * n_local);
  shift_codes_.clear();
  shift_codes_.reserve(8 * n_local);
  shifts_.assign(1, Vec3{});
  auto code_of = [this](const Vec3& shift) {
    const auto it = std::find(shifts_.begin(), shifts_.end(), shift);
    if (it != shifts_.end()) return static_cast<std::uint8_t>(it - shifts_.begin());
    if (shifts_.size() > std::numeric_limits<std::uint8_t>::max())
      throw std::logic_error("NeighborList: more distinct periodic shifts than codes");
    shifts_.push_back(shift);
    return static_cast<std::uint8_t>(shifts_.size() - 1);
  };
  // Room for every candidate of 27 cells: the scan below writes each one and keeps it by advancing
  // the count, without a branch on the (unpredictable) distance test.
  std::uint32_t fullest = 0;
  for (std::size_t c = 0; c < grid.size(); ++c) fullest = std::max(fullest, cell_start_[c + 1] - cell_start_[c]);
  candidates_.resize(27 * static_cast<std::size_t>(fullest));
  std::int32_t* found = candidates_.data();
  for (std::size_t i = 0; i < n_local; ++i) {
    row_begin_[i] = static_cast<std::uint32_t>(partners_.size());
    const Vec3 xi = g.position[i];
    const double ri = g.radius[i];
    const std::int64_t id_i = g.id[i];
    const bool rigid_i = g.body[i] != kFreeBody;
    std::size_t n_found = 0;
    const int cx = grid.coordinate(xi, 0), cy = grid.coordinate(xi, 1), cz = grid.coordinate(xi, 2);
    for (int iz = std::max(cz - 1, 0); iz <= std::min(cz + 1, grid.n[2] - 1); ++iz)
      for (int iy = std::max(cy - 1, 0); iy <= std::min(cy + 1, grid.n[1] - 1); ++iy)
        for (int ix = std::max(cx - 1, 0); ix <= std::min(cx + 1, grid.n[0] - 1); ++ix) {
          const std::size_t c = grid.index(ix, iy, iz);
          for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
            const auto j = static_cast<std::size_t>(cell_items_[k]);
            const bool local_j = j < n_local;
            // A local pair once (j > i); a ghost pair on both sides, or under newton on only on the
            // side of the smaller id (the mirror pair keeps it); never two wall grains.
            const bool listed_here = local_j ? j > i : !(newton && g.id[j] < id_i);
            const bool both_rigid = rigid_i && g.body[j] != kFreeBody;
            const double reach = ri + g.radius[j] + listed_gap;
            const bool near = norm2(xi - g.position[j]) < reach * reach;
            found[n_found] = static_cast<std::int32_t>(j);
            n_found += static_cast<std::size_t>(listed_here & !both_rigid & near);
          }
        }
    // Ascending partner order makes the summation order independent of the cell scan; it also puts
    // the local partners (indices below n_local) before the ghosts.
    std::sort(found, found + n_found);
    std::int32_t* first_ghost = std::lower_bound(found, found + n_found, static_cast<std::int32_t>(n_local));
    partners_.insert(partners_.end(), found, first_ghost);
    ghost_begin_[i] = static_cast<std::uint32_t>(partners_.size());
    shift_codes_.resize(partners_.size(), 0);
    for (const std::int32_t j : std::span<const std::int32_t>(first_ghost, found + n_found)) {
      if (ghost_sources.empty()) {
        partners_.push_back(j);
        shift_codes_.push_back(0);
        continue;
      }
      const GhostSource& source = ghost_sources[static_cast<std::size_t>(j) - n_local];
      partners_.push_back(source.index);
      shift_codes_.push_back(code_of(source.shift));
    }
    // Partners at or above n_local are ghosts received from other ranks (images resolve to local
    // sources); they were built after every image, so they close the row.
    const auto row = std::span<const std::int32_t>(partners_).subspan(ghost_begin_[i]);
    const auto remote = std::find_if(row.begin(), row.end(), [&](std::int32_t j) { return static_cast<std::size_t>(j) >= n_local; });
    if (std::any_of(remote, row.end(), [&](std::int32_t j) { return static_cast<std::size_t>(j) < n_local; }))
      throw std::logic_error("NeighborList: a periodic image was built after a ghost from another rank");
    remote_begin_[i] = ghost_begin_[i] + static_cast<std::uint32_t>(remote - row.begin());
    if (remote != row.end()) remote_rows_.push_back(static_cast<std::uint32_t>(i));
  }
  if (partners_.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::overflow_error("NeighborList: more than 2^32 pairs on one rank");
  row_begin_[n_local] = static_cast<std::uint32_t>(partners_.size());
  reference_.assign(g.position.begin(), g.position.begin() + static_cast<std::ptrdiff_t>(n_local));
}

bool NeighborList::needs_rebuild(const GrainArrays& g) const {
  if (reference_.size() != g.n_local()) return true;
  const double limit2 = stale_displacement2();
  for (std::size_t i = 0; i < reference_.size(); ++i)
    if (norm2(g.position[i] - reference_[i]) > limit2) return true;
  return false;
}

std::size_t NeighborList::memory_bytes() const {
  return (row_begin_.capacity() + ghost_begin_.capacity() + remote_begin_.capacity() + remote_rows_.capacity()) *
             sizeof(std::uint32_t) +
         partners_.capacity() * sizeof(std::int32_t) + shift_codes_.capacity() + reference_.capacity() * sizeof(Vec3) +
         cell_start_.capacity() * sizeof(std::uint32_t) + cell_items_.capacity() * sizeof(std::int32_t) +
         cell_of_.capacity() * sizeof(std::uint32_t);
}

std::vector<std::uint32_t> spatial_order(const GrainArrays& g, double cell_size) {
  const std::size_t n = g.n_local();
  const CellGrid grid(std::span(g.position.data(), n), cell_size, 2 * n + 64);
  std::vector<std::uint32_t> start(grid.size() + 1, 0);
  std::vector<std::uint32_t> cell(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell[i] = static_cast<std::uint32_t>(grid.index(g.position[i]));
    ++start[cell[i] + 1];
  }
  for (std::size_t c = 0; c < grid.size(); ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[start[cell[i]]++] = static_cast<std::uint32_t>(i);
  return order;
}

}  // namespace sedwave::forward::dem
