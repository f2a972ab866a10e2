// Is the evidence as accurate as it says? For every model family (sediment::model_examples()), on a
// synthetic set it generated (its defaults; 20 log-spaced frequencies over 100 Hz - 100 kHz, 5 %
// attenuation and 1 % sound-speed noise), with two free parameters (the first two of its typical
// set) under default priors: ln Z from model_evidence (default options) over many seeds against
// brute-force quadrature of the same integral (inversion::evidence_integrand). Prints per model the
// reference, how many runs land within 2 stated sigmas (>= 90 % expected), the mean difference with
// its standard error (within 2 of 0 expected), and the run lengths and times.
//
// The quadrature: the midpoint rule in the free ln-parameters, first on a 200 x 200 grid over the
// whole prior, then twice zoomed onto the box of cells whose integrand is within e^-60 of the
// largest (widened by two cells, and always holding the best fit +- 10 linearised sigma), then on
// that box at n x n and 2n x 2n (n = 300); their difference is printed as the reference's own error.
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

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using namespace sedwave;

struct Box {
  double lo[2], hi[2];
};

// ln of the integral of exp(f) over the box by the midpoint rule on n x n cells; with `keep`, also
// the box of cells within `window` of the largest value (widened by two cells).
double log_integral(const sampling::PriorAndLikelihood& f, const Box& box, int n, Box* keep = nullptr,
                    double window = 60.0) {
  const double h0 = (box.hi[0] - box.lo[0]) / n, h1 = (box.hi[1] - box.lo[1]) / n;
  std::vector<double> values(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  double peak = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd x(2);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      x << box.lo[0] + (i + 0.5) * h0, box.lo[1] + (j + 0.5) * h1;
      const double lp = f.log_prior(x);
      const double v = std::isfinite(lp) ? lp + f.log_likelihood(x) : lp;
      values[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)] = v;
      peak = std::max(peak, v);
    }
  }
  double sum = 0.0;
  int lo_i = n, hi_i = -1, lo_j = n, hi_j = -1;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double v = values[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
      sum += std::exp(v - peak);
      if (v >= peak - window) {
        lo_i = std::min(lo_i, i), hi_i = std::max(hi_i, i), lo_j = std::min(lo_j, j), hi_j = std::max(hi_j, j);
      }
    }
  }
  if (keep) {
    keep->lo[0] = std::max(box.lo[0], box.lo[0] + (lo_i - 2) * h0);
    keep->hi[0] = std::min(box.hi[0], box.lo[0] + (hi_i + 3) * h0);
    keep->lo[1] = std::max(box.lo[1], box.lo[1] + (lo_j - 2) * h1);
    keep->hi[1] = std::min(box.hi[1], box.lo[1] + (hi_j + 3) * h1);
  }
  return peak + std::log(sum * h0 * h1);
}

Box hull(Box a, const Box& b) {
  for (int k = 0; k < 2; ++k) a.lo[k] = std::min(a.lo[k], b.lo[k]), a.hi[k] = std::max(a.hi[k], b.hi[k]);
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::string only = argc > 2 ? argv[2] : "";
  std::printf("evidence accuracy: model_evidence (default options) over %d seeds against quadrature; 2 free "
              "parameters, default priors\n", seeds);
  std::printf("%-22s %-22s %10s %7s %9s %16s %8s %8s %7s\n", "model", "free", "quadrature", "+-", "in 2 sd",
              "mean diff +- se", "sd(lnZ)", "stated", "s/run");
  for (const auto& model : sediment::model_examples()) {
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

    const std::vector<int> idx = best.fitted.free_indices();
    Box box{}, around_best{};
    for (int k = 0; k < 2; ++k) {
      const auto& spec = best.fitted.spec[idx[static_cast<std::size_t>(k)]];
      box.lo[k] = std::log(spec.lower);
      box.hi[k] = std::log(spec.upper);
      const auto& r = best.parameters[static_cast<std::size_t>(idx[static_cast<std::size_t>(k)])];
      const double sigma = r.log_sigma > 0.0 && std::isfinite(r.log_sigma) ? r.log_sigma : 0.1;
      around_best.lo[k] = std::max(box.lo[k], std::log(spec.value) - 10.0 * sigma);
      around_best.hi[k] = std::min(box.hi[k], std::log(spec.value) + 10.0 * sigma);
    }
    Box zoom{};
    (void)log_integral(f, box, 200, &zoom);
    zoom = hull(zoom, around_best);
    for (int pass = 0; pass < 2; ++pass) {
      Box next{};
      (void)log_integral(f, zoom, 200, &next);
      zoom = hull(next, around_best);
    }
    const double reference = log_integral(f, zoom, 300);
    const double refined = log_integral(f, zoom, 600);

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
                name.c_str(), free.c_str(), refined, std::abs(refined - reference), within, seeds, mean,
                sd / std::sqrt(seeds), sd, stated / seeds, seconds / seeds, converged, steps / seeds);
    std::fflush(stdout);
  }
  return 0;
}
