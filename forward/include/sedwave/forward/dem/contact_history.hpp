#pragma once
// Contact history (the tangential spring's shear displacement) keyed by the pair's global ids.
//
// During a run the history lives in slots parallel to the neighbour list (one Vec3 per listed pair,
// oriented as seen from the row grain i), so the force loop reads it by index. At every rebuild the
// non-zero slots are extracted as HistoryEntry records keyed by (smaller id, larger id) and oriented
// as seen from the smaller id; migration ships the records of departing grains with them, and the
// new list looks its slots up by key. The same records are what checkpoints store, so history
// survives rebuilds, spatial sorting, migration between ranks and restarts.
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/dem/neighbor_list.hpp"

namespace sedwave::forward::dem {

struct HistoryEntry {
  std::int64_t a = 0;  ///< smaller global id
  std::int64_t b = 0;  ///< larger global id
  Vec3 shear;          ///< shear displacement of a relative to b
};

class HistoryMap {
 public:
  HistoryMap() = default;
  /// Indexes the entries; the first of duplicated keys wins (duplicates agree to round-off).
  explicit HistoryMap(std::span<const HistoryEntry> entries);
  /// Shear of id_i relative to id_j (zero if the pair has no history).
  [[nodiscard]] Vec3 find(std::int64_t id_i, std::int64_t id_j) const;

 private:
  struct KeyHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& k) const {
      return std::hash<std::int64_t>{}(k.first * 0x9E3779B97F4A7C15LL ^ k.second);
    }
  };
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, Vec3, KeyHash> map_;
};

/// Non-zero history slots of a list as keyed records (in list order).
[[nodiscard]] std::vector<HistoryEntry> extract_history(const NeighborList& list, const GrainArrays& g,
                                                        std::span<const Vec3> slots);
/// Slots for a freshly built list from keyed records.
void assign_history(const NeighborList& list, const GrainArrays& g, const HistoryMap& map,
                    std::vector<Vec3>& slots);

}  // namespace sedwave::forward::dem
