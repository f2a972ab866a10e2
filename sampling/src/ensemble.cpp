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

struct KeptSamples {
  std::vector<Eigen::MatrixXd> chains;
  std::vector<Eigen::VectorXd> log_density;
};

KeptSamples allocate_kept(int walkers, int kept, Eigen::Index dim) {
  KeptSamples kept_samples;
  kept_samples.chains.assign(static_cast<std::size_t>(walkers), Eigen::MatrixXd(kept, dim));
  kept_samples.log_density.assign(static_cast<std::size_t>(walkers), Eigen::VectorXd(kept));
  return kept_samples;
}

void record(const detail::Ensemble& ensemble, int row, KeptSamples& kept) {
  for (std::size_t k = 0; k < ensemble.positions.size(); ++k) {
    kept.chains[k].row(row) = ensemble.positions[k].transpose();
    kept.log_density[k](row) = ensemble.parts[k].log_prior;
  }
}

}  // namespace

int default_walkers(int dim) {
  const int walkers = std::max(4 * dim, 16);
  return walkers + walkers % 2;
}

int walker_count(const EnsembleOptions& options, int dim) {
  return options.walkers == 0 ? default_walkers(dim) : options.walkers;
}

int burn_in_steps(const EnsembleOptions& options) { return options.burn_in == -1 ? options.steps / 2 : options.burn_in; }

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
  const int burn_in = burn_in_steps(options);
  detail::check_run_options(walkers, dim, options.steps, burn_in, options.stretch, options.threads);

  detail::CountingEvaluator evaluate(
      [&log_density](const Eigen::VectorXd& x) { return detail::LogParts{log_density(x), 0.0}; }, options.threads);
  detail::Ensemble ensemble = detail::start_ensemble(start_walkers, walkers, 1.0, evaluate);
  RandomStream random(options.seed);
  KeptSamples kept = allocate_kept(walkers, options.steps - burn_in, dim);
  for (int step = 0; step < options.steps; ++step) {
    detail::stretch_update(ensemble, 1.0, options.stretch, random, evaluate);
    if (step >= burn_in) record(ensemble, step - burn_in, kept);
  }

  EnsembleRun run;
  run.chains = std::move(kept.chains);
  run.log_density = std::move(kept.log_density);
  run.walker_acceptance.resize(walkers);
  for (int k = 0; k < walkers; ++k) {
    run.walker_acceptance(k) =
        static_cast<double>(ensemble.accepted[static_cast<std::size_t>(k)]) / static_cast<double>(options.steps);
  }
  run.acceptance = run.walker_acceptance.mean();
  run.evaluations = evaluate.evaluations();
  return run;
}

}  // namespace sedwave::sampling
