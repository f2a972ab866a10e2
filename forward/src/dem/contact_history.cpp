#include "sedwave/forward/dem/contact_history.hpp"

namespace sedwave::forward::dem {

HistoryMap::HistoryMap(std::span<const HistoryEntry> entries) {
  map_.reserve(entries.size());
  for (const HistoryEntry& e : entries) map_.try_emplace({e.a, e.b}, e.shear);
}

Vec3 HistoryMap::find(std::int64_t id_i, std::int64_t id_j) const {
  if (map_.empty()) return {};
  const bool i_first = id_i < id_j;
  const auto it = map_.find(i_first ? std::pair{id_i, id_j} : std::pair{id_j, id_i});
  if (it == map_.end()) return {};
  return i_first ? it->second : -it->second;
}

std::vector<HistoryEntry> extract_history(const NeighborList& list, const GrainArrays& g,
                                          std::span<const Vec3> slots) {
  std::vector<HistoryEntry> out;
  if (slots.empty()) return out;
  const auto partners = list.partners();
  for (std::size_t i = 0; i < list.n_rows(); ++i)
    for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k) {
      const Vec3& s = slots[k];
      if (s == Vec3{}) continue;
      const std::int64_t id_i = g.id[i];
      const std::int64_t id_j = g.id[static_cast<std::size_t>(partners[k])];
      if (id_i < id_j) out.push_back({id_i, id_j, s});
      else out.push_back({id_j, id_i, -s});
    }
  return out;
}

void assign_history(const NeighborList& list, const GrainArrays& g, const HistoryMap& map,
                    std::vector<Vec3>& slots) {
  slots.assign(list.n_pairs(), Vec3{});
  const auto partners = list.partners();
  for (std::size_t i = 0; i < list.n_rows(); ++i)
    for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k)
      slots[k] = map.find(g.id[i], g.id[static_cast<std::size_t>(partners[k])]);
}

}  // namespace sedwave::forward::dem
