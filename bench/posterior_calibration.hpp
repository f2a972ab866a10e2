#pragma once
// Simulation-based calibration of the posterior (Talts et al. 2018, arXiv:1804.06788; Cook,
// Gelman & Rubin 2006): draw a truth from the prior, synthesise data from it with the likelihood's
// own noise, sample the posterior under the same prior, and record whether each credible interval
// contains the truth. Averaged over many data sets, a correct posterior contains the truth in its
// 68 % interval 68 % of the time and in its 95 % interval 95 % of the time (and the truth's rank
// among the draws is uniform). Shared by bench/posterior_calibration.cpp (the full study) and
// tests/inversion/test_coverage.cpp (a small one).
//
// The model: the lattice chain with free kappa, d, gamma under log-normal priors (a site prior:
// grain size 0.3 mm within a factor e^0.5; kappa and gamma broad), 20 log-spaced frequencies over
// 1-100 kHz, 5 % attenuation and 1 % sound-speed noise.
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sampling/summary.hpp"

namespace sedwave::bench {

struct CalibrationPrior {
  const char* name;
  double median;
  double sd_ln;
};
inline constexpr std::array<CalibrationPrior, 3> kCalibrationPriors{{
    {"kappa", 1.0e6, 1.0},
    {"d", 3.0e-4, 0.5},
    {"gamma", 5.0, 1.0},
}};

/// Per free parameter and per data set: whether the 68 % and 95 % intervals contain the truth, and
/// the truth's rank among the pooled draws (0 .. draws).
struct CalibrationResult {
  std::array<bool, 3> in68{}, in95{};
  std::array<double, 3> rank_fraction{};
  bool converged = false;
  bool importance = false;  ///< the evidence's sampler: importance sampling served
};

/// The posterior's draws and intervals from `sedwave invert --method posterior`'s sampler, or from
/// the evidence's own (importance sampling around the fit where it applies, parallel tempering
/// elsewhere: what `sedwave compare` draws its bands and corner plot from).
enum class CalibrationSampler { Posterior, Evidence };

inline CalibrationResult run_calibration_set(unsigned seed, int index, int steps,
                                             CalibrationSampler sampler = CalibrationSampler::Posterior) {
  std::mt19937_64 rng(seed * 7777ull + static_cast<unsigned>(index));
  std::normal_distribution<double> normal(0.0, 1.0);
  const forward::LatticeModel lattice;
  const auto frame = inversion::grain_contact_model(lattice, inversion::DampingForm::Gamma);
  inversion::FitParameters truth;
  std::vector<std::string> prior_items;
  for (std::size_t i = 0; i < kCalibrationPriors.size(); ++i) {
    const CalibrationPrior& p = kCalibrationPriors[i];
    truth.spec[i].value = p.median * std::exp(p.sd_ln * normal(rng));
    char item[96];
    std::snprintf(item, sizeof item, "%s=log-normal:%.17g,%.17g", p.name, p.median, p.sd_ln);
    prior_items.emplace_back(item);
  }
  const inversion::ObservationSet data = inversion::synthetic_observations(
      *frame, truth, {1e3, 1e5, 20, 0.05, 0.01, seed * 7919u + static_cast<unsigned>(index)});
  // The posterior does not depend on where the fit starts; start it at the prior medians.
  inversion::FitParameters start = truth;
  for (std::size_t i = 0; i < kCalibrationPriors.size(); ++i) start.spec[i].value = kCalibrationPriors[i].median;
  const inversion::FitOptions fit_options{.method = inversion::FitMethod::Ceres, .profile_likelihood = false};
  const inversion::FitResult best = inversion::fit(data, *frame, start, fit_options);
  const std::vector<inversion::Prior> priors = inversion::make_priors(best.fitted, prior_items);
  CalibrationResult r;
  Eigen::MatrixXd samples;
  if (sampler == CalibrationSampler::Evidence) {
    inversion::EvidenceOptions options;
    options.seed = seed + static_cast<unsigned>(index);
    const inversion::ModelEvidence e = inversion::model_evidence(data, *frame, best, priors, fit_options, options);
    r.converged = e.converged;
    r.importance = e.method == inversion::kImportanceSamplingMethod;
    samples = e.samples;
  } else {
    const inversion::PosteriorResult posterior = inversion::sample_posterior(
        data, *frame, best, priors, fit_options, {.steps = steps, .seed = seed + static_cast<unsigned>(index)});
    r.converged = posterior.converged;
    samples = posterior.samples;
  }
  for (std::size_t i = 0; i < kCalibrationPriors.size(); ++i) {
    const auto column = samples.col(static_cast<Eigen::Index>(i));
    const sampling::ParameterSummary q = sampling::summarize(Eigen::MatrixXd(column))[0];
    const double t = truth.spec[i].value;
    r.in68[i] = t >= q.central68.lower && t <= q.central68.upper;
    r.in95[i] = t >= q.central95.lower && t <= q.central95.upper;
    r.rank_fraction[i] = static_cast<double>((column.array() < t).count()) / static_cast<double>(column.size());
  }
  return r;
}

}  // namespace sedwave::bench
