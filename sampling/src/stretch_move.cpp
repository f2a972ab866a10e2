#include "stretch_move.hpp"

#include "minus_infinity.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <Eigen/SVD>

namespace sedwave::sampling::detail {

namespace {

// Smallest accepted singular value of the start walkers' standardised deviations (scaled so that it
// is the square root of the smallest eigenvalue of their correlation matrix). Below it the walkers
// lie, to rounding, in a lower-dimensional plane, which the stretch move can never leave: every
// proposal is an affine combination of two walkers (GW10 section 3).
constexpr double kMinSpreadRatio = 1e-6;

void check_spread(const std::vector<Eigen::VectorXd>& walkers) {
  const auto count = static_cast<Eigen::Index>(walkers.size());
  const Eigen::Index dim = walkers.front().size();
  Eigen::MatrixXd deviations(count, dim);
  for (Eigen::Index k = 0; k < count; ++k) deviations.row(k) = walkers[k].transpose();
  for (Eigen::Index i = 0; i < dim; ++i) {
    // Scaled to at most 1 before centring, so that huge coordinates cannot overflow the mean or norm.
    auto column = deviations.col(i);
    const double largest = column.cwiseAbs().maxCoeff();
    if (largest > 0.0) column /= largest;
    column.array() -= column.mean();
    const double spread = column.norm();
    if (!(spread > 0.0)) {
      throw std::invalid_argument("start walkers all have the same parameter " + std::to_string(i) +
                                  ": scatter them around the start point (e.g. start_ball with a spread > 0)");
    }
    column /= spread;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(deviations);
  const double smallest = svd.singularValues()(dim - 1);
  if (smallest < kMinSpreadRatio) {
    std::ostringstream message;
    message << "start walkers lie (nearly) in a lower-dimensional plane (smallest singular value of their "
               "standardised deviations "
            << smallest << " < " << kMinSpreadRatio
            << "): the stretch move cannot leave it; scatter the walkers independently in every parameter";
    throw std::invalid_argument(message.str());
  }
}

// z ~ g(z) = 1 / sqrt(z) on [1/a, a] (GW10 eq. 9) by inversion of its distribution function:
// z = ((a - 1) u + 1)^2 / a.
double draw_stretch(double a, RandomStream& random) {
  const double root = (a - 1.0) * random.uniform() + 1.0;
  return root * root / a;
}

enum class MoveKind { Stretch, DifferentialEvolution, Snooker };

// ter Braak 2006, section 3: g = 2.38 / sqrt(2 dim), the optimal scale for a Gaussian target, and
// g = 1 on one update in ten, a jump along the whole spread of the ensemble (between modes, or from
// one end of a ridge to the other).
constexpr double kDeScale = 2.38;
constexpr double kDeFullJumpShare = 0.1;
// The factor on g, uniform on [1 - b, 1 + b]: ter Braak's small random perturbation, which keeps
// the chain from being confined to the finite set of the ensemble's differences; made relative to
// g (rather than an added noise of fixed size) so the move stays unchanged by an affine map.
constexpr double kDeJitter = 0.1;
// ter Braak & Vrugt 2008, section 3: the snooker's scale uniform on [1.2, 2.2].
constexpr double kSnookerLow = 1.2;
constexpr double kSnookerHigh = 2.2;

// The random numbers of one walker's move: drawn for a whole half before any position is formed,
// in walker order, so the evaluations that follow may run in any order (or in parallel) without
// changing the samples.
struct MoveDraw {
  int anchor = 0;          ///< index into the complementary half (stretch: X_j; snooker: Z)
  int first = 0;           ///< differential moves: X_a (complementary half, distinct from anchor)
  int second = 0;          ///< differential moves: X_b (distinct from first and anchor)
  double scale = 1.0;      ///< stretch: z; differential evolution: g; snooker: its scale
  double log_uniform = 0.0;
};

// An index in [0, n) other than the `taken` ones (distinct, fewer than n), uniform over the rest.
int distinct_index(int n, std::initializer_list<int> taken, RandomStream& random) {
  int i = random.index(n - static_cast<int>(taken.size()));
  // Skip the taken ones in increasing order so that every free index is equally likely.
  std::vector<int> sorted(taken);
  std::sort(sorted.begin(), sorted.end());
  for (const int t : sorted) i += i >= t ? 1 : 0;
  return i;
}

std::vector<MoveDraw> draw_half(MoveKind kind, int count, double a, double de_scale, RandomStream& random) {
  std::vector<MoveDraw> draws(static_cast<std::size_t>(count));
  for (MoveDraw& draw : draws) {
    switch (kind) {
      case MoveKind::Stretch:
        draw.anchor = random.index(count);
        draw.scale = draw_stretch(a, random);
        break;
      case MoveKind::DifferentialEvolution:
        draw.first = random.index(count);
        draw.second = distinct_index(count, {draw.first}, random);
        draw.scale = de_scale * (1.0 + kDeJitter * (2.0 * random.uniform() - 1.0));
        break;
      case MoveKind::Snooker:
        draw.anchor = random.index(count);
        draw.first = distinct_index(count, {draw.anchor}, random);
        draw.second = distinct_index(count, {draw.anchor, draw.first}, random);
        draw.scale = kSnookerLow + (kSnookerHigh - kSnookerLow) * random.uniform();
        break;
    }
    draw.log_uniform = std::log(random.uniform());
  }
  return draws;
}

// The two halves of every ensemble's update, with their draws.
struct HalfMove {
  Ensemble* ensemble = nullptr;
  double beta = 1.0;
  MoveKind kind = MoveKind::Stretch;
  std::vector<MoveDraw> draws;
};

// A proposal and the log of its extra acceptance factor (the ratio of proposal densities and
// Jacobian; 0 for a symmetric proposal; -infinity for one never accepted).
struct Proposal {
  Eigen::VectorXd point;
  double log_factor = 0.0;
};

Proposal propose(MoveKind kind, const MoveDraw& draw, const Eigen::VectorXd& x,
                 const std::vector<Eigen::VectorXd>& positions, int other) {
  const auto at = [&](int i) -> const Eigen::VectorXd& { return positions[static_cast<std::size_t>(other + i)]; };
  const auto dim = static_cast<double>(x.size());
  switch (kind) {
    case MoveKind::Stretch:
      // GW10 eq. 7 (FM13 eq. 10): Y = X_j + z (X_k - X_j), X_j the anchor from the other half;
      // accepted with min(1, z^(N-1) p(Y) / p(X_k)) (GW10 eq. 7; FM13 eq. 11).
      return {at(draw.anchor) + draw.scale * (x - at(draw.anchor)), (dim - 1.0) * std::log(draw.scale)};
    case MoveKind::DifferentialEvolution:
      // ter Braak 2006, eq. 2: symmetric, since (a, b) and (b, a) are equally likely.
      return {x + draw.scale * (at(draw.first) - at(draw.second)), 0.0};
    case MoveKind::Snooker: {
      // ter Braak & Vrugt 2008, section 3 and eq. 4: a jump along the line through X_k and Z by
      // the projection of X_a - X_b on it, with the factor (|Y - Z| / |X_k - Z|)^(dim - 1).
      const Eigen::VectorXd line = x - at(draw.anchor);
      const double length = line.norm();
      if (!(length > 0.0)) return {x, kMinusInfinity};
      const Eigen::VectorXd unit = line / length;
      const Eigen::VectorXd y = x + draw.scale * unit.dot(at(draw.first) - at(draw.second)) * unit;
      const double new_length = (y - at(draw.anchor)).norm();
      if (!(new_length > 0.0)) return {y, kMinusInfinity};
      return {y, (dim - 1.0) * (std::log(new_length) - std::log(length))};
    }
  }
  return {x, kMinusInfinity};
}

void append_proposals(const HalfMove& move, int begin, int other, std::vector<Eigen::VectorXd>& proposals,
                      std::vector<double>& log_factors) {
  const std::vector<Eigen::VectorXd>& positions = move.ensemble->positions;
  for (std::size_t i = 0; i < move.draws.size(); ++i) {
    Proposal p = propose(move.kind, move.draws[i], positions[static_cast<std::size_t>(begin) + i], positions, other);
    proposals.push_back(std::move(p.point));
    log_factors.push_back(p.log_factor);
  }
}

void accept_or_reject(const HalfMove& move, int begin, std::vector<Eigen::VectorXd>& proposals,
                      const std::vector<double>& log_factors, const std::vector<LogParts>& parts, std::size_t first) {
  Ensemble& ensemble = *move.ensemble;
  for (std::size_t i = 0; i < move.draws.size(); ++i) {
    const auto k = static_cast<std::size_t>(begin) + i;
    const double proposed = tempered_log_density(parts[first + i], move.beta);
    if (proposed == kMinusInfinity || log_factors[first + i] == kMinusInfinity) continue;
    const double log_ratio = log_factors[first + i] + proposed - tempered_log_density(ensemble.parts[k], move.beta);
    if (move.draws[i].log_uniform < log_ratio) {
      ensemble.positions[k] = std::move(proposals[first + i]);
      ensemble.parts[k] = parts[first + i];
      ++ensemble.accepted[k];
    }
  }
}

// Moves half `which` (0: walkers [0, half) against [half, 2 half); 1: the reverse) of every ensemble,
// all proposals evaluated as one batch.
void update_halves(const std::vector<HalfMove>& moves, int which, CountingEvaluator& evaluate) {
  std::vector<Eigen::VectorXd> proposals;
  std::vector<double> log_factors;
  for (const HalfMove& move : moves) {
    const int half = static_cast<int>(move.ensemble->positions.size()) / 2;
    append_proposals(move, which * half, (1 - which) * half, proposals, log_factors);
  }
  const std::vector<LogParts> parts = evaluate.evaluate_all(proposals);
  std::size_t first = 0;
  for (const HalfMove& move : moves) {
    const int half = static_cast<int>(move.ensemble->positions.size()) / 2;
    accept_or_reject(move, which * half, proposals, log_factors, parts, first);
    first += move.draws.size();
  }
}

// One update of every ensemble with the move `kind`.
void update_all(const std::vector<Ensemble*>& ensembles, const std::vector<double>& betas, MoveKind kind,
                double stretch, double de_scale, RandomStream& random, CountingEvaluator& evaluate) {
  std::vector<HalfMove> first_halves, second_halves;
  for (std::size_t t = 0; t < ensembles.size(); ++t) {
    const int half = static_cast<int>(ensembles[t]->positions.size()) / 2;
    // The draws of the first half, then the second, ensemble after ensemble: the order in which
    // an update of each ensemble alone would draw them.
    first_halves.push_back({ensembles[t], betas[t], kind, draw_half(kind, half, stretch, de_scale, random)});
    second_halves.push_back({ensembles[t], betas[t], kind, draw_half(kind, half, stretch, de_scale, random)});
  }
  update_halves(first_halves, 0, evaluate);
  update_halves(second_halves, 1, evaluate);
}

}  // namespace

double tempered_log_density(const LogParts& parts, double beta) {
  if (beta == 0.0 || parts.log_prior == kMinusInfinity) return parts.log_prior;
  return parts.log_prior + beta * parts.log_likelihood;
}

LogParts CountingEvaluator::operator()(const Eigen::VectorXd& x) {
  if (x.allFinite()) ++evaluations_;
  return checked(x);
}

std::vector<LogParts> CountingEvaluator::evaluate_all(const std::vector<Eigen::VectorXd>& points) {
  const auto count = static_cast<long>(points.size());
  std::vector<LogParts> parts(points.size());
  std::vector<std::exception_ptr> errors(points.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads_) if (threads_ > 1)
  for (long i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    try {
      parts[k] = checked(points[k]);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  }
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  for (const Eigen::VectorXd& x : points) evaluations_ += x.allFinite() ? 1 : 0;
  return parts;
}

LogParts CountingEvaluator::checked(const Eigen::VectorXd& x) const {
  if (!x.allFinite()) return {kMinusInfinity, kMinusInfinity};
  const LogParts parts = function_(x);
  for (const double value : {parts.log_prior, parts.log_likelihood}) {
    if (std::isnan(value) || value == std::numeric_limits<double>::infinity()) {
      std::ostringstream message;
      message << "the log density returned " << value << " at (" << x.transpose()
              << "); it must return a finite value, or -infinity outside the support";
      throw std::domain_error(message.str());
    }
  }
  return parts;
}

Ensemble start_ensemble(const std::vector<Eigen::VectorXd>& walkers, int expected_count, double beta,
                        CountingEvaluator& evaluate) {
  if (static_cast<int>(walkers.size()) != expected_count) {
    throw std::invalid_argument("got " + std::to_string(walkers.size()) + " start walkers for an ensemble of " +
                                std::to_string(expected_count) +
                                ": give that many (start_ball makes them) or set the walkers option to " +
                                std::to_string(walkers.size()));
  }
  Ensemble ensemble;
  for (std::size_t k = 0; k < walkers.size(); ++k) {
    if (walkers[k].size() != walkers.front().size() || !walkers[k].allFinite()) {
      throw std::invalid_argument("start walker " + std::to_string(k) +
                                  " has another dimension than walker 0 or a non-finite coordinate");
    }
    const LogParts parts = evaluate(walkers[k]);
    if (tempered_log_density(parts, beta) == kMinusInfinity) {
      throw std::invalid_argument("start walker " + std::to_string(k) +
                                  " is outside the support (log density -infinity): start every walker "
                                  "where the density is positive");
    }
    ensemble.positions.push_back(walkers[k]);
    ensemble.parts.push_back(parts);
  }
  ensemble.accepted.assign(walkers.size(), 0);
  check_spread(walkers);
  return ensemble;
}

void stretch_update(Ensemble& ensemble, double beta, double stretch, RandomStream& random,
                    CountingEvaluator& evaluate) {
  stretch_update_all({&ensemble}, {beta}, stretch, random, evaluate);
}

void stretch_update_all(const std::vector<Ensemble*>& ensembles, const std::vector<double>& betas, double stretch,
                        RandomStream& random, CountingEvaluator& evaluate) {
  update_all(ensembles, betas, MoveKind::Stretch, stretch, 0.0, random, evaluate);
}

void mixed_update(Ensemble& ensemble, double stretch, const MoveMix& moves, RandomStream& random,
                  CountingEvaluator& evaluate) {
  if (moves.differential_evolution == 0.0 && moves.snooker == 0.0) {
    stretch_update(ensemble, 1.0, stretch, random, evaluate);
    return;
  }
  const double pick = random.uniform() * (moves.stretch + moves.differential_evolution + moves.snooker);
  const MoveKind kind = pick < moves.stretch                                  ? MoveKind::Stretch
                        : pick < moves.stretch + moves.differential_evolution ? MoveKind::DifferentialEvolution
                                                                              : MoveKind::Snooker;
  double de_scale = 0.0;
  if (kind == MoveKind::DifferentialEvolution) {
    const auto dim = static_cast<double>(ensemble.positions.front().size());
    de_scale = random.uniform() < kDeFullJumpShare ? 1.0 : kDeScale / std::sqrt(2.0 * dim);
  }
  update_all({&ensemble}, {1.0}, kind, stretch, de_scale, random, evaluate);
}

void History::record(const Ensemble& ensemble, double beta) {
  for (std::size_t k = 0; k < ensemble.positions.size(); ++k) {
    const Eigen::VectorXd& x = ensemble.positions[k];
    positions_[k].insert(positions_[k].end(), x.data(), x.data() + x.size());
    log_density_[k].push_back(tempered_log_density(ensemble.parts[k], beta));
    log_likelihood_[k].push_back(ensemble.parts[k].log_likelihood);
  }
  ++steps_;
}

std::vector<Eigen::MatrixXd> History::chains(int first) const {
  std::vector<Eigen::MatrixXd> out;
  const Eigen::Index rows = steps_ - first;
  for (const std::vector<double>& walker : positions_) {
    out.emplace_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        walker.data() + first * dim_, rows, dim_));
  }
  return out;
}

namespace {
std::vector<Eigen::VectorXd> tail_rows(const std::vector<std::vector<double>>& series, int first, int steps) {
  std::vector<Eigen::VectorXd> out;
  for (const std::vector<double>& walker : series) {
    out.emplace_back(Eigen::Map<const Eigen::VectorXd>(walker.data() + first, steps - first));
  }
  return out;
}
}  // namespace

std::vector<Eigen::VectorXd> History::log_density(int first) const { return tail_rows(log_density_, first, steps_); }
std::vector<Eigen::VectorXd> History::log_likelihood(int first) const {
  return tail_rows(log_likelihood_, first, steps_);
}

void check_adaptive_options(int check_every, bool has_stop, int burn_in) {
  if (check_every < 0) {
    throw std::invalid_argument("check_every = " + std::to_string(check_every) +
                                ": use 0 (a fixed number of steps) or the updates between convergence checks");
  }
  if (check_every > 0 && !has_stop) {
    throw std::invalid_argument("check_every > 0 needs a stop test to ask");
  }
  if (check_every > 0 && burn_in != -1) {
    throw std::invalid_argument("burn_in = " + std::to_string(burn_in) +
                                " with an adaptive run length: the burn-in is then the first half of the run; "
                                "leave burn_in at -1");
  }
}

void check_moves(const MoveMix& moves, int walkers) {
  double total = 0.0;
  for (const double w : {moves.stretch, moves.differential_evolution, moves.snooker}) {
    if (!(w >= 0.0) || !std::isfinite(w)) {
      throw std::invalid_argument("move weights must be finite and >= 0 (stretch " + std::to_string(moves.stretch) +
                                  ", differential_evolution " + std::to_string(moves.differential_evolution) +
                                  ", snooker " + std::to_string(moves.snooker) + ")");
    }
    total += w;
  }
  if (!(total > 0.0)) throw std::invalid_argument("move weights are all 0: give at least one move a weight > 0");
  // Differential evolution picks 2 distinct walkers of the other half, the snooker 3.
  const int needed = moves.snooker > 0.0 ? 6 : moves.differential_evolution > 0.0 ? 4 : 2;
  if (walkers < needed) {
    throw std::invalid_argument("walkers = " + std::to_string(walkers) +
                                " with the differential-evolution moves: use at least " + std::to_string(needed) +
                                " walkers (their distinct picks come from the other half)");
  }
}

void check_run_options(int walkers, int dim, int steps, int burn_in, double stretch, int threads) {
  if (threads < 1) {
    throw std::invalid_argument("threads = " + std::to_string(threads) + ": use at least 1 thread");
  }
  if (dim < 1) throw std::invalid_argument("start walkers have no parameters: give at least one");
  if (walkers < 2 * dim || walkers % 2 != 0) {
    throw std::invalid_argument("walkers = " + std::to_string(walkers) + " for " + std::to_string(dim) +
                                " parameters: use an even number >= " + std::to_string(2 * dim) +
                                " (0 picks max(4 dim, 16))");
  }
  if (burn_in < 0 || steps <= burn_in) {
    throw std::invalid_argument("steps = " + std::to_string(steps) + " with burn_in = " + std::to_string(burn_in) +
                                ": steps must exceed the burn-in (>= 0; -1 picks steps / 2) so that some are kept");
  }
  if (!(stretch > 1.0) || !std::isfinite(stretch)) {
    throw std::invalid_argument("stretch = " + std::to_string(stretch) +
                                ": the stretch scale a must be finite and > 1 (GW10 and emcee use 2)");
  }
}

}  // namespace sedwave::sampling::detail
