// The demo's evidences by brute force: each model of `sedwave compare`'s demo (the shipped field
// data, the medium-sand site prior, the model's typical free parameters) fitted as compare fits
// it, then the same integral model_evidence estimates (inversion::evidence_integrand) by the
// midpoint rule in the free ln-parameters over a box: the best fit +- 12 linearised sd cut to the
// prior's support, each face pushed out (doubling its distance from the fit) while the integrand
// on it is within e^-25 of the largest value and the support allows; then on n^k and (1.5 n)^k
// cells, whose difference is printed as the reference's own error. Beside it, model_evidence's
// default (importance sampling where its diagnostics allow) with its seed.
//
//   build/bin/bench_field_evidence_quadrature [MODELS=biot-stoll,edfm] [n=120] [SITE=data/sites/medium_sand.toml]
//
// SITE "none" integrates under the default priors (log-uniform over physical ranges), as
// examples/12-own-model and `compare` without --site do.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/setup.hpp"

namespace {

using namespace sedwave;

const inversion::FitOptions kFitOptions{.method = inversion::FitMethod::Global, .profile_likelihood = false};

struct Grid {
  std::vector<double> lo, hi;
};

/// ln of the integral of exp(f) over the box by the midpoint rule on n cells per axis; `face_peak`
/// gets, per axis and side, the largest value over the outermost layer of cells.
double log_integral(const sampling::PriorAndLikelihood& f, const Grid& box, int n,
                    std::vector<double>* face_peak = nullptr) {
  const auto k = box.lo.size();
  std::vector<double> h(k);
  for (std::size_t j = 0; j < k; ++j) h[j] = (box.hi[j] - box.lo[j]) / n;
  std::size_t cells = 1;
  for (std::size_t j = 0; j < k; ++j) cells *= static_cast<std::size_t>(n);
  std::vector<double> values(cells);
  std::vector<double> faces(2 * k, -std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < cells; ++c) {
    Eigen::VectorXd x(static_cast<Eigen::Index>(k));
    std::size_t rest = c;
    for (std::size_t j = 0; j < k; ++j) {
      x(static_cast<Eigen::Index>(j)) = box.lo[j] + (static_cast<double>(rest % n) + 0.5) * h[j];
      rest /= static_cast<std::size_t>(n);
    }
    const double lp = f.log_prior(x);
    values[c] = std::isfinite(lp) ? lp + f.log_likelihood(x) : lp;
  }
  double peak = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < cells; ++c) {
    peak = std::max(peak, values[c]);
    std::size_t rest = c;
    for (std::size_t j = 0; j < k; ++j) {
      const auto i = rest % static_cast<std::size_t>(n);
      rest /= static_cast<std::size_t>(n);
      if (i == 0) faces[2 * j] = std::max(faces[2 * j], values[c]);
      if (i + 1 == static_cast<std::size_t>(n)) faces[2 * j + 1] = std::max(faces[2 * j + 1], values[c]);
    }
  }
  double sum = 0.0;
  for (const double v : values) sum += std::exp(v - peak);
  if (face_peak) {
    face_peak->assign(faces.begin(), faces.end());
    for (double& v : *face_peak) v -= peak;
  }
  double volume = 1.0;
  for (const double step : h) volume *= step;
  return peak + std::log(sum * volume);
}

void run(const std::string& spec, const inversion::ObservationSet& data, int n, const std::string& site) {
  inversion::ModelSetup setup;
  setup.model = spec;
  if (site != "none") setup.site_file = site;
  setup.shared = true;
  const inversion::Candidate candidate = inversion::make_candidate(setup);
  const inversion::FitResult best = inversion::fit(data, *candidate.model, candidate.parameters, kFitOptions);
  const sampling::PriorAndLikelihood f =
      inversion::evidence_integrand(data, *candidate.model, best, candidate.priors, kFitOptions);
  Grid box, support;
  for (const int i : best.fitted.free_indices()) {
    const auto u = static_cast<std::size_t>(i);
    const auto [lo, hi] = candidate.priors[u].support();
    support.lo.push_back(std::log(lo));
    support.hi.push_back(std::log(hi));
    const double sigma = std::isfinite(best.parameters[u].log_sigma) && best.parameters[u].log_sigma > 0.0
                             ? best.parameters[u].log_sigma : 0.1;
    const double at = std::log(best.fitted.spec[u].value);
    box.lo.push_back(std::max(support.lo.back(), at - 12.0 * sigma));
    box.hi.push_back(std::min(support.hi.back(), at + 12.0 * sigma));
  }
  const std::size_t k = box.lo.size();
  for (int pass = 0; pass < 12; ++pass) {
    std::vector<double> faces;
    (void)log_integral(f, box, std::max(40, n / 2), &faces);
    bool moved = false;
    for (std::size_t j = 0; j < k; ++j) {
      const double centre = std::log(best.fitted.spec[static_cast<std::size_t>(best.fitted.free_indices()[j])].value);
      if (faces[2 * j] > -25.0 && box.lo[j] > support.lo[j]) {
        box.lo[j] = std::max(support.lo[j], centre - 2.0 * (centre - box.lo[j])), moved = true;
      }
      if (faces[2 * j + 1] > -25.0 && box.hi[j] < support.hi[j]) {
        box.hi[j] = std::min(support.hi[j], centre + 2.0 * (box.hi[j] - centre)), moved = true;
      }
    }
    if (!moved) break;
  }
  const double coarse = log_integral(f, box, n);
  const double fine = log_integral(f, box, n * 3 / 2);
  inversion::EvidenceOptions options;
  const inversion::ModelEvidence e = inversion::model_evidence(data, *candidate.model, best, candidate.priors,
                                                               kFitOptions, options);
  std::printf("%-12s quadrature %9.4f (n %d: %9.4f, change %.4f) over", spec.c_str(), fine, n, coarse,
              std::abs(fine - coarse));
  for (std::size_t j = 0; j < k; ++j) std::printf(" [%.2f, %.2f]", box.lo[j], box.hi[j]);
  std::printf("\n             model_evidence %9.4f +- %.4f (%s, %d evaluations)%s\n", e.log_evidence, e.uncertainty,
              e.method.c_str(), e.evaluations, e.fallback_reason.empty() ? "" : (": " + e.fallback_reason).c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string models = argc > 1 ? argv[1] : "biot-stoll,edfm";
  const int n = argc > 2 ? std::atoi(argv[2]) : 120;
  const std::string site = argc > 3 ? argv[3] : "data/sites/medium_sand.toml";
  const inversion::ObservationSet data = inversion::read_observation_csv("data/field/zhou2009_regression.csv");
  std::stringstream list(models);
  for (std::string spec; std::getline(list, spec, ',');) run(spec, data, n, site);
  return 0;
}
