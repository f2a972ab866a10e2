// Is the evidence as accurate as it says? For every model family (sediment::model_examples()), on a
// synthetic set it generated (its defaults; 20 log-spaced frequencies over 100 Hz - 100 kHz, 5 %
// attenuation and 1 % sound-speed noise), with two free parameters (the first two of its typical
// set) under default priors: ln Z from model_evidence (default options) over many seeds against
// brute-force quadrature of the same integral (inversion::evidence_integrand). Prints per model the
// reference, how many runs land within 2 stated sigmas (>= 90 % expected), the mean difference with
// its standard error (within 2 of 0 expected), and the run lengths and times.
//
// The quadrature: bench/evidence_quadrature.hpp (n = 300); its change from n to 2n is printed as the
// reference's own error.
//
//   build/bin/bench_evidence_accuracy [seeds=20] [model-substring]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "evidence_quadrature.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using namespace sedwave;

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::string only = argc > 2 ? argv[2] : "";
  std::printf("evidence accuracy: model_evidence (default options) over %d seeds against quadrature; 2 free "
              "parameters, default priors\n", seeds);
  std::printf("%-22s %-22s %10s %7s %9s %16s %8s %8s %7s\n", "model", "free", "quadrature", "+-", "in 2 sd",
              "mean diff +- se", "sd(lnZ)", "stated", "s/run");
  const auto families = sediment::model_examples();
  for (const auto& model : families) {
    const std::string name = model->name();
    if (!only.empty() && name.find(only) == std::string::npos) continue;
    std::string typical = sediment::typical_free_parameters(*model);
    const std::string free = typical.substr(0, typical.find(',', typical.find(',') + 1));
    const inversion::ObservationSet data = inversion::synthetic_observations(
        *model, inversion::FitParameters(model->parameters()), {100.0, 1e5, 20, 0.05, 0.01, 7});
    inversion::FitParameters start(model->parameters());
    start.set_free_from_list(free);
    const inversion::FitOptions fit_options{.method = inversion::FitMethod::Global, .profile_likelihood = false};
    const inversion::FitResult best = inversion::fit(data, *model, start, fit_options);
    const std::vector<inversion::Prior> priors = inversion::make_priors(best.fitted, {});
    const sampling::PriorAndLikelihood f = inversion::evidence_integrand(data, *model, best, priors, fit_options);

    const bench::QuadratureEvidence quadrature = bench::quadrature_evidence(f, best);
    const double refined = quadrature.log_evidence;
    int within = 0;
    double sum = 0.0, sum_squares = 0.0, stated = 0.0, seconds = 0.0;
    int converged = 0;
    long steps = 0;
    std::vector<double> values;
    for (int seed = 1; seed <= seeds; ++seed) {
      inversion::EvidenceOptions options;
      options.seed = static_cast<unsigned>(seed);
      const auto t0 = std::chrono::steady_clock::now();
      const inversion::ModelEvidence e = inversion::model_evidence(data, *model, best, priors, fit_options, options);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double d = e.log_evidence - refined;
      within += std::abs(d) <= 2.0 * e.uncertainty;
      sum += d;
      sum_squares += d * d;
      stated += e.uncertainty;
      converged += e.converged;
      steps += e.steps;
      values.push_back(e.log_evidence);
    }
    const double mean = sum / seeds;
    const double sd = std::sqrt(std::max(0.0, (sum_squares - seeds * mean * mean) / (seeds - 1.0)));
    std::printf("%-22s %-22s %10.3f %7.3f %4d/%-4d %7.3f +- %5.3f %8.3f %8.3f %7.2f   (%d converged, mean %ld "
                "steps)\n",
                name.c_str(), free.c_str(), refined, quadrature.refinement, within, seeds, mean,
                sd / std::sqrt(seeds), sd, stated / seeds, seconds / seeds, converged, steps / seeds);
    std::fflush(stdout);
  }
  return 0;
}
