#pragma once
// The affine-invariant ensemble sampler with the stretch move (Goodman & Weare 2010, Comm. App.
// Math. Comp. Sci. 5, 65; "GW10"), as implemented in emcee (Foreman-Mackey et al. 2013, PASP 125,
// 306; "FM13"). An ensemble of walkers moves together: each walker proposes a point on the line
// through itself and a walker of the other half-ensemble. The moves are unchanged by any affine map
// of the parameters, so a long, thin, correlated ridge is sampled as easily as a round blob, and the
// only tuning parameter is the stretch scale a. Manual: docs/sampling.md.
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace sedwave::sampling {

/// ln p(x) up to an additive constant; -infinity outside the support. It is never called with a
/// non-finite coordinate and must return a finite value or -infinity (NaN or +infinity: the sampler
/// throws std::domain_error).
using LogDensity = std::function<double(const Eigen::VectorXd&)>;

struct EnsembleRun;

/// The proposal moves an update chooses among, with their weights (normalised by their sum). Each
/// update draws one move for the whole ensemble, as emcee does with a weighted list of moves; every
/// move keeps the target invariant, so any mixture does too.
///  - stretch: Y = X_j + z (X_k - X_j) (GW10 eq. 7), the default alone.
///  - differential_evolution: Y = X_k + g (X_a - X_b), X_a, X_b two distinct walkers of the other
///    half, g = 2.38 / sqrt(2 dim) times a factor uniform on [0.9, 1.1], and g = 1 on one update in
///    ten (ter Braak 2006, Stat. Comput. 16, 239, section 3; emcee's DEMove).
///  - snooker: along the line through X_k and a walker Z of the other half, a jump of 1.7 times the
///    projection of X_a - X_b on it, accepted with the extra factor (|Y - Z| / |X_k - Z|)^(dim-1)
///    (ter Braak & Vrugt 2008, Stat. Comput. 18, 435, section 3; emcee's DESnookerMove).
/// The differential moves reach along the directions the ensemble spreads in at the scale it
/// spreads, which the stretch move on a long, bounded ridge does not (docs/sampling.md).
struct MoveMix {
  double stretch = 1.0;
  double differential_evolution = 0.0;
  double snooker = 0.0;
};

/// Differential evolution 0.8, snooker 0.2, no stretch: the mixture emcee's documentation shows
/// for these moves, and the one the inversion's posterior uses (docs/sampling.md: on the
/// benchmark's posteriors it cuts tau 2-4x against the stretch move alone).
[[nodiscard]] MoveMix differential_moves();

struct EnsembleOptions {
  int walkers = 0;        ///< ensemble size, even and >= 2 dim; 0: default_walkers(dim)
  int steps = 2000;       ///< ensemble updates in all, burn-in included (the cap when check_every > 0)
  int burn_in = -1;       ///< updates discarded at the start; -1: the first half of the updates run
  double stretch = 2.0;   ///< a in g(z) ~ 1/sqrt(z) on [1/a, a] (GW10 eq. 9); a = 2 as GW10 and FM13
  MoveMix moves;          ///< the stretch move alone by default
  std::uint64_t seed = 1; ///< the same seed gives the same samples
  /// Threads that share each half-ensemble's density evaluations (OpenMP). The samples do not
  /// depend on it; the density must then be safe to call concurrently.
  int threads = 1;
  /// A run length that adapts: with check_every > 0, after every check_every updates the run so far
  /// (its first half dropped as burn-in) is handed to `stop`, and the run ends when it returns true,
  /// or after `steps` updates, which is then the cap. Needs burn_in = -1. The decision depends on
  /// the samples only, so the run is the same for any thread count.
  int check_every = 0;
  std::function<bool(const EnsembleRun&)> stop;
};

struct EnsembleRun {
  std::vector<Eigen::MatrixXd> chains;       ///< per walker: kept steps x dim (burn-in dropped)
  std::vector<Eigen::VectorXd> log_density;  ///< per walker: ln p at each kept step
  Eigen::VectorXd walker_acceptance;         ///< per walker: accepted fraction of all its proposals
  double acceptance = 0.0;                   ///< mean of walker_acceptance
  int evaluations = 0;                       ///< calls of the log density, start walkers included
  int steps = 0;                             ///< updates run, burn-in included
};

/// max(4 dim, 16), made even: twice GW10's minimum and enough that the two halves span the space.
[[nodiscard]] int default_walkers(int dim);
/// The ensemble size these options give in `dim` dimensions.
[[nodiscard]] int walker_count(const EnsembleOptions& options, int dim);
/// The burn-in these options give after `steps_run` updates (options.steps by default).
[[nodiscard]] int burn_in_steps(const EnsembleOptions& options, int steps_run = -1);

/// walker_count(options, dim) start points centre + spread * N(0, I), from options.seed (a
/// stream separate from the sampler's). Points outside the density's support are the caller's to
/// avoid (e.g. by a spread well inside the bounds).
[[nodiscard]] std::vector<Eigen::VectorXd> start_ball(const Eigen::VectorXd& centre, const Eigen::VectorXd& spread,
                                                      const EnsembleOptions& options);

/// Samples `log_density` from `start_walkers` (walker_count(options, dim) points of one
/// dimension, each with a finite density, not all in one lower-dimensional plane). Each update
/// moves the first half-ensemble against the second, then the second against the first (GW10
/// section 5, FM13 algorithm 3), so each half's density evaluations are independent of one another.
/// Throws std::invalid_argument for bad options or start walkers, naming what to change.
[[nodiscard]] EnsembleRun sample(const LogDensity& log_density, const std::vector<Eigen::VectorXd>& start_walkers,
                                 const EnsembleOptions& options);

}  // namespace sedwave::sampling
