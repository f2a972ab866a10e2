#pragma once
// The evidence Z = integral of L(x) pi(x) dx of a posterior that an optimiser has already located,
// by importance sampling from heavy-tailed proposals around it; the Pareto shape k-hat of the
// weights' tail says whether the estimate can be trusted (Vehtari, Simpson, Gelman, Yao &
// Gabry 2024, JMLR 25(72), 1). Several priors over the same parameters (e.g. a prior and the same
// prior widened) are integrated from the same likelihood evaluations.
//
// A pilot run draws from a multivariate t around `centre` with scale `covariance` (the linearised
// posterior); each prior's posterior moments from the pilot's weights then place one more t
// component; the estimate uses only the draws from the final equal mixture of all of them (the
// pilot's t included, so the mixture's tails stay at least as wide as the pilot's), each weighted by
// L pi / q_mixture. The adaptation runs twice: the second pilot draws from the first mixture, and
// the components are placed again from both pilots' weights (each pilot weighted by its own q).
// With ImportanceOptions::defensive, where a prior's posterior is not a single Gaussian-like peak
// inside its support (a plateau, a cut at a bound, two modes) the mixture also holds a defensive
// slab for it, and the pilots are weighted by the balance heuristic (each draw against the average
// of both rounds' mixtures). Reproducible for any thread
// count: the draws come from one seeded stream before any likelihood is evaluated, and the sums
// run in the draws' order.
#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::sampling {

/// ImportanceEstimate::slab_axis's values other than a coordinate.
inline constexpr int kNoSlab = -2;
inline constexpr int kSlabAlongCombination = -1;
/// ImportanceOptions::defensive's triggers and slab (see there).
inline constexpr double kDefendBelowKurtosis = 2.5;
inline constexpr double kDefendWithinSd = 3.0;
/// In ln of L pi: a Gaussian posterior in 3 dimensions holds all but 3e-5 of its mass within it.
inline constexpr double kHighDensityDepth = 12.0;
/// Segments of a defensive slab, each with the t across it centred on its own draws.
inline constexpr int kSlabSegments = 6;
/// A slab's axis snaps to a coordinate axis within this cosine of it.
inline constexpr double kSnapCosine = 0.98;

/// Where a prior is non-zero: a box in the sampled coordinates (a coordinate beyond `lower` or
/// `upper`'s size is unbounded).
struct Support {
  Eigen::VectorXd lower, upper;
};

struct ImportanceOptions {
  int pilot_draws = 800;   ///< per adaptation round (two), to place the adapted components
  int draws = 2400;        ///< from the final mixture: the estimate
  int max_draws = 9600;    ///< more draws from the same mixture while an error exceeds the target
  double target_uncertainty = 0.025;  ///< the standard error of ln Z sought for every prior
  /// More draws are made only for a prior whose weights' Pareto k-hat is at most this: above it the
  /// estimate is not to be trusted at any practical number of draws (Vehtari et al. 2024, section
  /// 3.2), so drawing on towards the target error would be spent on an estimate that is refused.
  double draw_on_below_pareto_k = 0.7;
  int degrees_of_freedom = 4;         ///< of every t component (heavier tails than any Gaussian posterior)
  double pilot_scale = 1.5;    ///< the pilot t's scale matrix is pilot_scale^2 x covariance
  double adapted_scale = 1.3;  ///< an adapted t's scale matrix is adapted_scale^2 x the weighted covariance
  /// A defensive slab (after Hesterberg 1995, Technometrics 37, 185) per prior whose pilot
  /// posterior is not a single Gaussian-like peak inside its support (too few effective draws to
  /// place a t, mass beyond kFarDistance sd, a principal axis's kurtosis below kDefendBelowKurtosis,
  /// or its mean within kDefendWithinSd sd of a bound) joins the final mixture as one more equal
  /// component: uniform along one principal axis of that posterior (its flattest, where one is
  /// flatter than a peak; else the one it reaches farthest beyond the linearisation along; snapped to
  /// a parameter's own axis within kSnapCosine), over the span of the pilots' draws within
  /// kHighDensityDepth of its largest density widened by that span on each side and cut to the
  /// support; across it a t, centred per kSlabSegments segment on the draws there. Inside the slab
  /// no weight exceeds (L pi / t)(length / share), whatever the posterior's shape along the axis.
  /// The pilots are then weighted by the balance heuristic (Owen & Zhou 2000). Off by default: on
  /// some posteriors (docs/sampling.md) mass beside the slab is missed with every weight looking fine.
  bool defensive = false;
  std::vector<Support> supports = {};  ///< per prior, in the order given (missing: unbounded)
  std::uint64_t seed = 20090501;
  int threads = 1;  ///< share the likelihood evaluations; the result does not depend on it
};

/// One prior's evidence from the weighted draws.
struct ImportanceEstimate {
  double log_evidence = 0.0;
  /// Standard error of ln Z: the delta method on the mean of the weights, sd(w) / (sqrt(N) mean(w)),
  /// trustworthy where the weights' variance is finite (k-hat < 0.5; up to 0.7 in practice, Vehtari
  /// et al. section 3.2); the small bias of the logarithm of a noisy mean (-sd^2/2) is corrected.
  double uncertainty = 0.0;
  double pareto_k = 0.0;        ///< Pareto k-hat of the weights' upper tail: > 0.7 untrustworthy
  double effective_draws = 0.0; ///< Kish's (sum w)^2 / sum w^2
  Eigen::VectorXd mean;         ///< the posterior's weighted mean
  Eigen::MatrixXd covariance;   ///< and covariance
  /// Posterior mass (weighted) farther than kFarDistance from the weighted mean in the metric of
  /// the weighted covariance: a Gaussian-like posterior has almost none (a 3-D Gaussian 0.1 %
  /// beyond 4 sd); a small second mode far out, or a long tail, has more.
  double far_mass = 0.0;
  /// The smallest kurtosis E[z^4] / E[z^2]^2 of the posterior along the principal axes of its
  /// weighted covariance: 3 for a Gaussian, 1.8 for a flat plateau, towards 1 for two separated
  /// modes of similar weight.
  double min_axis_kurtosis = 0.0;
  Eigen::VectorXd log_weights;  ///< per draw, normalised (log-sum-exp 0); -inf: zero
  /// The final mixture's defensive slab for this prior runs along this coordinate (a parameter);
  /// kSlabAlongCombination: along a combination of them; kNoSlab: the prior has none.
  int slab_axis = kNoSlab;
  /// With a slab: the posterior's mass in its outermost sixths at the ends the support did not cut
  /// (beyond the pilots' high-density span by half that span). More than a trace says the posterior
  /// goes on past where the pilots looked.
  double slab_end_mass = 0.0;
  /// With a slab: the posterior's largest sd across it over the linearised posterior's along the
  /// same axis. About 1 where the slab's axis is the only one the linearisation got wrong (a
  /// plateau along one direction); far above it, the posterior is broad across the slab as well.
  double slab_across_spread = 0.0;
};

struct ImportanceRun {
  Eigen::MatrixXd draws;           ///< the estimate's draws (rows)
  Eigen::VectorXd log_likelihood;  ///< at each draw; -inf where every prior is zero (not evaluated)
  std::vector<ImportanceEstimate> priors;  ///< one per prior, in the order given
  int evaluations = 0;             ///< likelihood evaluations, the pilot's included
  int components = 0;              ///< of the final mixture, its defensive slabs included
  int slabs = 0;                   ///< defensive slabs among them
};

/// Mahalanobis distance beyond which draws count towards ImportanceEstimate::far_mass.
inline constexpr double kFarDistance = 4.0;
/// Each prior's evidence with `log_likelihood` (-inf where it has no value), from proposals around
/// `centre` scaled by `covariance` (symmetric positive definite). A prior that is -inf at a draw
/// skips it; the likelihood is evaluated only where some prior is not. Throws std::invalid_argument
/// for no priors, mismatched sizes, a covariance that is not positive definite, or options out of range.
[[nodiscard]] ImportanceRun importance_evidence(const LogDensity& log_likelihood,
                                                const std::vector<LogDensity>& log_priors,
                                                const Eigen::VectorXd& centre, const Eigen::MatrixXd& covariance,
                                                const ImportanceOptions& options = {});

/// One estimate (ImportanceEstimate, every field but the slab's) from draws (rows) from any
/// proposal q and their log weights ln(L pi / q) (-inf: zero). Throws std::invalid_argument for
/// mismatched sizes or fewer than two draws.
[[nodiscard]] ImportanceEstimate weighted_estimate(const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_weights);

/// Pareto-smoothed importance weights (Vehtari et al. 2024, section 3): the largest
/// M = ceil(min(0.2 S, 3 sqrt(S))) of S log weights replaced by the expected order statistics of a
/// generalized Pareto distribution fitted to them (Zhang & Stephens 2009, Technometrics 51, 316,
/// with the weakly informative prior on k of Vehtari et al.), capped at the largest raw weight.
/// Weights of -inf stay so. Returns the smoothed log weights (on the same scale as the raw ones) and k-hat
/// (+inf when fewer than 5 weights lie in the tail).
struct ParetoSmoothed {
  Eigen::VectorXd log_weights;
  double k = 0.0;
};
[[nodiscard]] ParetoSmoothed pareto_smooth(const Eigen::VectorXd& log_weights);

/// `count` draws (rows of `draws`) picked by systematic resampling with probabilities
/// exp(log_weights) (normalised or not): an equally weighted sample of the weighted one.
[[nodiscard]] Eigen::MatrixXd resample(const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_weights, int count,
                                       RandomStream& random);

}  // namespace sedwave::sampling
