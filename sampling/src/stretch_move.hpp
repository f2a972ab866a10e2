#pragma once
// The stretch move on a half-ensemble (GW10 section 5; FM13 algorithm 3), shared by the plain and
// the tempered sampler, and the differential-evolution moves the plain sampler may mix in
// (ensemble.hpp, MoveMix). A target is ln prior(x) + beta ln L(x); the plain sampler uses beta = 1
// and puts its whole density in the "prior" part.
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::sampling::detail {

struct LogParts {
  double log_prior = 0.0;
  double log_likelihood = 0.0;
};

/// Evaluates a point; the caller guarantees finite coordinates.
using PartsFunction = std::function<LogParts(const Eigen::VectorXd&)>;

/// ln prior + beta ln L, with 0 * ln L read as 0 (at beta = 0 the target is the prior).
[[nodiscard]] double tempered_log_density(const LogParts& parts, double beta);

struct Ensemble {
  std::vector<Eigen::VectorXd> positions;
  std::vector<LogParts> parts;
  std::vector<long> accepted;  ///< accepted proposals per walker
};

/// Counts the calls of a PartsFunction and guards it: non-finite coordinates are never passed
/// (the point is outside every support), NaN or +infinity results throw std::domain_error.
/// evaluate_all() spreads a batch over `threads` threads (OpenMP); the function must then be safe to
/// call concurrently. Results and the error thrown do not depend on the thread count.
class CountingEvaluator {
 public:
  explicit CountingEvaluator(PartsFunction function, int threads = 1)
      : function_(std::move(function)), threads_(threads) {}
  [[nodiscard]] LogParts operator()(const Eigen::VectorXd& x);
  /// Every point of the batch, in parallel where threads > 1; the first point's error (in batch
  /// order) is rethrown.
  [[nodiscard]] std::vector<LogParts> evaluate_all(const std::vector<Eigen::VectorXd>& points);
  [[nodiscard]] int evaluations() const { return evaluations_; }

 private:
  [[nodiscard]] LogParts checked(const Eigen::VectorXd& x) const;

  PartsFunction function_;
  int threads_ = 1;
  int evaluations_ = 0;
};

/// Evaluates the start walkers and checks them (count, dimension, finite target at beta, not all in
/// one lower-dimensional plane); std::invalid_argument names what to change.
[[nodiscard]] Ensemble start_ensemble(const std::vector<Eigen::VectorXd>& walkers, int expected_count, double beta,
                                      CountingEvaluator& evaluate);

/// One ensemble update: the first half moved against the second, then the second against the first.
void stretch_update(Ensemble& ensemble, double beta, double stretch, RandomStream& random,
                    CountingEvaluator& evaluate);

/// One update with a move drawn from `moves` (the stretch move alone draws no random number for the
/// choice, so its samples are those of stretch_update).
void mixed_update(Ensemble& ensemble, double stretch, const MoveMix& moves, RandomStream& random,
                  CountingEvaluator& evaluate);

/// One update of every ensemble (ensembles[t] at betas[t]), drawing the random numbers in the same
/// order as stretch_update on each ensemble in turn, so the samples are the same; but the first
/// halves of all ensembles are evaluated as one batch, then the second halves, which gives the
/// evaluator batches large enough to share among threads.
void stretch_update_all(const std::vector<Ensemble*>& ensembles, const std::vector<double>& betas, double stretch,
                        RandomStream& random, CountingEvaluator& evaluate);

/// Every update's state of one ensemble, kept so that a run whose length adapts can drop the first
/// half of whatever it has run as burn-in.
class History {
 public:
  History(int walkers, Eigen::Index dim) : dim_(dim), positions_(static_cast<std::size_t>(walkers)),
        log_density_(positions_.size()), log_likelihood_(positions_.size()) {}
  void record(const Ensemble& ensemble, double beta);
  [[nodiscard]] int steps() const { return steps_; }
  /// Per walker: the rows [first, steps()) as a steps x dim matrix, and the same rows of ln p and ln L.
  [[nodiscard]] std::vector<Eigen::MatrixXd> chains(int first) const;
  [[nodiscard]] std::vector<Eigen::VectorXd> log_density(int first) const;
  [[nodiscard]] std::vector<Eigen::VectorXd> log_likelihood(int first) const;

 private:
  Eigen::Index dim_;
  int steps_ = 0;
  std::vector<std::vector<double>> positions_;
  std::vector<std::vector<double>> log_density_;
  std::vector<std::vector<double>> log_likelihood_;
};

/// Checks the options shared by both samplers; std::invalid_argument names what to change.
void check_run_options(int walkers, int dim, int steps, int burn_in, double stretch, int threads);
/// Checks a move mixture for an ensemble of `walkers` (weights finite, >= 0, not all 0; enough
/// walkers in a half for the differential moves' distinct picks).
void check_moves(const MoveMix& moves, int walkers);
/// Checks the adaptive-length options (check_every >= 0; with check_every > 0 a stop test and burn_in = -1).
void check_adaptive_options(int check_every, bool has_stop, int burn_in);

}  // namespace sedwave::sampling::detail
