#include "sedwave/sampling/tempering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/random_stream.hpp"
#include "stretch_move.hpp"

namespace sedwave::sampling {

namespace {

constexpr int kDefaultTemperatures = 16;
constexpr double kDefaultMaxTemperature = 1e6;
// The ladder's adaptation gain kappa(t) = t0 / (nu (t + t0)) (VFM16 eq. 13, with their and
// ptemcee's t0 = 10^4 and nu = 10^2): nearly constant over a burn-in of a few thousand steps.
constexpr double kAdaptationLag = 1e4;
constexpr double kAdaptationTime = 1e1;

void check_ladder(const std::vector<double>& betas) {
  if (betas.empty() || betas.front() != 1.0) {
    throw std::invalid_argument("the ladder of inverse temperatures must start at beta = 1 (the posterior)");
  }
  for (std::size_t i = 1; i < betas.size(); ++i) {
    const bool last = i + 1 == betas.size();
    if (!(betas[i] < betas[i - 1] && (betas[i] > 0.0 || (last && betas[i] == 0.0)))) {
      throw std::invalid_argument("inverse temperature " + std::to_string(i) + " = " + std::to_string(betas[i]) +
                                  ": the ladder must descend strictly and stay > 0, but for a last beta = 0 "
                                  "(evidence_ladder makes one)");
    }
  }
}

struct Level {
  detail::Ensemble ensemble;
  detail::History history;
  bool prior_draws = false;  ///< beta = 0, refreshed by independent prior draws
};

// One round of swaps, hottest pair first (VFM16 section 2, ptemcee): walkers of neighbouring
// temperatures are paired at random and swap positions with probability
// min(1, exp((beta_cold - beta_hot) (ln L_hot - ln L_cold))) (VFM16 eq. 6).
void propose_swaps(std::vector<Level>& levels, const std::vector<double>& betas, RandomStream& random,
                   std::vector<long>& accepted) {
  const auto walkers = static_cast<int>(levels.front().ensemble.positions.size());
  for (std::size_t hot = levels.size() - 1; hot > 0; --hot) {
    const std::size_t cold = hot - 1;
    std::vector<int> partner(static_cast<std::size_t>(walkers));
    std::iota(partner.begin(), partner.end(), 0);
    for (int k = walkers - 1; k > 0; --k) std::swap(partner[static_cast<std::size_t>(k)], partner[static_cast<std::size_t>(random.index(k + 1))]);
    for (int k = 0; k < walkers; ++k) {
      const auto hot_walker = static_cast<std::size_t>(k);
      const auto cold_walker = static_cast<std::size_t>(partner[hot_walker]);
      detail::Ensemble& hot_ensemble = levels[hot].ensemble;
      detail::Ensemble& cold_ensemble = levels[cold].ensemble;
      const double log_ratio = (betas[cold] - betas[hot]) * (hot_ensemble.parts[hot_walker].log_likelihood -
                                                             cold_ensemble.parts[cold_walker].log_likelihood);
      if (std::log(random.uniform()) < log_ratio) {
        std::swap(hot_ensemble.positions[hot_walker], cold_ensemble.positions[cold_walker]);
        std::swap(hot_ensemble.parts[hot_walker], cold_ensemble.parts[cold_walker]);
        ++accepted[cold];
      }
    }
  }
}

// One step of VFM16's ladder dynamics (section 3.1, eqs. 12-13): the log width S_i of the
// interval from temperature T_i = 1 / beta_i to T_(i+1) moves by kappa(t) (A_i - A_(i+1)), A_i the
// fraction of this step's swaps accepted between them, so an interval that swaps more easily than
// the next widens and rates even out. T_0 = 1 and the hottest finite temperature stay; the last
// interval takes up what the others leave. A step that would push the next-hottest past the
// hottest is skipped, so the ladder stays strictly ordered.
void adapt_ladder(std::vector<double>& betas, const std::vector<long>& accepted_now, int walkers, int step) {
  const std::size_t finite = betas.back() == 0.0 ? betas.size() - 1 : betas.size();
  if (finite < 3) return;
  const double kappa = kAdaptationLag / (kAdaptationTime * (static_cast<double>(step) + kAdaptationLag));
  std::vector<double> temperature(finite), adapted(finite);
  for (std::size_t i = 0; i < finite; ++i) temperature[i] = 1.0 / betas[i];
  adapted[0] = temperature[0];
  for (std::size_t i = 0; i + 2 < finite; ++i) {
    const double rate_difference = static_cast<double>(accepted_now[i] - accepted_now[i + 1]) / walkers;
    adapted[i + 1] = adapted[i] + (temperature[i + 1] - temperature[i]) * std::exp(kappa * rate_difference);
  }
  if (!(adapted[finite - 2] < temperature[finite - 1])) return;
  for (std::size_t i = 1; i + 1 < finite; ++i) betas[i] = 1.0 / adapted[i];
}

// A beta = 0 rung refreshed by independent prior draws: every walker replaced (drawn in walker
// order before any is evaluated, so the run does not depend on the thread count).
void redraw_from_prior(detail::Ensemble& ensemble, const PriorAndLikelihood& density, RandomStream& random,
                       detail::CountingEvaluator& evaluate) {
  std::vector<Eigen::VectorXd> draws;
  for (std::size_t k = 0; k < ensemble.positions.size(); ++k) draws.push_back(density.draw_prior(random));
  const std::vector<detail::LogParts> parts = evaluate.evaluate_all(draws);
  for (std::size_t k = 0; k < draws.size(); ++k) {
    if (!(parts[k].log_prior > -std::numeric_limits<double>::infinity())) {
      throw std::domain_error("a draw from the prior lies outside the prior's support: draw_prior and log_prior "
                              "disagree");
    }
    ensemble.positions[k] = std::move(draws[k]);
    ensemble.parts[k] = parts[k];
    ++ensemble.accepted[k];
  }
}

EnsembleRun level_run(const Level& level, int burn_in) {
  EnsembleRun run;
  run.chains = level.history.chains(burn_in);
  run.log_density = level.history.log_density(burn_in);
  const auto walkers = static_cast<Eigen::Index>(level.ensemble.accepted.size());
  run.walker_acceptance.resize(walkers);
  for (Eigen::Index k = 0; k < walkers; ++k) {
    run.walker_acceptance(k) = static_cast<double>(level.ensemble.accepted[static_cast<std::size_t>(k)]) /
                               static_cast<double>(level.history.steps());
  }
  run.acceptance = run.walker_acceptance.mean();
  run.steps = level.history.steps();
  return run;
}

// The run so far, its burn-in dropped; swaps_accepted counts the swaps of the steps after the
// ladder's adaptation (adapt_steps of them before).
TemperedRun tempered_run(const std::vector<Level>& levels, const std::vector<double>& betas,
                         const std::vector<long>& swaps_accepted, int adapt_steps, int burn_in, int evaluations) {
  TemperedRun run;
  run.betas = betas;
  const int steps = levels.front().history.steps();
  const auto walkers = static_cast<double>(levels.front().ensemble.positions.size());
  const auto counted = static_cast<double>(std::max(steps - adapt_steps, 1));
  run.swap_acceptance.resize(static_cast<Eigen::Index>(swaps_accepted.size()));
  for (std::size_t i = 0; i < swaps_accepted.size(); ++i) {
    run.swap_acceptance(static_cast<Eigen::Index>(i)) = static_cast<double>(swaps_accepted[i]) / (counted * walkers);
  }
  for (std::size_t t = 0; t < levels.size(); ++t) {
    run.log_likelihood.push_back(levels[t].history.log_likelihood(burn_in));
    run.levels.push_back(level_run(levels[t], burn_in));
    run.levels.back().evaluations = evaluations;
  }
  run.evaluations = evaluations;
  run.steps = steps;
  return run;
}

// <ln L> and its beta-derivative d<ln L>/d beta = Var(ln L) at each beta (the variance identity of
// the power posterior; Friel & Pettitt 2008, JRSS B 70, 589).
struct LadderPoint {
  double beta = 0.0;
  double mean = 0.0;
  double variance = 0.0;
};

// Trapezoid rule with the Euler-Maclaurin end correction built from the exact derivatives
// (Friel, Hurn & Wyse 2014, Stat. Comput. 24, 709, eq. 9): per segment
// (b_i - b_j) (f_i + f_j) / 2 - (b_i - b_j)^2 (f'_i - f'_j) / 12, error O(h^4) instead of O(h^2).
// Points in descending beta, ending at beta = 0. <ln L>_beta never decreases with beta (its
// derivative is a variance), so a segment's integral lies between its width times the two end
// values; the correction is held inside those limits, which it leaves only where the variances are
// poorly sampled (an unconverged hot ensemble) and would otherwise dominate the sum.
double corrected_trapezoid(const std::vector<LadderPoint>& points) {
  double integral = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double width = points[i - 1].beta - points[i].beta;
    const double segment = 0.5 * width * (points[i - 1].mean + points[i].mean) -
                           width * width / 12.0 * (points[i - 1].variance - points[i].variance);
    const auto [low, high] = std::minmax(points[i].mean, points[i - 1].mean);
    integral += std::clamp(segment, width * low, width * high);
  }
  return integral;
}

LadderPoint ladder_point(double beta, const std::vector<Eigen::VectorXd>& chains) {
  const auto draws = static_cast<double>(chains.size() * static_cast<std::size_t>(chains.front().size()));
  double sum = 0.0;
  double sum_squares = 0.0;
  for (const Eigen::VectorXd& chain : chains) sum += chain.sum();
  const double mean = sum / draws;
  for (const Eigen::VectorXd& chain : chains) sum_squares += (chain.array() - mean).square().sum();
  return {beta, mean, sum_squares / (draws - 1.0)};
}

// Per kept step, the mean over the walkers of one rung's values: the ensemble as one chain.
Eigen::VectorXd step_means(const std::vector<Eigen::VectorXd>& walkers) {
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(walkers.front().size());
  for (const Eigen::VectorXd& walker : walkers) mean += walker;
  return mean / static_cast<double>(walkers.size());
}

// The variance of the time average of `series` (one value per kept step): its variance times its
// integrated autocorrelation time over the number of steps (0 for a constant series). The time is
// Geyer's initial sequence estimate: walkers wander through the ladder by swaps, slowly, and give
// the ladder's series a long, faint tail of autocorrelation that Sokal's window (c = 5) cuts off;
// with it the stated error was ~10 % low over 200 seeds of a Gaussian problem (90 % of runs within
// 2 stated sigmas), with Geyer's estimate it matches the scatter (94 of 100).
double variance_of_mean(const Eigen::VectorXd& series) {
  const auto steps = static_cast<double>(series.size());
  const double variance = (series.array() - series.mean()).square().sum() / (steps - 1.0);
  const double tau = initial_sequence_autocorrelation_time(series);
  return std::isnan(tau) || !(variance > 0.0) ? 0.0 : variance * std::max(tau, 1.0) / steps;
}

// One stone: ln < L^delta >_hot from the hotter rung's ln L draws; its per-step weight means
// (normalised by their overall mean) for the error; and the Kish fraction of its weights.
struct Stone {
  double log_ratio = 0.0;
  Eigen::VectorXd relative_weights;  ///< per kept step: mean weight / overall mean weight
  double overlap = 0.0;
};

Stone stone(const std::vector<Eigen::VectorXd>& hot_log_likelihood, double delta) {
  double peak = -std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& walker : hot_log_likelihood) peak = std::max(peak, walker.maxCoeff());
  if (!std::isfinite(peak)) {
    throw std::invalid_argument("every draw of a rung has likelihood zero: the evidence cannot be estimated");
  }
  std::vector<Eigen::VectorXd> weights;
  double sum = 0.0, sum_squares = 0.0, count = 0.0;
  for (const Eigen::VectorXd& walker : hot_log_likelihood) {
    // exp(-infinity) = 0: a draw where the model has no value carries no weight.
    weights.emplace_back((delta * (walker.array() - peak)).exp().matrix());
    sum += weights.back().sum();
    sum_squares += weights.back().squaredNorm();
    count += static_cast<double>(walker.size());
  }
  const double mean = sum / count;
  return {delta * peak + std::log(mean), step_means(weights) / mean, sum * sum / (count * sum_squares)};
}

}  // namespace

std::vector<double> geometric_ladder(int temperatures, double max_temperature) {
  if (temperatures < 2 || !(max_temperature > 1.0)) {
    throw std::invalid_argument("geometric_ladder: need at least 2 temperatures and a maximum temperature > 1");
  }
  std::vector<double> betas(static_cast<std::size_t>(temperatures));
  for (int i = 0; i < temperatures; ++i) {
    betas[static_cast<std::size_t>(i)] = std::pow(max_temperature, -static_cast<double>(i) / (temperatures - 1));
  }
  return betas;
}

std::vector<double> evidence_ladder(int temperatures, double max_temperature) {
  std::vector<double> betas = geometric_ladder(temperatures, max_temperature);
  betas.push_back(0.0);
  return betas;
}

TemperedRun sample_tempered(const PriorAndLikelihood& density, const std::vector<Eigen::VectorXd>& start_walkers,
                            const TemperingOptions& options) {
  const std::size_t temperatures =
      options.betas.empty() ? static_cast<std::size_t>(kDefaultTemperatures) + 1 : options.betas.size();
  return sample_tempered(density, std::vector<std::vector<Eigen::VectorXd>>(temperatures, start_walkers), options);
}

TemperedRun sample_tempered(const PriorAndLikelihood& density,
                            const std::vector<std::vector<Eigen::VectorXd>>& level_starts,
                            const TemperingOptions& options) {
  if (!density.log_prior || !density.log_likelihood) {
    throw std::invalid_argument("tempering needs both the log prior and the log likelihood");
  }
  std::vector<double> betas =
      options.betas.empty() ? evidence_ladder(kDefaultTemperatures, kDefaultMaxTemperature) : options.betas;
  check_ladder(betas);
  if (level_starts.size() != betas.size()) {
    throw std::invalid_argument("got " + std::to_string(level_starts.size()) + " sets of start walkers for " +
                                std::to_string(betas.size()) + " temperatures: give one per temperature");
  }
  if (level_starts.front().empty()) {
    throw std::invalid_argument("no start walkers: give walker_count(options, dim) of them");
  }
  const EnsembleOptions& ensemble_options = options.ensemble;
  const auto dim = static_cast<int>(level_starts.front().front().size());
  const int walkers = walker_count(ensemble_options, dim);
  detail::check_run_options(walkers, dim, ensemble_options.steps, burn_in_steps(ensemble_options),
                            ensemble_options.stretch, ensemble_options.threads);
  detail::check_adaptive_options(ensemble_options.check_every, static_cast<bool>(options.stop),
                                 ensemble_options.burn_in);
  if (ensemble_options.moves.differential_evolution != 0.0 || ensemble_options.moves.snooker != 0.0) {
    // The evidence's accuracy was established with the stretch move on every rung.
    throw std::invalid_argument("parallel tempering moves its rungs by the stretch move only: leave "
                                "ensemble.moves at its default");
  }
  if (options.adapt_steps < 0 || burn_in_steps(ensemble_options) < 2 * options.adapt_steps) {
    throw std::invalid_argument("adapt_steps = " + std::to_string(options.adapt_steps) + " with a burn-in of " +
                                std::to_string(burn_in_steps(ensemble_options)) +
                                " steps: the ladder may adapt only during the first half of the burn-in (0 keeps it fixed)");
  }

  detail::CountingEvaluator evaluate([&density](const Eigen::VectorXd& x) {
    const double log_prior = density.log_prior(x);
    // Outside the prior's support the likelihood is not asked (it may be undefined there).
    if (std::isinf(log_prior) && log_prior < 0.0) return detail::LogParts{log_prior, log_prior};
    return detail::LogParts{log_prior, density.log_likelihood(x)};
  }, ensemble_options.threads);
  std::vector<Level> levels;
  for (std::size_t t = 0; t < betas.size(); ++t) {
    levels.push_back({detail::start_ensemble(level_starts[t], walkers, betas[t], evaluate),
                      detail::History(walkers, dim), betas[t] == 0.0 && static_cast<bool>(density.draw_prior)});
  }

  RandomStream random(ensemble_options.seed);
  std::vector<long> swaps_accepted(betas.size() - 1, 0);
  // The rungs the stretch move updates (a rung of prior draws is redrawn instead) and their betas,
  // which follow the ladder while it adapts.
  std::vector<detail::Ensemble*> moved;
  for (Level& level : levels) {
    if (!level.prior_draws) moved.push_back(&level.ensemble);
  }
  const auto betas_of_moved = [&] {
    std::vector<double> out;
    for (std::size_t t = 0; t < levels.size(); ++t) {
      if (!levels[t].prior_draws) out.push_back(betas[t]);
    }
    return out;
  };
  std::vector<double> moved_betas = betas_of_moved();
  const int adapt_steps = options.adapt_steps;
  std::vector<long> accepted_now(swaps_accepted.size());
  for (int step = 1; step <= ensemble_options.steps; ++step) {
    detail::stretch_update_all(moved, moved_betas, ensemble_options.stretch, random, evaluate);
    if (levels.back().prior_draws) redraw_from_prior(levels.back().ensemble, density, random, evaluate);
    std::fill(accepted_now.begin(), accepted_now.end(), 0);
    propose_swaps(levels, betas, random, accepted_now);
    for (std::size_t t = 0; t < levels.size(); ++t) levels[t].history.record(levels[t].ensemble, betas[t]);
    if (step <= adapt_steps) {
      adapt_ladder(betas, accepted_now, walkers, step);
      moved_betas = betas_of_moved();
    } else {
      for (std::size_t i = 0; i < swaps_accepted.size(); ++i) swaps_accepted[i] += accepted_now[i];
    }
    if (ensemble_options.check_every > 0 && step % ensemble_options.check_every == 0 &&
        step < ensemble_options.steps && step >= 4 * adapt_steps &&
        options.stop(tempered_run(levels, betas, swaps_accepted, adapt_steps, burn_in_steps(ensemble_options, step),
                                  evaluate.evaluations()))) {
      break;
    }
  }
  const int steps = levels.front().history.steps();
  return tempered_run(levels, betas, swaps_accepted, adapt_steps, burn_in_steps(ensemble_options, steps),
                      evaluate.evaluations());
}

Evidence thermodynamic_evidence(const TemperedRun& run) {
  if (run.betas.size() < 2 || run.betas.back() != 0.0) {
    throw std::invalid_argument("the evidence needs a ladder that ends at beta = 0 (the prior): append it "
                                "(evidence_ladder makes such a ladder)");
  }
  Evidence evidence;
  // Stepping stones, rung k + 1's draws giving Z_k / Z_(k+1) (Xie et al. 2011, eq. 6). The error by
  // the delta method: ln Z - its estimate ~ sum_k (mean_k - r_k) / r_k, whose terms are averages
  // over the same kept steps; their sum per step is one time series whose autocorrelation time
  // counts the correlations within and between rungs that the swaps make.
  Eigen::VectorXd ladder_series = Eigen::VectorXd::Zero(run.log_likelihood.front().front().size());
  evidence.stone_overlap = 1.0;
  for (std::size_t k = 0; k + 1 < run.betas.size(); ++k) {
    const Stone s = stone(run.log_likelihood[k + 1], run.betas[k] - run.betas[k + 1]);
    // E[ln mean] = ln r - Var(mean) / (2 r^2) to second order: the bias corrected.
    evidence.log_evidence += s.log_ratio + 0.5 * variance_of_mean(s.relative_weights);
    ladder_series += s.relative_weights;
    evidence.stone_overlap = std::min(evidence.stone_overlap, s.overlap);
  }
  evidence.uncertainty = std::sqrt(variance_of_mean(ladder_series));
  evidence.autocorrelation_time = initial_sequence_autocorrelation_time(ladder_series);
  if (std::isnan(evidence.autocorrelation_time)) evidence.autocorrelation_time = 1.0;

  std::vector<LadderPoint> points;
  for (std::size_t t = 0; t < run.betas.size(); ++t) points.push_back(ladder_point(run.betas[t], run.log_likelihood[t]));
  evidence.thermodynamic_integration = corrected_trapezoid(points);
  std::vector<LadderPoint> coarse;
  for (std::size_t i = 0; i < points.size(); i += 2) coarse.push_back(points[i]);
  if (coarse.back().beta != 0.0) coarse.push_back(points.back());
  evidence.discretisation = std::abs(evidence.thermodynamic_integration - corrected_trapezoid(coarse));
  if (!std::isfinite(evidence.thermodynamic_integration)) {
    evidence.thermodynamic_integration = std::numeric_limits<double>::quiet_NaN();
    evidence.discretisation = std::numeric_limits<double>::quiet_NaN();
  }
  return evidence;
}

}  // namespace sedwave::sampling
