#pragma once
// Collecting rank-local records on one rank: the only moments a rank may hold every grain are
// writing a checkpoint or a packing file.
#include <mpi.h>

#include <vector>

#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {

/// Gathers trivially copyable records from all ranks on rank 0, in rank order (empty elsewhere).
template <typename T>
std::vector<T> gather_on_root(MPI_Comm comm, const std::vector<T>& local) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // Counted in records, not bytes (a byte count overflows int at 1.4e7 grains).
  const parallel::RecordType<T> record;
  const int count = parallel::mpi_count(local.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  const std::vector<int> displs = rank == 0 ? parallel::displacements(counts) : std::vector<int>(counts.size());
  std::vector<T> all(rank == 0 ? static_cast<std::size_t>(displs.back()) + static_cast<std::size_t>(counts.back()) : 0);
  MPI_Gatherv(local.data(), count, record.get(), all.data(), counts.data(), displs.data(), record.get(), 0, comm);
  return all;
}

/// The engine's grains on rank 0 (collective; empty on other ranks).
inline std::vector<Grain> gather_grains(const Engine& engine) {
  std::vector<Grain> local;
  local.reserve(engine.n_local());
  for (std::size_t i = 0; i < engine.n_local(); ++i) local.push_back(engine.grains().grain(i));
  return gather_on_root(engine.domain().comm(), local);
}

}  // namespace sedwave::forward::dem
