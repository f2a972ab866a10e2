#pragma once
// Verlet neighbour list built from a cell list.
//
// A pair enters the list when its gap is below the skin: |x_i - x_j| < r_i + r_j + skin. The list
// stays valid until some grain has moved more than skin/2 since the build (two grains approaching
// each other by skin/2 each just close the gap), which needs_rebuild() checks. Forces that act
// across gaps (a pore fluid's lubrication, fluid.hpp) widen the listed gap by their reach,
// |x_i - x_j| < r_i + r_j + gap + skin, with the same rebuild rule.
//
// Layout: compressed rows over the local grains. Row i holds first its local partners j > i (each
// local pair once: the loop applies +F to i and -F to j) and then its ghost partners.
// A pair across a periodic face or slab boundary is seen from both sides (i with the ghost of j,
// j with the ghost of i). "Newton off" lists it on both sides and each side computes the force on
// its own grain. "Newton on" lists it only on the side of the smaller global id: the force is
// computed once, -F lands on the ghost and reverse communication (Domain::reverse_forces) adds it to
// the owner. The id rule is exact: the mirror pair has the two ids swapped, so exactly one side
// keeps it, with no floating-point ties (a coordinate rule needs care with periodic shifts).
// Pairs of two rigid-body grains are excluded (walls do not interact with walls).
//
// Periodic images made on this rank are found as ghost copies and then listed as their source grain
// plus a shift (Domain::ghost_sources): partner k's position is position[partner] + shift(k). Under
// "newton on" the reaction of such a pair lands on the source grain directly.
//
// Ghosts received from other ranks are the last ghosts built, so each row ends with its pairs with
// them (from remote_begin(i)); remote_rows() lists the rows that have any. The engine evaluates the
// other pairs while those ghosts' fresh positions are still on their way.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::dem {

class NeighborList {
 public:
  /// Builds the list for the current local and ghost grains. max_radius: largest radius anywhere.
  /// newton: list each cross-boundary pair on one side only (see above).
  /// ghost_sources: per ghost, the grain to list instead and the shift to add (Domain::ghost_sources);
  /// empty: ghosts are listed as themselves. interaction_gap: the largest gap across which a force
  /// acts (0: contact forces only).
  void build(const GrainArrays& g, double skin, double max_radius, bool newton = false,
             std::span<const GhostSource> ghost_sources = {}, double interaction_gap = 0.0);
  /// True when a local grain moved more than skin/2 since the last build (local decision: the engine
  /// reduces it over ranks).
  [[nodiscard]] bool needs_rebuild(const GrainArrays& g) const;
  /// The local positions at the last build and the squared displacement from them, (skin/2)², past
  /// which the list is stale: what needs_rebuild() compares, for a caller that moves the grains and
  /// checks them in the same pass.
  [[nodiscard]] std::span<const Vec3> reference_positions() const { return reference_; }
  [[nodiscard]] double stale_displacement2() const { return 0.25 * skin_ * skin_; }

  [[nodiscard]] std::size_t n_rows() const { return ghost_begin_.size(); }
  [[nodiscard]] std::size_t n_pairs() const { return partners_.size(); }
  [[nodiscard]] std::uint32_t row_begin(std::size_t i) const { return row_begin_[i]; }
  [[nodiscard]] std::uint32_t ghost_begin(std::size_t i) const { return ghost_begin_[i]; }
  [[nodiscard]] std::uint32_t row_end(std::size_t i) const { return row_begin_[i + 1]; }
  /// First pair of row i whose partner is a ghost received from another rank (row_end(i) if none).
  [[nodiscard]] std::uint32_t remote_begin(std::size_t i) const { return remote_begin_[i]; }
  /// The rows with at least one pair with a ghost received from another rank, ascending.
  [[nodiscard]] std::span<const std::uint32_t> remote_rows() const { return remote_rows_; }
  [[nodiscard]] std::span<const std::int32_t> partners() const { return partners_; }
  /// Per pair, an index into shifts(): what to add to the partner's position (0: no shift).
  [[nodiscard]] std::span<const std::uint8_t> shift_codes() const { return shift_codes_; }
  [[nodiscard]] std::span<const Vec3> shifts() const { return shifts_; }
  [[nodiscard]] const Vec3& shift(std::size_t k) const { return shifts_[shift_codes_[k]]; }
  [[nodiscard]] double skin() const { return skin_; }
  /// Whether cross-boundary pairs are listed once (their reactions go to ghosts).
  [[nodiscard]] bool newton() const { return newton_; }
  /// Bytes held (for the memory report).
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  std::vector<std::uint32_t> row_begin_;    // n_local + 1
  std::vector<std::uint32_t> ghost_begin_;  // n_local
  std::vector<std::uint32_t> remote_begin_;  // n_local
  std::vector<std::uint32_t> remote_rows_;
  std::vector<std::int32_t> partners_;
  std::vector<std::uint8_t> shift_codes_;
  std::vector<Vec3> shifts_{Vec3{}};  // distinct shifts, [0] = none
  std::vector<Vec3> reference_;             // local positions at build time
  // Cell-list scratch, kept between builds to avoid reallocation.
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::int32_t> cell_items_;
  std::vector<std::uint32_t> cell_of_;
  std::vector<std::int32_t> candidates_;
  double skin_ = 0.0;
  bool newton_ = false;
};

/// Order of the local grains along a z-major cell grid (cells of size cell_size; stable within a
/// cell). Applied before ghosts are built, it keeps neighbours close in memory.
[[nodiscard]] std::vector<std::uint32_t> spatial_order(const GrainArrays& g, double cell_size);

}  // namespace sedwave::forward::dem
