// Simulation-based calibration of `sedwave invert --method posterior` (bench/posterior_calibration.hpp
// says how the data sets are drawn): coverage of the 68 % and 95 % credible intervals of kappa, d and
// gamma, and a 10-bin histogram of the truth's rank among the draws (uniform when calibrated).
//
// With "evidence" as the fourth argument the draws are the evidence's (model_evidence: resampled
// importance draws where importance sampling serves, as `sedwave compare`'s bands and corner plot).
//
//   build/bin/bench_posterior_calibration [data_sets=200] [seed=1] [steps=3000] [posterior|evidence]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "posterior_calibration.hpp"

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200;
  const unsigned seed = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 1u;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 3000;
  const bool evidence = argc > 4 && std::string(argv[4]) == "evidence";
  const auto sampler = evidence ? sedwave::bench::CalibrationSampler::Evidence : sedwave::bench::CalibrationSampler::Posterior;
  using sedwave::bench::kCalibrationPriors;
  std::array<int, 3> in68{}, in95{};
  std::array<std::array<int, 10>, 3> ranks{};
  int converged = 0, importance = 0;
  for (int k = 0; k < n; ++k) {
    const sedwave::bench::CalibrationResult r = sedwave::bench::run_calibration_set(seed, k, steps, sampler);
    converged += r.converged;
    importance += r.importance;
    for (std::size_t i = 0; i < 3; ++i) {
      in68[i] += r.in68[i];
      in95[i] += r.in95[i];
      ++ranks[i][std::min(9, static_cast<int>(10.0 * r.rank_fraction[i]))];
    }
  }
  std::printf("posterior calibration: lattice model, kappa, d, gamma, %d data sets (seed %u, %s); "
              "%d converged, %d by importance sampling\n", n, seed,
              evidence ? "the evidence's draws" : ("the posterior sampler, " + std::to_string(steps) + " steps").c_str(),
              converged, importance);
  std::printf("%-6s | %8s %8s | rank histogram (10 bins, expected %.1f each)\n", "param", "68 %", "95 %", n / 10.0);
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("%-6s | %8.3f %8.3f |", kCalibrationPriors[i].name, double(in68[i]) / n, double(in95[i]) / n);
    for (int b : ranks[i]) std::printf(" %3d", b);
    std::printf("\n");
  }
  return 0;
}
