// The 68 % profile-likelihood intervals are calibrated: over synthetic data sets drawn from known
// parameters (bench/coverage_study.hpp: gamma_hat 0.01-300, d 0.05-2 mm, 1-10 % noise, bands from
// the continuum limit to the lattice's dispersion), each quantity's interval contains the truth at
// the nominal rate. The full study (300 data sets) is bench/profile_coverage.cpp; this is its small
// version: 60 data sets, each quantity within 3 binomial sigmas (+-0.18) of 0.68, all of them
// together within +-0.08.
#include <gtest/gtest.h>

#include "coverage_study.hpp"

namespace sedwave::bench {
namespace {

TEST(ProfileCoverage, SixtyEightPercentIntervalsContainTheTruthAtTheirNominalRate) {
  constexpr int kDataSets = 60;
  constexpr unsigned kSeed = 2;
  std::array<int, 8> contains{};
  for (int i = 0; i < kDataSets; ++i) {
    const DataSetResult r = run_data_set(kSeed, i);
    for (size_t q = 0; q < kCoverageQuantities.size(); ++q) contains[q] += r.checks[q].contains;
  }
  double pooled = 0.0;
  for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
    const double coverage = static_cast<double>(contains[q]) / kDataSets;
    pooled += coverage / static_cast<double>(kCoverageQuantities.size());
    EXPECT_NEAR(coverage, 0.68, 3.0 * coverage_sigma(kDataSets)) << kCoverageQuantities[q];
  }
  EXPECT_NEAR(pooled, 0.68, 0.08);
}

TEST(ProfileCoverage, SidesReportedOpenAreOpen) {
  int checked = 0;
  for (int i = 0; i < 12; ++i) {
    const auto [n, wrong] = verify_open_sides(3, i);
    checked += n;
    EXPECT_EQ(wrong, 0) << "data set " << i;
  }
  EXPECT_GT(checked, 0) << "no data set had an open side: the check checked nothing";
}

}  // namespace
}  // namespace sedwave::bench
