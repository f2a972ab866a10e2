#include "sedwave/sampling/ensemble.hpp"

#include <algorithm>
#include <stdexcept>

#include "sedwave/sampling/random_stream.hpp"
#include "stretch_move.hpp"

namespace sedwave::sampling {

namespace {

// Start points and moves draw from separate streams, so a caller who makes its own start walkers
// gets the same moves as one who uses start_ball.
constexpr std::uint64_t kStartStreamOffset = 0x9E3779B97F4A7C15ULL;

// The run so far as sample() returns it: the last steps_run - burn-in updates of every walker.
EnsembleRun kept_run(const detail::History& history, const detail::Ensemble& ensemble, int burn_in,
                     int evaluations) {
  EnsembleRun run;
  run.chains = history.chains(burn_in);
  run.log_density = history.log_density(burn_in);
  const auto walkers = static_cast<Eigen::Index>(ensemble.accepted.size());
  run.walker_acceptance.resize(walkers);
  for (Eigen::Index k = 0; k < walkers; ++k) {
    run.walker_acceptance(k) =
        static_cast<double>(ensemble.accepted[static_cast<std::size_t>(k)]) / static_cast<double>(history.steps());
  }
  run.acceptance = run.walker_acceptance.mean();
  run.evaluations = evaluations;
  run.steps = history.steps();
  return run;
}

}  // namespace

MoveMix differential_moves() { return {.stretch = 0.0, .differential_evolution = 0.8, .snooker = 0.2}; }

int default_walkers(int dim) {
  const int walkers = std::max(4 * dim, 16);
  return walkers + walkers % 2;
}

int walker_count(const EnsembleOptions& options, int dim) {
  return options.walkers == 0 ? default_walkers(dim) : options.walkers;
}

int burn_in_steps(const EnsembleOptions& options, int steps_run) {
  if (steps_run < 0) steps_run = options.steps;
  return options.burn_in == -1 ? steps_run / 2 : options.burn_in;
}

std::vector<Eigen::VectorXd> start_ball(const Eigen::VectorXd& centre, const Eigen::VectorXd& spread,
                                        const EnsembleOptions& options) {
  if (centre.size() != spread.size()) throw std::invalid_argument("start_ball: centre and spread differ in size");
  RandomStream random(options.seed ^ kStartStreamOffset);
  std::vector<Eigen::VectorXd> walkers(static_cast<std::size_t>(walker_count(options, static_cast<int>(centre.size()))));
  for (Eigen::VectorXd& walker : walkers) {
    walker = centre;
    for (Eigen::Index i = 0; i < centre.size(); ++i) walker(i) += spread(i) * random.normal();
  }
  return walkers;
}

EnsembleRun sample(const LogDensity& log_density, const std::vector<Eigen::VectorXd>& start_walkers,
                   const EnsembleOptions& options) {
  if (start_walkers.empty()) throw std::invalid_argument("no start walkers: give walker_count(options, dim) of them");
  const int dim = static_cast<int>(start_walkers.front().size());
  const int walkers = walker_count(options, dim);
  detail::check_run_options(walkers, dim, options.steps, burn_in_steps(options), options.stretch, options.threads);

  detail::CountingEvaluator evaluate(
      [&log_density](const Eigen::VectorXd& x) { return detail::LogParts{log_density(x), 0.0}; }, options.threads);
  detail::check_adaptive_options(options.check_every, static_cast<bool>(options.stop), options.burn_in);
  detail::check_moves(options.moves, walkers);
  detail::Ensemble ensemble = detail::start_ensemble(start_walkers, walkers, 1.0, evaluate);
  RandomStream random(options.seed);
  detail::History history(walkers, dim);
  for (int step = 1; step <= options.steps; ++step) {
    detail::mixed_update(ensemble, options.stretch, options.moves, random, evaluate);
    history.record(ensemble, 1.0);
    if (options.check_every > 0 && step % options.check_every == 0 && step < options.steps &&
        options.stop(kept_run(history, ensemble, burn_in_steps(options, step), evaluate.evaluations()))) {
      break;
    }
  }
  return kept_run(history, ensemble, burn_in_steps(options, history.steps()), evaluate.evaluations());
}

}  // namespace sedwave::sampling
