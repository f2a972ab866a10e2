#pragma once
// Typed MPI collectives: sums, minima, maxima and broadcasts of spans (in place) and of single
// values, over any communicator. The element type picks the MPI datatype, so a count or a type
// cannot disagree with the buffer; the MPI error handler (abort by default) deals with failures.
//
// The scene side (channel/) uses these instead of raw MPI calls; MPI itself stays in the DEM
// domain, the task farm and the applications.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace sedwave::forward::parallel {

/// The MPI datatype of a C++ arithmetic type.
template <typename T>
MPI_Datatype datatype() {
  using U = std::remove_const_t<T>;
  if constexpr (std::is_same_v<U, double>) return MPI_DOUBLE;
  else if constexpr (std::is_same_v<U, int>) return MPI_INT;
  else if constexpr (std::is_same_v<U, std::int64_t>) return MPI_INT64_T;
  else if constexpr (std::is_same_v<U, std::uint64_t>) return MPI_UINT64_T;
  else if constexpr (std::is_same_v<U, char>) return MPI_CHAR;
  else if constexpr (std::is_same_v<U, std::byte>) return MPI_BYTE;
  else static_assert(sizeof(T) == 0, "no MPI datatype for this type");
}

namespace detail {
template <typename T, std::size_t N>
void all_reduce(MPI_Comm comm, std::span<T, N> values, MPI_Op op) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), datatype<T>(), op, comm);
}
}  // namespace detail

/// This process's rank in `comm`.
inline int rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

/// The number of ranks in `comm`.
inline int size(MPI_Comm comm) {
  int n = 0;
  MPI_Comm_size(comm, &n);
  return n;
}

/// Element by element over every rank of `comm`, in place (collective).
template <typename T, std::size_t N>
void sum(MPI_Comm comm, std::span<T, N> values) { detail::all_reduce(comm, values, MPI_SUM); }
template <typename T, std::size_t N>
void min(MPI_Comm comm, std::span<T, N> values) { detail::all_reduce(comm, values, MPI_MIN); }
template <typename T, std::size_t N>
void max(MPI_Comm comm, std::span<T, N> values) { detail::all_reduce(comm, values, MPI_MAX); }

/// One value over every rank of `comm` (collective).
template <typename T>
[[nodiscard]] T sum(MPI_Comm comm, T value) {
  sum(comm, std::span<T, 1>(&value, 1));
  return value;
}

/// `values` as `root` holds them, on every rank of `comm` (collective; the sizes must agree).
template <typename T, std::size_t N>
void broadcast(MPI_Comm comm, std::span<T, N> values, int root = 0) {
  MPI_Bcast(values.data(), static_cast<int>(values.size()), datatype<T>(), root, comm);
}

}  // namespace sedwave::forward::parallel
