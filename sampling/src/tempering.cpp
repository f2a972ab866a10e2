#include "sedwave/sampling/tempering.hpp"

#include <algorithm>
#include <cmath>
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

void check_ladder(const std::vector<double>& betas) {
  if (betas.empty() || betas.front() != 1.0) {
    throw std::invalid_argument("the ladder of inverse temperatures must start at beta = 1 (the posterior)");
  }
  for (std::size_t i = 1; i < betas.size(); ++i) {
    if (!(betas[i] < betas[i - 1] && betas[i] > 0.0)) {
      throw std::invalid_argument("inverse temperature " + std::to_string(i) + " = " + std::to_string(betas[i]) +
                                  ": the ladder must descend strictly and stay > 0 (geometric_ladder makes one)");
    }
  }
}

struct Level {
  detail::Ensemble ensemble;
  std::vector<Eigen::MatrixXd> chains;
  std::vector<Eigen::VectorXd> log_density;
  std::vector<Eigen::VectorXd> log_likelihood;
};

void record(Level& level, double beta, int row) {
  for (std::size_t k = 0; k < level.ensemble.positions.size(); ++k) {
    level.chains[k].row(row) = level.ensemble.positions[k].transpose();
    level.log_density[k](row) = detail::tempered_log_density(level.ensemble.parts[k], beta);
    level.log_likelihood[k](row) = level.ensemble.parts[k].log_likelihood;
  }
}

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

EnsembleRun finish_level(Level& level, long steps) {
  EnsembleRun run;
  run.chains = std::move(level.chains);
  run.log_density = std::move(level.log_density);
  const auto walkers = static_cast<Eigen::Index>(level.ensemble.accepted.size());
  run.walker_acceptance.resize(walkers);
  for (Eigen::Index k = 0; k < walkers; ++k) {
    run.walker_acceptance(k) =
        static_cast<double>(level.ensemble.accepted[static_cast<std::size_t>(k)]) / static_cast<double>(steps);
  }
  run.acceptance = run.walker_acceptance.mean();
  return run;
}

// <ln L> and its beta-derivative d<ln L>/d beta = Var(ln L) at each beta (the variance identity of
// the power posterior; Friel & Pettitt 2008, JRSS B 70, 589).
struct LadderPoint {
  double beta = 0.0;
  double mean = 0.0;
  double variance = 0.0;
  double standard_error = 0.0;  ///< of the mean: sqrt(variance tau / draws)
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
  LadderPoint point;
  point.beta = beta;
  point.mean = mean;
  point.variance = sum_squares / (draws - 1.0);
  const double tau = autocorrelation_time(chains);
  point.standard_error = std::isnan(tau) ? 0.0 : std::sqrt(point.variance * tau / draws);
  return point;
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

TemperedRun sample_tempered(const PriorAndLikelihood& density, const std::vector<Eigen::VectorXd>& start_walkers,
                            const TemperingOptions& options) {
  if (!density.log_prior || !density.log_likelihood) {
    throw std::invalid_argument("tempering needs both the log prior and the log likelihood");
  }
  if (start_walkers.empty()) throw std::invalid_argument("no start walkers: give walker_count(options, dim) of them");
  const std::vector<double> betas =
      options.betas.empty() ? geometric_ladder(kDefaultTemperatures, kDefaultMaxTemperature) : options.betas;
  check_ladder(betas);
  const EnsembleOptions& ensemble_options = options.ensemble;
  const auto dim = static_cast<int>(start_walkers.front().size());
  const int walkers = walker_count(ensemble_options, dim);
  const int burn_in = burn_in_steps(ensemble_options);
  detail::check_run_options(walkers, dim, ensemble_options.steps, burn_in, ensemble_options.stretch,
                            ensemble_options.threads);

  detail::CountingEvaluator evaluate([&density](const Eigen::VectorXd& x) {
    const double log_prior = density.log_prior(x);
    // Outside the prior's support the likelihood is not asked (it may be undefined there).
    if (std::isinf(log_prior) && log_prior < 0.0) return detail::LogParts{log_prior, log_prior};
    return detail::LogParts{log_prior, density.log_likelihood(x)};
  }, ensemble_options.threads);
  const int kept = ensemble_options.steps - burn_in;
  std::vector<Level> levels;
  for (const double beta : betas) {
    Level level;
    level.ensemble = detail::start_ensemble(start_walkers, walkers, beta, evaluate);
    level.chains.assign(static_cast<std::size_t>(walkers), Eigen::MatrixXd(kept, dim));
    level.log_density.assign(static_cast<std::size_t>(walkers), Eigen::VectorXd(kept));
    level.log_likelihood.assign(static_cast<std::size_t>(walkers), Eigen::VectorXd(kept));
    levels.push_back(std::move(level));
  }

  RandomStream random(ensemble_options.seed);
  std::vector<long> swaps_accepted(betas.size() - 1, 0);
  std::vector<detail::Ensemble*> ensembles;
  for (Level& level : levels) ensembles.push_back(&level.ensemble);
  for (int step = 0; step < ensemble_options.steps; ++step) {
    detail::stretch_update_all(ensembles, betas, ensemble_options.stretch, random, evaluate);
    propose_swaps(levels, betas, random, swaps_accepted);
    if (step < burn_in) continue;
    for (std::size_t t = 0; t < levels.size(); ++t) record(levels[t], betas[t], step - burn_in);
  }

  TemperedRun run;
  run.betas = betas;
  run.swap_acceptance.resize(static_cast<Eigen::Index>(swaps_accepted.size()));
  for (std::size_t i = 0; i < swaps_accepted.size(); ++i) {
    run.swap_acceptance(static_cast<Eigen::Index>(i)) =
        static_cast<double>(swaps_accepted[i]) / (static_cast<double>(ensemble_options.steps) * walkers);
  }
  for (Level& level : levels) {
    run.log_likelihood.push_back(std::move(level.log_likelihood));
    run.levels.push_back(finish_level(level, ensemble_options.steps));
  }
  run.evaluations = evaluate.evaluations();
  return run;
}

Evidence thermodynamic_evidence(const TemperedRun& run) {
  std::vector<LadderPoint> points;
  for (std::size_t t = 0; t < run.betas.size(); ++t) points.push_back(ladder_point(run.betas[t], run.log_likelihood[t]));
  // The segment [0, beta_min] at beta_min's values (ptemcee).
  LadderPoint zero = points.back();
  zero.beta = 0.0;
  points.push_back(zero);

  Evidence evidence;
  evidence.log_evidence = corrected_trapezoid(points);
  std::vector<LadderPoint> coarse;
  for (std::size_t i = 0; i < points.size(); i += 2) coarse.push_back(points[i]);
  if (coarse.back().beta != 0.0) coarse.push_back(points.back());
  evidence.discretisation = std::abs(evidence.log_evidence - corrected_trapezoid(coarse));
  // Monte Carlo error of the means through the trapezoid weights (temperatures taken as independent).
  double variance = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double left = i > 0 ? points[i - 1].beta - points[i].beta : 0.0;
    const double right = i + 1 < points.size() ? points[i].beta - points[i + 1].beta : 0.0;
    const double weight = 0.5 * (left + right);
    variance += weight * weight * points[i].standard_error * points[i].standard_error;
  }
  evidence.monte_carlo = std::sqrt(variance);
  evidence.uncertainty = std::hypot(evidence.discretisation, evidence.monte_carlo);
  return evidence;
}

}  // namespace sedwave::sampling
