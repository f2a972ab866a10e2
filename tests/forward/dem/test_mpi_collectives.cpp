// Counts beyond what one MPI call takes (run with mpirun -np 4): spans longer than the largest
// count per call go in pieces, records are counted as records (not bytes), and a count that does
// not fit an int is refused rather than wrapped. Small piece sizes stand in for 2^31 - 1.
#include <gtest/gtest.h>

#include <climits>
#include <cstdint>
#include <numeric>
#include <stdexcept>
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
  const std::vector<dem::Grain> all = dem::gather_on_root(MPI_COMM_WORLD, mine);
  if (r != 0) {
    EXPECT_TRUE(all.empty());
    return;
  }
  ASSERT_EQ(all.size(), static_cast<std::size_t>(n * (n + 1) / 2));
  std::size_t at = 0;
  for (int from = 0; from < n; ++from)
    for (int k = 0; k <= from; ++k, ++at) {
      EXPECT_EQ(all[at].id, 100 * from + k);
      EXPECT_EQ(all[at].position.y, double(k));
      EXPECT_EQ(all[at].torque.y, double(from));
      EXPECT_EQ(all[at].torque.z, double(k));
    }
}

}  // namespace
}  // namespace sedwave::forward::parallel
