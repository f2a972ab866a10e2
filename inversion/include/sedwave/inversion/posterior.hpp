#pragma once
// The Bayesian answer: the posterior distribution of a model's free parameters given the data and
// the priors (priors.hpp), sampled by the affine-invariant ensemble sampler (sampling/ensemble.hpp)
// from walkers started around the best fit. The likelihood is the fit's: exp(-chi^2/2) with the
// same whitened residuals (residuals.hpp), so a posterior and a fit answer the same question.
//
// Reported per free parameter and per combination (c0, tau, f*, gamma_hat, kappa/kappa_Hertz where
// they mean something): the posterior median, the 68 % and 95 % central credible intervals, and the
// sampler's split-R-hat and effective sample size; plus the acceptance, a convergence verdict with
// advice, and whether each parameter's marginal is still its prior (the data did not inform it).
#include <Eigen/Dense>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/priors.hpp"

namespace sedwave::inversion {

struct PosteriorOptions {
  int walkers = 0;        ///< 0: max(4 x free parameters, 16), even
  int steps = 2000;       ///< per walker, burn-in included
  int burn_in = -1;       ///< -1: the first half
  unsigned seed = 20090501;
};

struct PosteriorQuantity {
  std::string name;
  std::string unit;
  double median = 0.0;
  double lower_68 = 0.0, upper_68 = 0.0;  ///< central credible interval [unit]
  double lower_95 = 0.0, upper_95 = 0.0;
  double split_rhat = 0.0;
  double effective_samples = 0.0;
  /// The 68 % interval spans at least 80 % (in ln) of the prior's own 68 % interval: the data did
  /// not inform this quantity, its posterior is (close to) its prior.
  bool prior_dominated = false;
};

struct PosteriorResult {
  std::vector<PosteriorQuantity> parameters;    ///< the free ones
  std::vector<PosteriorQuantity> combinations;
  std::vector<std::string> priors;              ///< one line per free parameter (Prior::describe)
  Eigen::MatrixXd samples;                      ///< pooled kept draws x free parameters, values [unit]
  std::vector<std::string> sample_names;
  Eigen::MatrixXd correlation;                  ///< of the free ln-parameters
  double acceptance = 0.0;
  bool converged = false;
  std::string advice;                           ///< what to change when not converged
  int walkers = 0, steps = 0, evaluations = 0;
  double wall_seconds = 0.0;
};

/// Samples the posterior of `best.fitted`'s free parameters (walkers started in a small ball around
/// the best fit, scaled by its covariance where determined and by the prior elsewhere). Throws
/// std::invalid_argument for priors that do not cover the best fit or a sampler option it refuses.
[[nodiscard]] PosteriorResult sample_posterior(const ObservationSet& data, const sediment::SedimentModel& model,
                                               const FitResult& best, const std::vector<Prior>& priors,
                                               const FitOptions& fit_options, const PosteriorOptions& options);

/// The posterior as JSON (fit.json's "posterior" entry) and the pooled samples as CSV (one column
/// per free parameter, SI units in the header).
[[nodiscard]] nlohmann::json posterior_report(const PosteriorResult& posterior);
void write_posterior_samples_csv(const std::filesystem::path& path, const PosteriorResult& posterior);

}  // namespace sedwave::inversion
