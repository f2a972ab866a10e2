#include "sedwave/sampling/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <unsupported/Eigen/FFT>

#include "normal_quantile.hpp"

namespace sedwave::sampling {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_chains(const std::vector<Eigen::VectorXd>& chains, Eigen::Index min_length) {
  if (chains.empty()) throw std::invalid_argument("no chains to diagnose");
  for (const Eigen::VectorXd& chain : chains) {
    if (chain.size() != chains.front().size()) throw std::invalid_argument("chains differ in length");
  }
  if (chains.front().size() < min_length) {
    throw std::invalid_argument("chains of " + std::to_string(chains.front().size()) + " draws: need at least " +
                                std::to_string(min_length));
  }
}

// Each chain's first and last floor(n/2) draws as two chains (BDA3 section 11.4; V21 section 4.1
// drops the middle draw of an odd-length chain).
std::vector<Eigen::VectorXd> split_halves(const std::vector<Eigen::VectorXd>& chains) {
  std::vector<Eigen::VectorXd> halves;
  const Eigen::Index half = chains.front().size() / 2;
  for (const Eigen::VectorXd& chain : chains) {
    halves.emplace_back(chain.head(half));
    halves.emplace_back(chain.tail(half));
  }
  return halves;
}

// R-hat of chains taken as they are: BDA3 eqs. 11.1-11.4.
double rhat_of(const std::vector<Eigen::VectorXd>& chains) {
  const auto m = static_cast<double>(chains.size());
  const auto n = static_cast<double>(chains.front().size());
  Eigen::VectorXd means(chains.size());
  double within = 0.0;
  for (std::size_t j = 0; j < chains.size(); ++j) {
    means(static_cast<Eigen::Index>(j)) = chains[j].mean();
    within += (chains[j].array() - chains[j].mean()).square().sum() / (n - 1.0);
  }
  within /= m;
  const double between = n / (m - 1.0) * (means.array() - means.mean()).square().sum();
  if (within == 0.0) return between == 0.0 ? kNaN : std::numeric_limits<double>::infinity();
  const double pooled_variance = (n - 1.0) / n * within + between / n;
  return std::sqrt(pooled_variance / within);
}

// Ranks 1..S of all draws pooled (ties get their average rank), mapped to normal scores
// Phi^-1((r - 3/8) / (S + 1/4)) (Blom 1958; V21 eq. 14), back in the chains' shape.
std::vector<Eigen::VectorXd> rank_normalize(const std::vector<Eigen::VectorXd>& chains) {
  const Eigen::Index n = chains.front().size();
  const auto total = static_cast<Eigen::Index>(chains.size()) * n;
  std::vector<double> pooled(static_cast<std::size_t>(total));
  for (std::size_t j = 0; j < chains.size(); ++j) {
    std::copy(chains[j].begin(), chains[j].end(), pooled.begin() + static_cast<std::ptrdiff_t>(j) * n);
  }
  std::vector<std::size_t> order(pooled.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pooled[a] < pooled[b]; });
  std::vector<double> scores(pooled.size());
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first;
    while (last + 1 < order.size() && pooled[order[last + 1]] == pooled[order[first]]) ++last;
    const double rank = 0.5 * static_cast<double>(first + last) + 1.0;
    const double score = detail::normal_quantile((rank - 0.375) / (static_cast<double>(total) + 0.25));
    for (std::size_t i = first; i <= last; ++i) scores[order[i]] = score;
    first = last + 1;
  }
  std::vector<Eigen::VectorXd> normalized(chains.size(), Eigen::VectorXd(n));
  for (std::size_t j = 0; j < chains.size(); ++j) {
    std::copy_n(scores.begin() + static_cast<std::ptrdiff_t>(j) * n, n, normalized[j].begin());
  }
  return normalized;
}

double pooled_median(const std::vector<Eigen::VectorXd>& chains) {
  std::vector<double> pooled;
  for (const Eigen::VectorXd& chain : chains) pooled.insert(pooled.end(), chain.begin(), chain.end());
  const std::size_t middle = pooled.size() / 2;
  std::nth_element(pooled.begin(), pooled.begin() + static_cast<std::ptrdiff_t>(middle), pooled.end());
  const double upper = pooled[middle];
  if (pooled.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(pooled.begin(), pooled.begin() + static_cast<std::ptrdiff_t>(middle)));
}

// Normalised autocorrelation function rho(0..n-1) of one chain (biased autocovariance over its lag-0
// value) by the Wiener-Khinchin theorem: |FFT|^2 of the centred chain zero-padded to >= 2n (so the
// circular correlation equals the linear one), transformed back; O(n log n) as emcee's
// function_1d. Empty when the chain is constant.
Eigen::VectorXd autocorrelation_function(const Eigen::VectorXd& chain) {
  const auto n = static_cast<std::size_t>(chain.size());
  std::size_t padded_size = 1;
  while (padded_size < 2 * n) padded_size *= 2;
  std::vector<double> padded(padded_size, 0.0);
  const double mean = chain.mean();
  for (std::size_t i = 0; i < n; ++i) padded[i] = chain(static_cast<Eigen::Index>(i)) - mean;
  // One transform object per thread: it keeps the plan (twiddle factors) of each length it has
  // seen, which a fresh object computes again with a sine and cosine per point.
  thread_local Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, padded);
  for (std::complex<double>& value : spectrum) value = std::norm(value);
  std::vector<double> autocovariance;
  fft.inv(autocovariance, spectrum);
  if (!(autocovariance[0] > 0.0)) return {};
  Eigen::VectorXd rho(chain.size());
  for (std::size_t t = 0; t < n; ++t) rho(static_cast<Eigen::Index>(t)) = autocovariance[t] / autocovariance[0];
  return rho;
}

std::string format_number(double value, int precision = 3) {
  std::ostringstream text;
  text.precision(precision);
  text << value;
  return text.str();
}

}  // namespace

std::vector<Eigen::VectorXd> parameter_chains(const std::vector<Eigen::MatrixXd>& chains, int parameter) {
  std::vector<Eigen::VectorXd> columns;
  columns.reserve(chains.size());
  for (const Eigen::MatrixXd& chain : chains) columns.emplace_back(chain.col(parameter));
  return columns;
}

double split_rhat(const std::vector<Eigen::VectorXd>& chains) {
  check_chains(chains, 4);
  return rhat_of(split_halves(chains));
}

double rank_normalized_rhat(const std::vector<Eigen::VectorXd>& chains) {
  check_chains(chains, 4);
  const std::vector<Eigen::VectorXd> halves = split_halves(chains);
  const double bulk = rhat_of(rank_normalize(halves));
  const double median = pooled_median(halves);
  std::vector<Eigen::VectorXd> folded;
  for (const Eigen::VectorXd& half : halves) folded.emplace_back((half.array() - median).abs().matrix());
  const double tail = rhat_of(rank_normalize(folded));
  if (std::isnan(bulk) || std::isnan(tail)) return kNaN;
  return std::max(bulk, tail);
}

double autocorrelation_time(const std::vector<Eigen::VectorXd>& chains, double window_factor) {
  check_chains(chains, 2);
  Eigen::VectorXd mean_rho = Eigen::VectorXd::Zero(chains.front().size());
  int varying = 0;
  for (const Eigen::VectorXd& chain : chains) {
    const Eigen::VectorXd rho = autocorrelation_function(chain);
    if (rho.size() == 0) continue;
    mean_rho += rho;
    ++varying;
  }
  if (varying == 0) return kNaN;
  mean_rho /= varying;
  // Sokal's window: the first M >= c tau(M), tau(M) = 1 + 2 sum_{t=1..M} rho(t).
  double tau = 1.0;
  for (Eigen::Index lag = 1; lag < mean_rho.size(); ++lag) {
    tau += 2.0 * mean_rho(lag);
    if (static_cast<double>(lag) >= window_factor * tau) break;
  }
  return tau;
}

double initial_sequence_autocorrelation_time(const Eigen::VectorXd& series) {
  check_chains({series}, 2);
  const Eigen::VectorXd rho = autocorrelation_function(series);
  if (rho.size() == 0) return kNaN;
  double sum = 0.0;
  double previous = std::numeric_limits<double>::infinity();
  for (Eigen::Index lag = 0; lag + 1 < rho.size(); lag += 2) {
    const double pair = std::min(rho(lag) + rho(lag + 1), previous);
    if (!(pair > 0.0)) break;
    sum += pair;
    previous = pair;
  }
  return std::max(-1.0 + 2.0 * sum, 1.0 / std::log10(static_cast<double>(series.size())));
}

Diagnostics diagnose(const std::vector<Eigen::MatrixXd>& chains, double acceptance) {
  if (chains.empty()) throw std::invalid_argument("no chains to diagnose");
  const auto dim = static_cast<int>(chains.front().cols());
  Diagnostics diagnostics;
  diagnostics.acceptance = acceptance;
  diagnostics.kept_steps = static_cast<int>(chains.front().rows());
  diagnostics.walkers = static_cast<int>(chains.size());
  diagnostics.rhat.resize(dim);
  diagnostics.autocorrelation_time.resize(dim);
  diagnostics.ess.resize(dim);
  const double draws = static_cast<double>(diagnostics.kept_steps) * diagnostics.walkers;
  for (int i = 0; i < dim; ++i) {
    const std::vector<Eigen::VectorXd> columns = parameter_chains(chains, i);
    diagnostics.rhat(i) = rank_normalized_rhat(columns);
    diagnostics.autocorrelation_time(i) = autocorrelation_time(columns);
    diagnostics.ess(i) = draws / diagnostics.autocorrelation_time(i);
  }
  return diagnostics;
}

Diagnostics diagnose(const EnsembleRun& run) { return diagnose(run.chains, run.acceptance); }

Convergence assess_convergence(const Diagnostics& d, const ConvergenceCriteria& criteria) {
  Convergence verdict;
  verdict.converged = true;
  std::ostringstream advice;
  const double worst_tau = d.autocorrelation_time.maxCoeff();
  // Kept steps that would meet both the ESS and the steps-per-tau thresholds at the current tau.
  const double kept_needed =
      std::max(criteria.min_ess * worst_tau / d.walkers, criteria.min_steps_per_tau * worst_tau);
  for (Eigen::Index i = 0; i < d.rhat.size(); ++i) {
    const auto column = static_cast<std::size_t>(i);
    const std::string name = column < d.names.size() ? d.names[column] : "parameter " + std::to_string(i);
    if (!std::isfinite(d.rhat(i))) {
      // Too few kept draws per half-chain, or walkers that never moved: no between/within variance.
      verdict.converged = false;
      advice << name << ": R-hat cannot be computed from " << d.kept_steps
             << " kept steps (too few, or the walkers did not move): run more steps.\n";
    } else if (!(d.rhat(i) < criteria.max_rhat)) {
      verdict.converged = false;
      advice << name << ": R-hat across walkers " << format_number(d.rhat(i), 4) << " >= " << criteria.max_rhat
             << ": the walkers disagree. Run more steps (R-hat - 1 falls roughly as tau / steps); if some "
                "walkers stay apart however long the run, the posterior is multimodal: start every walker in "
                "one mode, or use parallel tempering.\n";
    }
    if (!(d.ess(i) >= criteria.min_ess)) {
      verdict.converged = false;
      advice << name << ": effective sample size " << format_number(d.ess(i)) << " < " << criteria.min_ess
             << ": run more steps or more walkers (ESS grows as kept steps x walkers / tau).\n";
    }
    if (!(d.kept_steps >= criteria.min_steps_per_tau * d.autocorrelation_time(i))) {
      verdict.converged = false;
      advice << name << ": " << d.kept_steps << " kept steps < " << criteria.min_steps_per_tau
             << " autocorrelation times (tau = " << format_number(d.autocorrelation_time(i))
             << "): tau itself is not yet reliable; run more steps.\n";
    }
  }
  if (!verdict.converged && std::isfinite(kept_needed)) {
    advice << "Got " << d.kept_steps << " kept steps; at the current tau at least "
           << static_cast<long>(std::ceil(kept_needed)) << " kept steps with " << d.walkers << " walkers (steps = "
           << static_cast<long>(std::ceil(2.0 * kept_needed))
           << " with the default burn-in of half) are needed, more if R-hat stays high.\n";
  }
  if (d.acceptance < criteria.min_acceptance) {
    advice << "Acceptance fraction " << format_number(d.acceptance) << " < " << criteria.min_acceptance
           << ": walkers may be stuck in a poor region or mode, or the posterior is a curved ridge; a smaller "
              "stretch scale (e.g. 1.5) accepts more, but judge a change by tau (the ESS per evaluation), not "
              "by the acceptance.\n";
  }
  if (verdict.converged) {
    advice << "converged: kept steps >= " << criteria.min_steps_per_tau << " tau and ESS >= " << criteria.min_ess
           << " for every " << (d.names.empty() ? "parameter" : "quantity") << ", walkers agree (R-hat < "
           << criteria.max_rhat << "; smallest ESS " << format_number(d.ess.minCoeff()) << ", largest tau " << format_number(worst_tau) << " steps).\n";
  }
  verdict.advice = advice.str();
  return verdict;
}

}  // namespace sedwave::sampling
