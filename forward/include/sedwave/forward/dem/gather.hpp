#pragma once
// Collecting rank-local records on one rank: the only moments a rank may hold every grain are
// writing a checkpoint or a packing file.
#include <vector>

#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {

/// The engine's grains on rank 0 (collective; empty on other ranks).
inline std::vector<Grain> gather_grains(const Engine& engine) {
  std::vector<Grain> local;
  local.reserve(engine.n_local());
  for (std::size_t i = 0; i < engine.n_local(); ++i) local.push_back(engine.grains().grain(i));
  return parallel::gather_on_root(engine.domain().comm(), local);
}

}  // namespace sedwave::forward::dem
