#pragma once
// Parallel tempering with one stretch-move ensemble per inverse temperature beta, each sampling
// prior(x) L(x)^beta, and swaps between neighbouring temperatures (Vousden, Farr & Mandel 2016,
// MNRAS 455, 1919, "VFM16", section 2; as ptemcee). The hot ensembles cross valleys between modes
// and hand what they find down the ladder; the ladder's mean log likelihoods give the log evidence
// by stepping stones (checked by thermodynamic integration). Manual: docs/sampling.md.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::sampling {

/// The density split as tempering needs it: ln p(x) = ln prior(x) + ln L(x). The prior must be
/// proper (normalised) for the evidence to mean anything; -infinity outside its support.
struct PriorAndLikelihood {
  LogDensity log_prior;
  LogDensity log_likelihood;
  /// Optional: one independent draw from the prior. With it, a beta = 0 rung of the ladder is
  /// refreshed with independent prior draws at every step (an exact move for the prior) instead of
  /// stretch moves, and its walkers are independent of one another and of their past.
  std::function<Eigen::VectorXd(RandomStream&)> draw_prior = nullptr;
};

struct TemperedRun;

struct TemperingOptions {
  /// Inverse temperatures, strictly descending from betas[0] = 1 (the posterior); the last may be
  /// 0 exactly (the prior), which the evidence needs (evidence_ladder makes such a ladder). Empty:
  /// evidence_ladder(16, 1e6).
  std::vector<double> betas;
  /// Per temperature: walkers, steps (the cap when check_every > 0), burn-in, stretch; the seed
  /// drives the whole run; check_every as in the plain sampler, with `stop` below.
  EnsembleOptions ensemble;
  /// Asked with the run so far (first half dropped) every ensemble.check_every steps; true ends it.
  std::function<bool(const TemperedRun&)> stop;
  /// Updates during which the interior of the ladder adapts so that neighbouring temperatures swap
  /// at equal rates (VFM16 section 3.1): betas[0] = 1, the smallest beta > 0 and a last beta = 0
  /// stay where they are. 0: the ladder is fixed. The burn-in must hold the adaptation (it is
  /// at most half the run; an adaptive run is not stopped before 2 x adapt_steps), so that every
  /// kept step sees the final ladder.
  int adapt_steps = 0;
};

/// `temperatures` inverse temperatures beta_i = max_temperature^(-i / (temperatures - 1)): evenly
/// spaced in ln beta, as VFM16's initial ladder (section 3) and ptemcee's default.
[[nodiscard]] std::vector<double> geometric_ladder(int temperatures, double max_temperature);
/// geometric_ladder(temperatures, max_temperature) with beta = 0 (the prior) appended.
[[nodiscard]] std::vector<double> evidence_ladder(int temperatures, double max_temperature);

struct TemperedRun {
  /// The ladder the kept steps used (adapted where TemperingOptions::adapt_steps > 0).
  std::vector<double> betas;
  /// Per temperature, as sample() returns it; levels[0] (beta = 1) samples the posterior. Its
  /// log_density is ln prior + beta ln L; acceptance counts stretch moves only (1 at a beta = 0 rung
  /// refreshed by prior draws).
  std::vector<EnsembleRun> levels;
  /// Per temperature, per walker: ln L at each kept step.
  std::vector<std::vector<Eigen::VectorXd>> log_likelihood;
  /// Accepted fraction of swaps between betas[i] and betas[i + 1] over the steps after the ladder's
  /// adaptation (VFM16 aim at evenly spread rates).
  Eigen::VectorXd swap_acceptance;
  int evaluations = 0;  ///< calls of the prior-and-likelihood pair
  int steps = 0;        ///< updates run, burn-in included
};

/// Samples every temperature from the same start walkers (walker_count(options.ensemble, dim)
/// points with finite prior and likelihood). Each step: one stretch-move update per temperature,
/// then one round of swap proposals between neighbours. Throws std::invalid_argument for bad
/// options, naming what to change.
[[nodiscard]] TemperedRun sample_tempered(const PriorAndLikelihood& density,
                                          const std::vector<Eigen::VectorXd>& start_walkers,
                                          const TemperingOptions& options);
/// The same with one set of start walkers per temperature (level_starts[t] for betas[t]): e.g. hot
/// temperatures started from prior draws, cold ones around the best fit.
[[nodiscard]] TemperedRun sample_tempered(const PriorAndLikelihood& density,
                                          const std::vector<std::vector<Eigen::VectorXd>>& level_starts,
                                          const TemperingOptions& options);

struct Evidence {
  /// ln Z by the stepping-stone estimator (Xie, Lewis, Fan, Kuo & Chen 2011, Syst. Biol. 60, 150,
  /// eq. 6): ln Z = sum_k ln < L^(beta_k - beta_(k+1)) >_(beta_(k+1)) over neighbouring rungs down to
  /// beta = 0. Each ratio is an average of the hotter rung's draws, so it has no discretisation
  /// error, whatever the ladder; its small bias from the logarithm of a noisy mean (-var / 2) is
  /// corrected.
  double log_evidence = 0.0;
  /// The Monte Carlo standard error of log_evidence: from the time series of the whole ladder's
  /// contribution at each kept step and its integrated autocorrelation time, so the correlations
  /// that swaps make between rungs are counted (delta method).
  double uncertainty = 0.0;
  /// The integrated autocorrelation time of that time series [steps]: the error is trustworthy once
  /// the kept steps exceed about 50 of it (emcee's rule).
  double autocorrelation_time = 0.0;
  /// Cross-check: thermodynamic integration, ln Z = integral_0^1 <ln L>_beta d beta by the trapezoid
  /// rule corrected with d<ln L>/d beta = Var_beta(ln L) (Friel, Hurn & Wyse 2014, Stat. Comput. 24,
  /// 709), beta = 0 included; NaN where ln L is -infinity at some draw.
  double thermodynamic_integration = 0.0;
  /// Its discretisation error, estimated as ptemcee does (the rule on every other rung; an overestimate).
  double discretisation = 0.0;
  /// Smallest over the stones of the effective fraction of the hotter rung's draws that carry its
  /// weights L^(delta beta) (Kish: (sum w)^2 / (n sum w^2)); near 0 the stone is too wide, its
  /// error estimate unreliable: add temperatures there.
  double stone_overlap = 0.0;
};

/// The log evidence of a run whose ladder ends at beta = 0 (throws std::invalid_argument
/// otherwise, saying to append it), from its kept draws.
[[nodiscard]] Evidence thermodynamic_evidence(const TemperedRun& run);

}  // namespace sedwave::sampling
