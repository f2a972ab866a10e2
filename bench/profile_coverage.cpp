// Coverage of the 68 % profile-likelihood intervals of `sedwave invert` (lattice chain model) over
// many synthetic data sets (bench/coverage_study.hpp says how they are drawn). Prints, per
// quantity, how often the interval contains the truth where the report calls the quantity
// determined (nominal 0.68) and where it does not (the interval then follows a flat direction to
// a bound and covers more: conservative), and checks that every side reported open is open.
//
//   build/bin/bench_profile_coverage [data_sets=200] [seed=1]
#include <cstdio>
#include <cstdlib>

#include "coverage_study.hpp"

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  const unsigned seed = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 1u;
  using sedwave::bench::kCoverageQuantities;
  std::array<int, 8> contains{}, determined{}, determined_contains{}, by_design{}, by_design_contains{};
  int open_checked = 0, open_wrong = 0;
  for (int i = 0; i < n; ++i) {
    const sedwave::bench::DataSetResult r = sedwave::bench::run_data_set(seed, i);
    for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
      contains[q] += r.checks[q].contains;
      determined[q] += r.checks[q].determined;
      determined_contains[q] += r.checks[q].determined && r.checks[q].contains;
      by_design[q] += r.checks[q].design_determined;
      by_design_contains[q] += r.checks[q].design_determined && r.checks[q].contains;
    }
    const auto [checked, wrong] = sedwave::bench::verify_open_sides(seed, i);
    open_checked += checked;
    open_wrong += wrong;
  }
  std::printf("68 %% profile intervals, lattice model, %d synthetic data sets (seed %u); nominal 0.68\n", n, seed);
  std::printf("%-18s | %9s %9s | %9s %9s | %9s %9s | %9s\n", "quantity", "all", "coverage", "by design",
              "coverage", "by fit", "coverage", "not det.");
  for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
    auto rate = [](int hits, int count) { return count ? double(hits) / count : 0.0; };
    const int undetermined = n - determined[q];
    std::printf("%-18s | %9d %9.3f | %9d %9.3f | %9d %9.3f | %9.3f\n", kCoverageQuantities[q], n,
                rate(contains[q], n), by_design[q], rate(by_design_contains[q], by_design[q]), determined[q],
                rate(determined_contains[q], determined[q]), rate(contains[q] - determined_contains[q], undetermined));
  }
  std::printf("columns: data sets and coverage over all; where the design determines the quantity (linearised at the "
              "truth, noise-free); where the fit calls it determined; and the coverage where the fit does not "
              "(intervals along flat directions to a bound)\nbinomial 1 sigma at 0.68: %.3f for %d data sets\n",
              sedwave::bench::coverage_sigma(n), n);
  std::printf("open sides of parameter intervals checked: %d, not open (Delta chi2 > 1.05 at the bound, also with the "
              "other bounds lifted): %d\n",
              open_checked, open_wrong);
  return 0;
}
