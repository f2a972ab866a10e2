#pragma once
// Typed MPI collectives: sums, minima, maxima and broadcasts of spans (in place) and of single
// values, over any communicator. The element type picks the MPI datatype, so a count or a type
// cannot disagree with the buffer; the MPI error handler (abort by default) deals with failures.
//
// The scene side (channel/) uses these instead of raw MPI calls; MPI itself stays in the DEM
// domain, the task farm and the applications.
//
// MPI counts are int: a span longer than 2^31 - 1 elements (a broadcast packing of 1.4e7 grains as
// bytes) is sent in pieces, so no length wraps around.
#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

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

/// The largest count one MPI call takes.
inline constexpr std::size_t kMaxMpiCount = INT_MAX;

/// `n` as an MPI count; throws std::overflow_error where it does not fit (rather than wrapping).
inline int mpi_count(std::size_t n) {
  if (n > kMaxMpiCount)
    throw std::overflow_error("MPI: a count of " + std::to_string(n) + " exceeds the largest MPI count (2^31 - 1)");
  return static_cast<int>(n);
}

/// An MPI datatype of one trivially copyable record (committed here, freed with this object), so
/// that counts and displacements are in records: 2^31 - 1 grains per call rather than 2^31 - 1 bytes.
template <typename T>
class RecordType {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  RecordType() {
    MPI_Type_contiguous(mpi_count(sizeof(T)), MPI_BYTE, &type_);
    MPI_Type_commit(&type_);
  }
  ~RecordType() { MPI_Type_free(&type_); }
  RecordType(const RecordType&) = delete;
  RecordType& operator=(const RecordType&) = delete;
  [[nodiscard]] MPI_Datatype get() const { return type_; }

 private:
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

/// Exclusive prefix sums of per-rank counts as MPI displacements (each checked by mpi_count).
inline std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> displs(counts.size());
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = mpi_count(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  return displs;
}

namespace detail {
/// Calls piece(first, count) over [0, n) in pieces of at most max_count elements (at least one call).
template <class Piece>
void in_pieces(std::size_t n, std::size_t max_count, Piece piece) {
  std::size_t first = 0;
  do {
    const std::size_t count = std::min(n - first, max_count);
    piece(first, mpi_count(count));
    first += count;
  } while (first < n);
}

template <typename T, std::size_t N>
void all_reduce(MPI_Comm comm, std::span<T, N> values, MPI_Op op, std::size_t max_count) {
  in_pieces(values.size(), max_count, [&](std::size_t first, int count) {
    MPI_Allreduce(MPI_IN_PLACE, values.data() + first, count, datatype<T>(), op, comm);
  });
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

/// The ranks of `comm` that pass `member` = true, as a communicator in the same rank order
/// (collective over `comm`; get() is MPI_COMM_NULL on the others). Freed with this object.
class SubCommunicator {
 public:
  SubCommunicator(MPI_Comm comm, bool member) {
    MPI_Comm_split(comm, member ? 0 : MPI_UNDEFINED, rank(comm), &sub_);
  }
  ~SubCommunicator() {
    if (sub_ != MPI_COMM_NULL) MPI_Comm_free(&sub_);
  }
  SubCommunicator(const SubCommunicator&) = delete;
  SubCommunicator& operator=(const SubCommunicator&) = delete;
  [[nodiscard]] MPI_Comm get() const { return sub_; }

 private:
  MPI_Comm sub_ = MPI_COMM_NULL;
};

/// Element by element over every rank of `comm`, in place (collective). `max_count`: the most
/// elements per MPI call (any length works; tests pass small values to exercise the pieces).
template <typename T, std::size_t N>
void sum(MPI_Comm comm, std::span<T, N> values, std::size_t max_count = kMaxMpiCount) {
  detail::all_reduce(comm, values, MPI_SUM, max_count);
}
template <typename T, std::size_t N>
void min(MPI_Comm comm, std::span<T, N> values, std::size_t max_count = kMaxMpiCount) {
  detail::all_reduce(comm, values, MPI_MIN, max_count);
}
template <typename T, std::size_t N>
void max(MPI_Comm comm, std::span<T, N> values, std::size_t max_count = kMaxMpiCount) {
  detail::all_reduce(comm, values, MPI_MAX, max_count);
}

/// One value over every rank of `comm` (collective).
template <typename T>
[[nodiscard]] T sum(MPI_Comm comm, T value) {
  sum(comm, std::span<T, 1>(&value, 1));
  return value;
}

/// `values` as `root` holds them, on every rank of `comm` (collective; the sizes must agree).
template <typename T, std::size_t N>
void broadcast(MPI_Comm comm, std::span<T, N> values, int root = 0, std::size_t max_count = kMaxMpiCount) {
  detail::in_pieces(values.size(), max_count, [&](std::size_t first, int count) {
    MPI_Bcast(values.data() + first, count, datatype<T>(), root, comm);
  });
}

}  // namespace sedwave::forward::parallel
