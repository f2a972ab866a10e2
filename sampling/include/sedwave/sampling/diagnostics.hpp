#pragma once
// Convergence diagnostics of Markov chains: split-R-hat (Gelman et al., Bayesian Data Analysis, 3rd
// ed. 2013, "BDA3", section 11.4), its rank-normalised form (Vehtari, Gelman, Simpson, Carpenter &
// Buerkner 2021, Bayesian Analysis 16, 667, "V21"), the integrated autocorrelation time with Sokal's
// automatic window (Sokal 1997, in Functional Integration, NATO ASI Series B 361, 131; as emcee's
// integrated_time), the effective sample size, and a verdict with advice. Manual: docs/sampling.md.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sedwave/sampling/ensemble.hpp"

namespace sedwave::sampling {

/// One parameter's draws from every chain (walker): column `parameter` of each chain matrix.
[[nodiscard]] std::vector<Eigen::VectorXd> parameter_chains(const std::vector<Eigen::MatrixXd>& chains,
                                                            int parameter);

/// Split-R-hat of BDA3 eqs. 11.1-11.4: each chain cut into two halves (an odd middle draw dropped),
/// then sqrt(var+ / W) with W the mean within-half variance and var+ = (n-1)/n W + B/n. 1 when
/// the halves agree; NaN when every half is constant (nothing to compare).
[[nodiscard]] double split_rhat(const std::vector<Eigen::VectorXd>& chains);

/// Rank-normalised split-R-hat (V21 section 4.2): the larger of the split-R-hat of the
/// rank-normalised draws ("bulk") and of the rank-normalised distances from the median ("tail").
/// Robust to heavy tails and catches chains that agree in location but not in scale.
[[nodiscard]] double rank_normalized_rhat(const std::vector<Eigen::VectorXd>& chains);

/// Integrated autocorrelation time tau = 1 + 2 sum_{t=1..M} rho(t) [draws], with rho the
/// autocorrelation function (biased autocovariance, divided by lag 0) averaged over the chains, as
/// emcee 3 does (not the autocorrelation of the chain-averaged series: for an ensemble that is
/// noisier and can be biased low, see emcee's "Autocorrelation analysis" tutorial). Sokal's window:
/// the smallest M >= window_factor * tau(M), window_factor = 5 (Sokal 1997; emcee's c = 5).
/// The estimate is trustworthy when the chains are longer than about 50 tau (emcee's tol = 50).
/// NaN when every chain is constant.
[[nodiscard]] double autocorrelation_time(const std::vector<Eigen::VectorXd>& chains, double window_factor = 5.0);

/// The integrated autocorrelation time of one series by Geyer's initial monotone sequence (Geyer
/// 1992, Stat. Sci. 7, 473, section 3.3; as Stan's ESS, V21 section 3.2): tau = -1 + 2 sum_k Gamma_k
/// with Gamma_k = rho(2k) + rho(2k+1), summed while positive and made non-increasing. Unlike Sokal's
/// window it follows a slowly decaying tail of the autocorrelation (a mixture of fast and slow
/// motions) to its end. NaN for a constant series.
[[nodiscard]] double initial_sequence_autocorrelation_time(const Eigen::VectorXd& series);

struct Diagnostics {
  Eigen::VectorXd rhat;                  ///< rank_normalized_rhat per parameter
  Eigen::VectorXd autocorrelation_time;  ///< tau per parameter [ensemble updates]
  Eigen::VectorXd ess;                   ///< effective sample size per parameter: kept_steps * walkers / tau
  double acceptance = 0.0;               ///< mean accepted fraction of proposals
  int kept_steps = 0;
  int walkers = 0;
  /// What each column is, for the advice ("parameter i" where absent): a caller that diagnoses
  /// derived quantities beside the parameters names both.
  std::vector<std::string> names{};
};

/// Diagnostics of chains (per walker: steps x dim) with the run's acceptance fraction.
[[nodiscard]] Diagnostics diagnose(const std::vector<Eigen::MatrixXd>& chains, double acceptance);
[[nodiscard]] Diagnostics diagnose(const EnsembleRun& run);

/// Thresholds of the verdict (defaults justified in docs/sampling.md). The convergence tests are the
/// run length in autocorrelation times and the ESS; R-hat across the walkers of one ensemble, which
/// are not independent chains, is a check that the walkers agree (it catches walkers split between
/// modes), not a convergence test of its own.
struct ConvergenceCriteria {
  double max_rhat = 1.05;          ///< walkers agree: R-hat across walkers below this
  double min_ess = 400.0;          ///< V21 section 4.3: ESS > 400 (MC error of a quantile ~5 % of the posterior sd)
  double min_steps_per_tau = 50.0; ///< emcee: kept steps > 50 tau, else tau itself is not yet reliable
  /// Below this acceptance the advice says that walkers may be stuck (advice only; the stretch move
  /// accepts ~0.4-0.7 of its proposals in 2-5 dimensions at a = 2, and efficiency is judged by tau).
  double min_acceptance = 0.1;
};

struct Convergence {
  bool converged = false;  ///< every parameter meets max_rhat, min_ess and min_steps_per_tau
  std::string advice;      ///< what failed and what to change; or the verdict when converged
};

[[nodiscard]] Convergence assess_convergence(const Diagnostics& diagnostics, const ConvergenceCriteria& criteria = {});

}  // namespace sedwave::sampling
