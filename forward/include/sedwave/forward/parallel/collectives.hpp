#pragma once
// Typed MPI collectives: sums, minima, maxima and broadcasts of spans (in place) and of single
// values, over any communicator. The element type picks the MPI datatype, so a count or a type
// cannot disagree with the buffer; the MPI error handler (abort by default) deals with failures.
//
// The scene side (channel/) uses these instead of raw MPI calls; MPI itself stays in the DEM
// domain, the task farm and the applications.
//
// MPI counts are int, and Open MPI 4.1 has no MPI-4 large-count calls (MPI_Bcast_c and kin): a span
// longer than 2^31 - 1 elements (a broadcast packing of 1.4e7 grains as bytes) is sent in pieces,
// a gather beyond 2^31 - 1 records goes in windows, and any other count that does not fit an int
// is refused (std::overflow_error) rather than wrapped.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstddef>
#include <exception>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
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

/// The part of [first, first + count) that falls in the window [lo, hi), as (offset, length).
inline std::array<std::size_t, 2> overlap(std::size_t first, std::size_t count, std::size_t lo, std::size_t hi) {
  const std::size_t begin = std::clamp(first, lo, hi), end = std::clamp(first + count, lo, hi);
  return {begin, end - begin};
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

/// The rank of `ranks` that answers for `key` (key mod ranks, non-negative for any key): a
/// directory that needs no table, as when ranks meet at one place per grain id to join records.
inline std::size_t rank_for_key(std::int64_t key, int ranks) {
  return static_cast<std::size_t>(((key % ranks) + ranks) % ranks);
}

/// The ranks of `comm` that pass `member` = true, as a communicator in the same rank order
/// (collective over `comm`; get() is MPI_COMM_NULL on the others), or the ranks of one colour.
/// Freed with this object.
class SubCommunicator {
 public:
  SubCommunicator(MPI_Comm comm, bool member) {
    MPI_Comm_split(comm, member ? 0 : MPI_UNDEFINED, rank(comm), &sub_);
  }
  /// A colour (>= 0) that picks this rank's communicator when `comm` is cut into several.
  struct Colour {
    int value = 0;
  };
  /// The ranks of `comm` with this rank's colour, in the same rank order (every rank is in one).
  SubCommunicator(MPI_Comm comm, Colour colour) { MPI_Comm_split(comm, colour.value, rank(comm), &sub_); }
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
template <typename T>
[[nodiscard]] T min(MPI_Comm comm, T value) {
  min(comm, std::span<T, 1>(&value, 1));
  return value;
}
template <typename T>
[[nodiscard]] T max(MPI_Comm comm, T value) {
  max(comm, std::span<T, 1>(&value, 1));
  return value;
}

/// Whether `value` is true on any rank of `comm` (collective).
[[nodiscard]] inline bool any(MPI_Comm comm, bool value) {
  int v = value ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LOR, comm);
  return v != 0;
}

/// The sum of `value` over the ranks before this one (0 on rank 0; collective).
template <typename T>
[[nodiscard]] T exclusive_prefix_sum(MPI_Comm comm, T value) {
  T before{};
  MPI_Exscan(&value, &before, 1, datatype<T>(), MPI_SUM, comm);
  return rank(comm) == 0 ? T{} : before;  // MPI_Exscan leaves rank 0's result undefined
}

/// Every rank's `value`, in rank order, on every rank (collective).
template <typename T>
[[nodiscard]] std::vector<T> all_gather(MPI_Comm comm, T value) {
  std::vector<T> all(static_cast<std::size_t>(size(comm)));
  MPI_Allgather(&value, 1, datatype<T>(), all.data(), 1, datatype<T>(), comm);
  return all;
}

/// `values` as `root` holds them, on every rank of `comm` (collective; the sizes must agree).
template <typename T, std::size_t N>
void broadcast(MPI_Comm comm, std::span<T, N> values, int root = 0, std::size_t max_count = kMaxMpiCount) {
  detail::in_pieces(values.size(), max_count, [&](std::size_t first, int count) {
    MPI_Bcast(values.data() + first, count, datatype<T>(), root, comm);
  });
}

/// One value as `root` holds it, on every rank of `comm` (collective).
template <typename T>
void broadcast(MPI_Comm comm, T& value, int root = 0) requires std::is_arithmetic_v<T> {
  broadcast(comm, std::span<T, 1>(&value, 1), root);
}

/// A vector (length and contents) as `root` holds it, on every rank of `comm` (collective). Numbers
/// go as their MPI type, trivially copyable records (grains) as their bytes.
template <typename T>
void broadcast(MPI_Comm comm, std::vector<T>& values, int root = 0, std::size_t max_count = kMaxMpiCount) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::uint64_t length = values.size();
  broadcast(comm, length, root);
  values.resize(static_cast<std::size_t>(length));
  if constexpr (std::is_arithmetic_v<T>) {
    broadcast(comm, std::span(values), root, max_count);
  } else {
    broadcast(comm, std::as_writable_bytes(std::span(values)), root, max_count);
  }
}

/// A string as `root` holds it, on every rank of `comm` (collective).
inline void broadcast(MPI_Comm comm, std::string& text, int root = 0) {
  std::uint64_t length = text.size();
  broadcast(comm, length, root);
  text.resize(static_cast<std::size_t>(length));
  broadcast(comm, std::span(text.data(), text.size()), root);
}

/// Trivially copyable records from every rank on rank 0, in rank order (empty elsewhere;
/// collective). Counted in records, not bytes; a total beyond `max_count` records goes in windows
/// of the rank-ordered sequence, each one MPI_Gatherv whose counts and displacements fit an int.
template <typename T>
std::vector<T> gather_on_root(MPI_Comm comm, const std::vector<T>& local, std::size_t max_count = kMaxMpiCount) {
  const RecordType<T> record;
  const std::vector<std::uint64_t> counts = all_gather(comm, std::uint64_t{local.size()});
  std::vector<std::size_t> first(counts.size() + 1, 0);  // where each rank's records start
  for (std::size_t r = 0; r < counts.size(); ++r) first[r + 1] = first[r] + static_cast<std::size_t>(counts[r]);
  const std::size_t total = first.back();
  const bool root = rank(comm) == 0;
  const auto me = static_cast<std::size_t>(rank(comm));
  std::vector<T> all(root ? total : 0);
  std::vector<int> window_counts(counts.size()), window_displs(counts.size());
  detail::in_pieces(total, max_count, [&](std::size_t lo, int length) {
    const std::size_t hi = lo + static_cast<std::size_t>(length);
    for (std::size_t r = 0; r < counts.size(); ++r) {
      const auto [at, n] = detail::overlap(first[r], static_cast<std::size_t>(counts[r]), lo, hi);
      window_counts[r] = mpi_count(n);
      window_displs[r] = mpi_count(at - lo);
    }
    const auto [mine, n_mine] = detail::overlap(first[me], local.size(), lo, hi);
    const T* send = n_mine > 0 ? local.data() + (mine - first[me]) : local.data();
    MPI_Gatherv(send, mpi_count(n_mine), record.get(), root ? all.data() + lo : nullptr,
                window_counts.data(), window_displs.data(), record.get(), 0, comm);
  });
  return all;
}

/// Sends per-destination vectors (one per rank of `comm`) of trivially copyable records with one
/// all-to-all; returns what arrived, ordered by source rank (deterministic; collective). Counted in
/// records, not bytes; a total beyond 2^31 - 1 records sent or received on any rank is refused
/// with std::overflow_error on every rank.
template <typename T>
std::vector<T> all_to_all(MPI_Comm comm, const std::vector<std::vector<T>>& outgoing) {
  const RecordType<T> record;
  const std::size_t n = outgoing.size();
  if (n != static_cast<std::size_t>(size(comm))) {
    throw std::invalid_argument("MPI all-to-all: " + std::to_string(n) + " destinations for " +
                                std::to_string(size(comm)) + " ranks");
  }
  // Counts go as ints (an oversized one as 0, refused below); the totals each rank sends and
  // receives are checked in one agreement, so every rank throws or none does.
  std::size_t send_total = 0;
  std::vector<int> send_counts(n), recv_counts(n);
  for (std::size_t r = 0; r < n; ++r) {
    send_total += outgoing[r].size();
    send_counts[r] = outgoing[r].size() <= kMaxMpiCount ? static_cast<int>(outgoing[r].size()) : 0;
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  std::size_t recv_total = 0;
  for (const int c : recv_counts) recv_total += static_cast<std::size_t>(c);
  if (any(comm, send_total > kMaxMpiCount || recv_total > kMaxMpiCount)) {
    throw std::overflow_error("MPI all-to-all: the records to send or receive on some rank exceed the largest "
                              "MPI count (2^31 - 1)");
  }
  const std::vector<int> send_displs = displacements(send_counts);
  const std::vector<int> recv_displs = displacements(recv_counts);
  std::vector<T> send(static_cast<std::size_t>(send_displs.back()) + outgoing.back().size());
  for (std::size_t r = 0; r < n; ++r) std::copy(outgoing[r].begin(), outgoing[r].end(), send.begin() + send_displs[r]);
  std::vector<T> incoming(static_cast<std::size_t>(recv_displs.back()) + static_cast<std::size_t>(recv_counts.back()));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), record.get(), incoming.data(),
                recv_counts.data(), recv_displs.data(), record.get(), comm);
  return incoming;
}

/// Runs `work` and returns "" where it returns, else what it threw: its message, or `fallback` for an
/// exception without one or not derived from std::exception. A rank's own part of a collective
/// job, whose outcome the ranks then agree on (throw_first_failure), whatever it throws.
template <class Work>
[[nodiscard]] std::string failure_of(Work&& work, const std::string& fallback) {
  try {
    work();
    return {};
  } catch (const std::exception& e) {
    return *e.what() ? e.what() : fallback;
  } catch (...) {
    return fallback;
  }
}

/// A failure that every rank of a communicator throws with the same message, after agreeing on it:
/// those ranks end together, none waits in a collective call for another, and one of them (the
/// communicator's rank 0) is the one to report it.
class AgreedFailure : public std::runtime_error {
 public:
  AgreedFailure(MPI_Comm comm, const std::string& what)
      : std::runtime_error(what), reporter_(rank(comm) == 0), ranks_(size(comm)) {}
  /// The same failure told with another message (context added on its way up).
  AgreedFailure(const AgreedFailure& failure, const std::string& what)
      : std::runtime_error(what), reporter_(failure.reporter_), ranks_(failure.ranks_) {}
  /// Whether this rank reports it.
  [[nodiscard]] bool reporter() const { return reporter_; }
  /// How many ranks throw it: the communicator's size.
  [[nodiscard]] int ranks() const { return ranks_; }

 private:
  bool reporter_;
  int ranks_;
};

/// Throws `Failure` (AgreedFailure or a kind of it) on every rank of `comm` with the message of the
/// lowest rank whose `error` is not empty, and returns where none has one (collective): ranks that
/// each did their own part agree on the outcome before going on into a collective that a failed
/// rank would not reach.
template <class Failure = AgreedFailure>
void throw_first_failure(MPI_Comm comm, std::string error) {
  static_assert(std::is_base_of_v<AgreedFailure, Failure>);
  const int me = rank(comm), n = size(comm);
  const int first_failing = min(comm, error.empty() ? n : me);
  if (first_failing == n) return;
  broadcast(comm, error, first_failing);
  throw Failure(comm, error);
}

/// Asks `question` (returning bool) on rank 0 alone and gives every rank its answer (collective):
/// ranks that must go the same way on what one look at a shared filesystem finds.
template <class Question>
[[nodiscard]] bool root_says(MPI_Comm comm, Question question) {
  int yes = rank(comm) == 0 && question() ? 1 : 0;
  broadcast(comm, yes);
  return yes == 1;
}

/// Runs `job` on rank 0 of `comm` with every rank's records, a chunk at a time, while the other
/// ranks send theirs (collective): a file of a spread packing that no rank holds whole.
/// `job(pieces)` calls `pieces(visit)` up to `passes` times; each call hands visit(std::span<const T>)
/// every rank's records in rank order (rank 0's own first, whole; then the others' in chunks of at
/// most 8 MiB and `max_count` records, each message one chunk), so rank 0 holds its own records and
/// one chunk of another rank's. The chunk's buffer is allocated before anything is sent, and a pass
/// never stops half way: whatever fails on rank 0 (the buffer, the job, or a visit, which skips the
/// records after it), every record sent is received, so no rank is left waiting, and every rank then
/// throws AgreedFailure with the failure's message.
template <typename T, class Job>
void on_root_with_pieces(MPI_Comm comm, std::span<const T> local, int passes, Job job,
                         std::size_t max_count = kMaxMpiCount) {
  constexpr int kPieceTag = 0x7071;
  constexpr std::size_t kChunkBytes = std::size_t{8} << 20;
  const std::size_t chunk = std::min(max_count, std::max<std::size_t>(1, kChunkBytes / sizeof(T)));
  const RecordType<T> record;
  const std::vector<std::uint64_t> counts = all_gather(comm, std::uint64_t{local.size()});
  const bool root = rank(comm) == 0;
  std::vector<T> buffer;
  std::string error;
  if (root) {
    const std::string message = "cannot hold a chunk of " + std::to_string(chunk) + " records on rank 0";
    if (!failure_of([&] { buffer.resize(chunk); }, message).empty()) error = message;
  }
  throw_first_failure(comm, error);
  if (!root) {
    for (int pass = 0; pass < passes; ++pass) {
      detail::in_pieces(local.size(), chunk, [&](std::size_t first, int count) {
        MPI_Send(local.data() + first, count, record.get(), 0, kPieceTag, comm);
      });
    }
    throw_first_failure(comm, error);
    return;
  }
  int done = 0;
  const auto pieces = [&](auto&& visit) {
    if (done == passes) throw std::logic_error("on_root_with_pieces: more passes than announced");
    ++done;
    std::string failure;
    const auto take = [&](std::span<const T> records) {  // whatever visit throws, the pass goes on
      if (failure.empty()) failure = failure_of([&] { visit(records); }, "failed on rank 0");
    };
    take(local);
    for (std::size_t r = 1; r < counts.size(); ++r) {
      detail::in_pieces(static_cast<std::size_t>(counts[r]), chunk, [&](std::size_t, int count) {
        MPI_Recv(buffer.data(), count, record.get(), static_cast<int>(r), kPieceTag, comm, MPI_STATUS_IGNORE);
        if (count > 0) take(std::span<const T>(buffer.data(), static_cast<std::size_t>(count)));
      });
    }
    if (!failure.empty()) throw std::runtime_error(failure);
  };
  error = failure_of([&] { job(pieces); }, "failed on rank 0");
  while (done < passes) pieces([](std::span<const T>) {});  // receive what the others still send
  throw_first_failure(comm, error);
}

/// Waits until every rank of `comm` has come here (a barrier), sleeping `nap` between looks instead
/// of spinning as MPI's own waits do: for ranks that may wait long for one of them (rank 0 waiting
/// for a lock that another job holds through a whole preparation).
inline void barrier_sleeping(MPI_Comm comm, std::chrono::milliseconds nap = std::chrono::milliseconds(20)) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(comm, &request);
  int done = 0;
  MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  while (done == 0) {
    std::this_thread::sleep_for(nap);
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

/// Folds `step` over the ranks of `comm` one after another in rank order (collective): rank 0 calls
/// step(initial), rank r step(what rank r - 1's returned), each once the one before has finished,
/// and every rank returns the last rank's result. An accumulation over records spread in rank order
/// (a hash) that moves no record; T is trivially copyable. A token passed along carries the failure
/// so far: once a rank's step throws, the ranks after it skip theirs, and every rank then throws
/// AgreedFailure with the first failing rank's message (no rank is left waiting for a token).
template <class T, class Step>
[[nodiscard]] T fold_in_turn(MPI_Comm comm, T initial, Step step) {
  static_assert(std::is_trivially_copyable_v<T>);
  constexpr int kTokenTag = 0x7070;
  struct Token {
    int failed;
    T state;
  };
  const int me = rank(comm), n = size(comm);
  Token token{0, initial};
  std::string error;
  if (me > 0) MPI_Recv(&token, sizeof(Token), MPI_BYTE, me - 1, kTokenTag, comm, MPI_STATUS_IGNORE);
  if (token.failed == 0) {
    // Whatever the step throws, the token goes on.
    error = failure_of([&] { token.state = step(token.state); }, "failed on rank " + std::to_string(me));
    token.failed = error.empty() ? 0 : 1;
  }
  if (me + 1 < n) MPI_Send(&token, sizeof(Token), MPI_BYTE, me + 1, kTokenTag, comm);
  throw_first_failure(comm, error);
  broadcast(comm, std::as_writable_bytes(std::span(&token.state, 1)), n - 1);
  return token.state;
}

/// Runs `turn` on every rank of `comm` one after another in rank order (rank 0 first), each rank
/// starting once the one before has finished: ranks writing their own part of one file in turn, so
/// that no rank holds everything (collective). Failures as in fold_in_turn.
template <class Turn>
void in_turn(MPI_Comm comm, Turn turn) {
  (void)fold_in_turn(comm, 0, [&](int) {
    turn();
    return 0;
  });
}

}  // namespace sedwave::forward::parallel
