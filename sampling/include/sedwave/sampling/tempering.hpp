#pragma once
// Parallel tempering with one stretch-move ensemble per inverse temperature beta, each sampling
// prior(x) L(x)^beta, and swaps between neighbouring temperatures (Vousden, Farr & Mandel 2016,
// MNRAS 455, 1919, "VFM16", section 2; as ptemcee). The hot ensembles cross valleys between modes
// and hand what they find down the ladder; the ladder's mean log likelihoods give the log evidence
// by thermodynamic integration. Manual: docs/sampling.md.
#include <vector>

#include <Eigen/Core>

#include "sedwave/sampling/ensemble.hpp"

namespace sedwave::sampling {

/// The density split as tempering needs it: ln p(x) = ln prior(x) + ln L(x). The prior must be
/// proper (normalised) for the evidence to mean anything; -infinity outside its support.
struct PriorAndLikelihood {
  LogDensity log_prior;
  LogDensity log_likelihood;
};

struct TemperingOptions {
  /// Inverse temperatures, strictly descending from betas[0] = 1 (the posterior), all > 0.
  /// Empty: geometric_ladder(16, 1e6).
  std::vector<double> betas;
  /// Per temperature: walkers, steps, burn-in, stretch; the seed drives the whole run.
  EnsembleOptions ensemble;
};

/// `temperatures` inverse temperatures beta_i = max_temperature^(-i / (temperatures - 1)): evenly
/// spaced in ln beta, as VFM16's initial ladder (section 3) and ptemcee's default.
[[nodiscard]] std::vector<double> geometric_ladder(int temperatures, double max_temperature);

struct TemperedRun {
  std::vector<double> betas;
  /// Per temperature, as sample() returns it; levels[0] (beta = 1) samples the posterior. Its
  /// log_density is ln prior + beta ln L; acceptance counts stretch moves only.
  std::vector<EnsembleRun> levels;
  /// Per temperature, per walker: ln L at each kept step.
  std::vector<std::vector<Eigen::VectorXd>> log_likelihood;
  /// Accepted fraction of swaps between betas[i] and betas[i + 1] (VFM16 aim at evenly spread rates).
  Eigen::VectorXd swap_acceptance;
  int evaluations = 0;  ///< calls of the prior-and-likelihood pair
};

/// Samples every temperature from the same start walkers (walker_count(options.ensemble, dim)
/// points with finite prior and likelihood). Each step: one stretch-move update per temperature,
/// then one round of swap proposals between neighbours. Throws std::invalid_argument for bad
/// options, naming what to change.
[[nodiscard]] TemperedRun sample_tempered(const PriorAndLikelihood& density,
                                          const std::vector<Eigen::VectorXd>& start_walkers,
                                          const TemperingOptions& options);

struct Evidence {
  double log_evidence = 0.0;
  double uncertainty = 0.0;       ///< sqrt(discretisation^2 + monte_carlo^2)
  double discretisation = 0.0;    ///< |rule on every beta - rule on every other beta|
  double monte_carlo = 0.0;       ///< from each temperature's ESS of ln L, through the trapezoid weights
};

/// ln Z = integral_0^1 <ln L>_beta d beta (thermodynamic integration; e.g. Gelman & Meng 1998,
/// Stat. Sci. 13, 163; VFM16 eq. 14) by the trapezoid rule over the ladder corrected with the
/// derivative d<ln L>/d beta = Var_beta(ln L) (Friel, Hurn & Wyse 2014, Stat. Comput. 24, 709), with
/// the last segment [0, beta_min] taken at beta_min's values as ptemcee does (negligible for a small
/// beta_min). The discretisation error is estimated as ptemcee does, by the same rule on every other
/// temperature; it overestimates the error of the full ladder.
[[nodiscard]] Evidence thermodynamic_evidence(const TemperedRun& run);

}  // namespace sedwave::sampling
