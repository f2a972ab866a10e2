// The typed collectives (run with mpirun -np 4). Counts beyond what one MPI call takes: spans
// longer than the largest count per call go in pieces, gathers in windows, records are counted as
// records (not bytes), and a count that does not fit an int is refused rather than wrapped. Small
// piece and window sizes stand in for 2^31 - 1.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::parallel {
namespace {

TEST(Collectives, CountsAboveTheLargestIntAreRefusedNotWrapped) {
  EXPECT_EQ(mpi_count(std::size_t{INT_MAX}), INT_MAX);
  EXPECT_THROW((void)mpi_count(std::size_t{1} << 31), std::overflow_error);
  // 1.5e7 grains of 152 bytes: the byte count that used to wrap to a negative int.
  EXPECT_THROW((void)mpi_count(std::size_t{15'000'000} * 152), std::overflow_error);
  EXPECT_EQ(mpi_count(std::size_t{15'000'000}), 15'000'000);  // the same grains counted as records
}

TEST(Collectives, BroadcastAndSumInPiecesMatchOneCall) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  constexpr std::size_t kLength = 1000;
  for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, kLength - 1, kLength, kMaxMpiCount}) {
    std::vector<std::int64_t> values(kLength);
    std::iota(values.begin(), values.end(), 1000 * std::int64_t{r});
    broadcast(MPI_COMM_WORLD, std::span(values), 0, piece);
    for (std::size_t i = 0; i < kLength; ++i) ASSERT_EQ(values[i], static_cast<std::int64_t>(i)) << "piece " << piece;

    std::iota(values.begin(), values.end(), std::int64_t{r});
    sum(MPI_COMM_WORLD, std::span(values), piece);
    for (std::size_t i = 0; i < kLength; ++i)
      ASSERT_EQ(values[i], static_cast<std::int64_t>(i) * n + std::int64_t{n} * (n - 1) / 2) << "piece " << piece;
  }
  std::vector<double> empty;
  sum(MPI_COMM_WORLD, std::span(empty), 3);  // zero elements: one call, nothing to do
}

TEST(Collectives, SubCommunicatorHoldsTheMembersOnlyInRankOrder) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const bool member = r % 2 == 0;  // as the groups' leaders of ranks_per_point = 2
  const SubCommunicator even(MPI_COMM_WORLD, member);
  if (!member) {
    EXPECT_EQ(even.get(), MPI_COMM_NULL);
    return;
  }
  ASSERT_NE(even.get(), MPI_COMM_NULL);
  EXPECT_EQ(size(even.get()), (n + 1) / 2);
  EXPECT_EQ(rank(even.get()), r / 2);
  std::int64_t from_root = r == 0 ? 42 : -1;
  broadcast(even.get(), std::span(&from_root, 1));
  EXPECT_EQ(from_root, 42);
}

TEST(Collectives, GatherCountsGrainRecordsInRankOrder) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  std::vector<dem::Grain> mine(static_cast<std::size_t>(r + 1));
  for (std::size_t k = 0; k < mine.size(); ++k) {
    mine[k].id = 100 * r + static_cast<std::int64_t>(k);
    mine[k].position = {double(r), double(k), -1.0};
    mine[k].torque = {0.5, double(r), double(k)};  // the record's last bytes
  }
  // Windows smaller than the total stand in for a gather beyond 2^31 - 1 records: a window may
  // start or end inside one rank's records, or hold none of a rank's.
  for (const std::size_t window : {std::size_t{1}, std::size_t{2}, std::size_t{4}, kMaxMpiCount}) {
    const std::vector<dem::Grain> all = gather_on_root(MPI_COMM_WORLD, mine, window);
    if (r != 0) {
      EXPECT_TRUE(all.empty());
      continue;
    }
    ASSERT_EQ(all.size(), static_cast<std::size_t>(n * (n + 1) / 2));
    std::size_t at = 0;
    for (int from = 0; from < n; ++from)
      for (int k = 0; k <= from; ++k, ++at) {
        EXPECT_EQ(all[at].id, 100 * from + k) << "window " << window;
        EXPECT_EQ(all[at].position.y, double(k));
        EXPECT_EQ(all[at].torque.y, double(from));
        EXPECT_EQ(all[at].torque.z, double(k));
      }
  }
}

TEST(Collectives, GatherWithEmptyRanksAndWindowsOfEveryRankBoundary) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  // Odd ranks hold nothing; even ranks hold 3 values each.
  std::vector<std::int64_t> mine(r % 2 == 0 ? 3 : 0);
  std::iota(mine.begin(), mine.end(), std::int64_t{10} * r);
  std::vector<std::int64_t> expected;
  for (int from = 0; from < n; from += 2)
    for (std::int64_t k = 0; k < 3; ++k) expected.push_back(10 * from + k);
  for (std::size_t window = 1; window <= expected.size() + 1; ++window) {
    const std::vector<std::int64_t> all = gather_on_root(MPI_COMM_WORLD, mine, window);
    if (r == 0) EXPECT_EQ(all, expected) << "window " << window;
    else EXPECT_TRUE(all.empty());
  }
}

TEST(Collectives, MinMaxAnyPrefixSumAndAllGatherOfOneValue) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  EXPECT_EQ(min(MPI_COMM_WORLD, 5.0 + r), 5.0);
  EXPECT_EQ(max(MPI_COMM_WORLD, 5.0 + r), 5.0 + (n - 1));
  EXPECT_FALSE(any(MPI_COMM_WORLD, false));
  EXPECT_TRUE(any(MPI_COMM_WORLD, r == n - 1));  // true on one rank only
  EXPECT_EQ(exclusive_prefix_sum(MPI_COMM_WORLD, std::int64_t{r + 1}), std::int64_t{r} * (r + 1) / 2);
  const std::vector<double> all = all_gather(MPI_COMM_WORLD, 0.5 * r);
  ASSERT_EQ(all.size(), static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) EXPECT_EQ(all[static_cast<std::size_t>(k)], 0.5 * k);
}

TEST(Collectives, BroadcastOfStringsAndVectorsCarriesTheRootsLength) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const int root = n - 1;
  std::string text = r == root ? std::string("from the last rank") : std::string(100, 'x');
  broadcast(MPI_COMM_WORLD, text, root);
  EXPECT_EQ(text, "from the last rank");
  std::string empty = r == 0 ? std::string() : std::string("not empty");
  broadcast(MPI_COMM_WORLD, empty);
  EXPECT_TRUE(empty.empty());
  std::vector<std::uint64_t> values = r == 0 ? std::vector<std::uint64_t>{1, 2, 3, 4, 5} : std::vector<std::uint64_t>{};
  broadcast(MPI_COMM_WORLD, values, 0, 2);  // in pieces of two
  EXPECT_EQ(values, (std::vector<std::uint64_t>{1, 2, 3, 4, 5}));
}

TEST(Collectives, AllToAllDeliversRecordsBySourceRank) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  // Rank r sends `to` copies of (r, to) to rank `to`.
  std::vector<std::vector<std::array<std::int32_t, 2>>> out(static_cast<std::size_t>(n));
  for (int to = 0; to < n; ++to) out[static_cast<std::size_t>(to)].assign(static_cast<std::size_t>(to), {r, to});
  const auto in = all_to_all(MPI_COMM_WORLD, out);
  ASSERT_EQ(in.size(), static_cast<std::size_t>(n * r));
  for (std::size_t k = 0; k < in.size(); ++k) {
    EXPECT_EQ(in[k][0], static_cast<std::int32_t>(k) / r);  // by source rank, in order
    EXPECT_EQ(in[k][1], r);
  }
}

// Turns run in rank order, one at a time; a failing turn is passed along, so every rank throws the
// failing rank's message and no later rank runs or waits forever.
TEST(Collectives, TurnsRunInRankOrderAndAFailureReachesEveryRank) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  // Each turn appends its rank to one file: the file lists the ranks in order, each once.
  std::string path = (std::filesystem::temp_directory_path() / ("sedwave_turns_" + std::to_string(::getpid()))).string();
  broadcast(MPI_COMM_WORLD, path);
  in_turn(MPI_COMM_WORLD, [&] { std::ofstream(path, r == 0 ? std::ios::trunc : std::ios::app) << r << ' '; });
  if (r == 0) {
    std::ifstream in(path);
    std::vector<int> order{std::istream_iterator<int>(in), std::istream_iterator<int>()};
    std::vector<int> expected(static_cast<std::size_t>(n));
    std::iota(expected.begin(), expected.end(), 0);
    EXPECT_EQ(order, expected);
    std::filesystem::remove(path);
  }

  const int failing = n > 1 ? 1 : 0;
  bool ran = false;
  try {
    in_turn(MPI_COMM_WORLD, [&] {
      ran = true;
      if (r == failing) throw std::runtime_error("rank " + std::to_string(r) + " cannot open its output");
    });
    ADD_FAILURE() << "rank " << r << " did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), ("rank " + std::to_string(failing) + " cannot open its output").c_str());
  }
  EXPECT_EQ(ran, r <= failing) << "rank " << r;  // the ranks after the failing one skip their turn
}

// A fold passes its state from rank to rank: an order-dependent step (a polynomial hash of the ranks)
// gives every rank the value one process computes with the ranks in order. A failure is agreed:
// every rank throws it, and rank 0 alone tells it.
TEST(Collectives, AFoldPassesItsStateInRankOrder) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const auto step = [](std::uint64_t state, int k) { return state * 1000003u + static_cast<std::uint64_t>(k + 1); };
  std::uint64_t serial = 7;
  for (int k = 0; k < n; ++k) serial = step(serial, k);
  EXPECT_EQ(fold_in_turn(MPI_COMM_WORLD, std::uint64_t{7}, [&](std::uint64_t s) { return step(s, r); }), serial);

  try {
    (void)fold_in_turn(MPI_COMM_WORLD, 0.0, [&](double s) {
      if (r == n - 1) throw std::runtime_error("the last rank fails");
      return s + 1.0;
    });
    ADD_FAILURE() << "rank " << r << " did not throw";
  } catch (const AgreedFailure& e) {
    EXPECT_STREQ(e.what(), "the last rank fails");
    EXPECT_EQ(e.reporter(), r == 0);
    EXPECT_EQ(e.ranks(), n);
  }
}

TEST(Collectives, ColoursCutTheRanksIntoCommunicatorsInRankOrder) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const SubCommunicator place(MPI_COMM_WORLD, SubCommunicator::Colour{r % 2});
  ASSERT_NE(place.get(), MPI_COMM_NULL);
  EXPECT_EQ(size(place.get()), r % 2 == 0 ? (n + 1) / 2 : n / 2);
  EXPECT_EQ(rank(place.get()), r / 2);
  const std::vector<int> members = all_gather(place.get(), r);
  for (std::size_t k = 0; k < members.size(); ++k) EXPECT_EQ(members[k], static_cast<int>(2 * k) + r % 2);
}

/// Rank r's records for the piece tests: r + 1 values r * 100 + k (rank 0's one, rank 1's two, ...).
std::vector<std::int64_t> piece_of(int r) {
  std::vector<std::int64_t> v(static_cast<std::size_t>(r + 1));
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = r * 100 + static_cast<std::int64_t>(k);
  return v;
}

TEST(Collectives, RootTakesEveryRanksPieceInRankOrderOnceEachPass) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const std::vector<std::int64_t> mine = piece_of(r);
  std::vector<std::int64_t> expected;
  for (int k = 0; k < n; ++k) {
    const std::vector<std::int64_t> p = piece_of(k);
    expected.insert(expected.end(), p.begin(), p.end());
  }
  for (const std::size_t max_count : {kMaxMpiCount, std::size_t{2}}) {  // 2: chunks of 2 records
    std::vector<std::int64_t> first, second;
    std::size_t largest = 0;
    on_root_with_pieces(MPI_COMM_WORLD, std::span<const std::int64_t>(mine), 2, [&](auto&& pieces) {
      pieces([&](std::span<const std::int64_t> p) {
        first.insert(first.end(), p.begin(), p.end());
        largest = std::max(largest, p.size());
      });
      pieces([&](std::span<const std::int64_t> p) { second.insert(second.end(), p.begin(), p.end()); });
    }, max_count);
    if (r != 0) continue;
    EXPECT_EQ(first, expected);
    EXPECT_EQ(second, expected);
    EXPECT_EQ(largest, max_count == 2 ? std::size_t{2} : static_cast<std::size_t>(n)) << "a chunk at a time";
  }
}

TEST(Collectives, AFailureOnTheRootReachesEveryRankWhereverItHappens) {
  const int r = rank(MPI_COMM_WORLD), n = size(MPI_COMM_WORLD);
  const std::vector<std::int64_t> mine = piece_of(r);
  // Before any piece is taken (the output cannot be created), in the middle of the pieces, and after
  // one of two passes: every rank throws the root's message, and no rank waits for ever.
  for (const int fail_at : {-1, n / 2, n}) {
    try {
      on_root_with_pieces(MPI_COMM_WORLD, std::span<const std::int64_t>(mine), 2, [&](auto&& pieces) {
        if (fail_at < 0) throw std::runtime_error("cannot create the file");
        int seen = 0;
        pieces([&](std::span<const std::int64_t>) {
          if (seen++ == fail_at) throw std::runtime_error("disk full");
        });
        throw std::runtime_error("disk full");
      });
      ADD_FAILURE() << "rank " << r << " did not throw";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), fail_at < 0 ? "cannot create the file" : "disk full") << "rank " << r;
    }
  }
}

}  // namespace
}  // namespace sedwave::forward::parallel
