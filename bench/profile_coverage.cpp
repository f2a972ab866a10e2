// Coverage of the 68 % profile-likelihood intervals of `sedwave invert` (lattice chain model) over
// many synthetic data sets (bench/coverage_study.hpp says how they are drawn). Prints, per
// quantity, how often the interval contains the truth, over all data sets and over those whose
// interval closed on both sides, and checks that every side reported open is open.
//
//   build/bin/bench_profile_coverage [data_sets=200] [seed=1]
#include <cstdio>
#include <cstdlib>

#include "coverage_study.hpp"

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  const unsigned seed = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 1u;
  using sedwave::bench::kCoverageQuantities;
  std::array<int, 8> contains{}, closed{}, closed_contains{};
  int open_checked = 0, open_wrong = 0;
  for (int i = 0; i < n; ++i) {
    const sedwave::bench::DataSetResult r = sedwave::bench::run_data_set(seed, i);
    for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
      contains[q] += r.checks[q].contains;
      closed[q] += r.checks[q].closed;
      closed_contains[q] += r.checks[q].closed && r.checks[q].contains;
    }
    const auto [checked, wrong] = sedwave::bench::verify_open_sides(seed, i);
    open_checked += checked;
    open_wrong += wrong;
  }
  std::printf("68 %% profile intervals, lattice model, %d synthetic data sets (seed %u); nominal 0.68\n", n, seed);
  std::printf("%-18s %10s %12s %8s %14s\n", "quantity", "coverage", "(1 sigma)", "closed", "closed cov.");
  for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
    std::printf("%-18s %10.3f %12.3f %8d %14.3f\n", kCoverageQuantities[q], double(contains[q]) / n,
                sedwave::bench::coverage_sigma(n), closed[q],
                closed[q] ? double(closed_contains[q]) / closed[q] : 0.0);
  }
  std::printf("open sides of parameter intervals checked: %d, not open (Delta chi2 > 1.05 at the bound): %d\n",
              open_checked, open_wrong);
  return 0;
}
