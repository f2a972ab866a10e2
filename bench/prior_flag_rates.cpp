// How often `sedwave invert --method posterior` flags an interval as prior-controlled
// (PosteriorQuantity::prior_dominated) on sets whose free parameters the data cannot place (ridges,
// straight and curved, from a band or one frequency: every free parameter should be flagged) and on
// sets whose free parameters they determine (none should be), under the default priors and under
// site priors; bench/prior_flag_study.hpp says how the sets are drawn. Prints the rates with their
// binomial standard errors, each parameter's rate, the rates of the derived quantities c0 and tau (which
// the straight ridge sets determine), and the range of the prior shares.
//
// The fits compute their likelihood profiles first, as `sedwave invert --method posterior` does;
// `no-profiles` leaves them out (the posterior's own tests alone).
//
//   build/bin/bench_prior_flag_rates [data_sets=60] [seed=1] [steps=3000] [each|quiet] [profiles|no-profiles]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "prior_flag_study.hpp"

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 60;
  const unsigned seed = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 1u;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 3000;
  const bool each_set = argc > 4 && std::string(argv[4]) == "each";
  const bool profiles = !(argc > 5 && std::string(argv[5]) == "no-profiles");
  using sedwave::bench::FlagSet;
  std::printf("prior-controlled flag: lattice model; %d sets of each kind (seed %u, %d steps, %s)\n", n, seed, steps,
              profiles ? "fits with likelihood profiles" : "fits without likelihood profiles");
  std::printf("%-40s | %9s %9s | %6s %6s %6s | %6s %6s | %-11s | %9s\n", "sets", "flagged", "+- 1 se", "kappa", "d",
              "gamma", "c0", "tau", "prior share", "converged");
  using sedwave::bench::FlagPriors;
  for (const FlagPriors priors : {FlagPriors::Default, FlagPriors::Site}) {
    for (const FlagSet kind : sedwave::bench::kFlagSets) {
      const std::string label = std::string(sedwave::bench::flag_set_name(kind)) +
                                (priors == FlagPriors::Default ? ", default priors" : ", site priors");
      int flagged = 0, converged = 0, c0 = 0, tau = 0;
      std::array<int, 3> each{};
      double lowest = 1.0, highest = 0.0;
      bool d_free = true;
      for (int k = 0; k < n; ++k) {
        const sedwave::bench::FlagSetResult r = sedwave::bench::run_flag_set(kind, seed, k, steps, priors, profiles);
        flagged += sedwave::bench::set_flagged(kind, r);
        converged += r.converged;
        c0 += r.c0_flagged;
        tau += r.tau_flagged;
        d_free = r.d_free;
        for (std::size_t i = 0; i < 3; ++i) {
          each[i] += r.flagged[i];
          if (i == 1 && !r.d_free) continue;
          lowest = std::min(lowest, r.prior_share[i]);
          highest = std::max(highest, r.prior_share[i]);
        }
        if (each_set) {
          std::fprintf(stderr, "%s, set %d: prior share kappa %.2f d %.2f gamma %.2f%s\n", label.c_str(), k,
                       r.prior_share[0], r.prior_share[1], r.prior_share[2], r.converged ? "" : " (not converged)");
        }
      }
      const double rate = static_cast<double>(flagged) / n;
      const auto share = [n](int count) { return static_cast<double>(count) / n; };
      char d_rate[16] = "  (fixed)";
      if (d_free) std::snprintf(d_rate, sizeof d_rate, "%6.2f", share(each[1]));
      std::printf("%-40s | %9.3f %9.3f | %6.2f %6s %6.2f | %6.2f %6.2f | %4.2f-%4.2f   | %5d/%-3d\n", label.c_str(), rate,
                  std::sqrt(rate * (1.0 - rate) / n), share(each[0]), d_rate, share(each[2]), share(c0), share(tau),
                  lowest, highest, converged, n);
    }
  }
  std::printf("a ridge set (ridge, one-frequency ridge, curved ridge) counts as flagged when every free parameter is; "
              "any other set when any is\n");
  return 0;
}
