#include "sedwave/inversion/posterior.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "fit_problem.hpp"
#include "prior_control.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/io/column_file.hpp"
#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/summary.hpp"
#include "sedwave/sampling/tempering.hpp"

namespace sedwave::inversion {
namespace {

using detail::Setup;
using detail::Theta;

struct PriorQuantiles {
  double p16 = 0.0, p50 = 0.0, p84 = 0.0;  ///< in theta (ln units)
};

/// Quantiles of a prior in theta, by its CDF on a fine grid.
PriorQuantiles prior_quantiles(const Prior& p) {
  const double lo = std::log(p.lower), hi = std::log(p.upper);
  const int n = 4000;
  const double h = (hi - lo) / n;
  std::vector<double> cdf(n + 1, 0.0);
  for (int i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + std::exp(p.log_density_theta(lo + (i + 0.5) * h)) * h;
  const auto at = [&](double q) {
    const auto it = std::lower_bound(cdf.begin(), cdf.end(), q * cdf.back());
    return lo + h * static_cast<double>(it - cdf.begin());
  };
  return {at(0.16), at(0.5), at(0.84)};
}

/// Halvings of a start walker's distance to the best fit before it is given up.
constexpr int kStartHalvings = 40;

/// The walkers' start: a ball around the best fit, per parameter a tenth of its linearised sigma
/// where the fit determined it, else a tenth of the prior's 68 % width, kept inside the bounds.
/// For a tempered rung at beta < 1 the ball is 10 / sqrt(beta) times wider (at most the prior's
/// width): the width of L^beta where L is Gaussian, so the rung starts near its own distribution.
std::vector<Eigen::VectorXd> start_walkers(const Setup& s, const FitResult& best, const std::vector<Prior>& priors,
                                           const Theta& theta, const sampling::EnsembleOptions& options,
                                           const std::function<bool(const Eigen::VectorXd&)>& inside,
                                           double beta = 1.0) {
  const auto k = static_cast<Eigen::Index>(s.free.size());
  Eigen::VectorXd centre(k), spread(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const int i = s.free[static_cast<std::size_t>(j)];
    const ParameterResult& r = best.parameters[static_cast<std::size_t>(i)];
    const PriorQuantiles q = prior_quantiles(priors[static_cast<std::size_t>(i)]);
    const double prior_half_width = 0.5 * (q.p84 - q.p16);
    centre(j) = theta[i];
    const double scale = beta < 1.0 ? 1.0 / std::sqrt(beta) : 0.1;
    spread(j) = std::min(scale * (r.determined && r.log_sigma > 0.0 ? r.log_sigma : prior_half_width),
                         beta < 1.0 ? prior_half_width : 0.1 * prior_half_width);
  }
  std::vector<Eigen::VectorXd> walkers = sampling::start_ball(centre, spread, options);
  for (Eigen::VectorXd& w : walkers) {
    for (Eigen::Index j = 0; j < k; ++j) {
      const int i = s.free[static_cast<std::size_t>(j)];
      const double margin = 1e-9 * (detail::log_upper(s, i) - detail::log_lower(s, i));
      w(j) = std::clamp(w(j), detail::log_lower(s, i) + margin, detail::log_upper(s, i) - margin);
    }
    // Where the model has no value (a table's edge) or the prior none, pull the walker towards the
    // best fit, which has both, until it has them too.
    for (int halvings = 0; !inside(w) && halvings < kStartHalvings; ++halvings) w = centre + 0.5 * (w - centre);
    if (!inside(w)) {
      throw std::invalid_argument("the posterior has no density around the best fit (the model does not answer "
                                  "there, or the prior is zero): fix or bound the parameters that leave its range");
    }
  }
  return walkers;
}

/// Q(a, x) = Gamma(a, x) / Gamma(a), the regularised upper incomplete gamma function: a series below
/// x = a + 1, Legendre's continued fraction (modified Lentz) above (Abramowitz & Stegun 6.5.29,
/// 6.5.31).
double upper_incomplete_gamma(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefactor = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-16 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::max(0.0, 1.0 - std::exp(log_prefactor) * sum);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < tiny ? tiny : d;
    c = b + an / c;
    c = std::abs(c) < tiny ? tiny : c;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefactor) * h;
}

PosteriorQuantity summarize(const std::string& name, const std::string& unit, const Eigen::VectorXd& values,
                            double rhat, double ess) {
  const sampling::ParameterSummary m = sampling::summarize(values)[0];
  return {name, unit, m.median, m.central68.lower, m.central68.upper, m.central95.lower, m.central95.upper, rhat, ess,
          false, 0.0};
}

/// A 68 % profile-likelihood interval (FitResult): a missing end is open.
struct ProfileInterval {
  std::optional<double> lower, upper;
};

/// Marks a quantity whose posterior variance lies mostly along directions the data did not narrow,
/// or whose marginal spans most of its prior's, or whose credible interval the prior narrowed from
/// what the data alone allow (prior_control.hpp): `ln_values` its posterior draws in ln, `own` and
/// `prior_own` its posterior draws and its prior's in the prior's own coordinate, `profile` (where
/// the fit computed likelihood profiles) its profile interval.
void flag_prior_control(PosteriorQuantity& q, const detail::PriorControl& control, const Eigen::VectorXd& ln_values,
                        const Eigen::VectorXd& own, const Eigen::VectorXd& prior_own,
                        const std::optional<ProfileInterval>& profile) {
  q.prior_share = std::max(control.prior_share(ln_values), detail::prior_width_share(own, prior_own));
  if (profile) {
    q.prior_share = std::max(q.prior_share, detail::prior_share_against_profile(q.lower_68, q.upper_68,
                                                                                profile->lower, profile->upper));
  }
  q.prior_dominated = q.prior_share > detail::kPriorControlledShare;
}

/// The fit's profile interval of a parameter or derived quantity named `name`; nothing where the fit
/// computed no profiles.
std::optional<ProfileInterval> profile_of(const FitResult& best, const FitOptions& options, const std::string& name) {
  if (!options.profile_likelihood) return std::nullopt;
  for (const ParameterResult& p : best.parameters) {
    if (p.name == name) return ProfileInterval{p.profile_lower, p.profile_upper};
  }
  for (const DerivedResult& c : best.derived) {
    if (c.name == name) return ProfileInterval{c.profile_lower, c.profile_upper};
  }
  return std::nullopt;
}

/// The free ln-parameters of x placed into theta.
Theta with_free(const Setup& s, Theta theta, const Eigen::VectorXd& x) {
  for (Eigen::Index j = 0; j < x.size(); ++j) theta[s.free[static_cast<std::size_t>(j)]] = x(j);
  return theta;
}

void require_prior_covers(const Setup& s, const std::vector<Prior>& priors, const Theta& theta) {
  for (int i : s.free) {
    if (!std::isfinite(priors[static_cast<std::size_t>(i)].log_density_theta(theta[i]))) {
      throw std::invalid_argument("the prior of " + s.parameters.spec[i].name +
                                  " gives the best fit zero density: widen it, or start the fit inside it");
    }
  }
}

/// Independent draws of the free ln-parameters from their priors.
Eigen::VectorXd draw_free_from_priors(const Setup& s, const std::vector<Prior>& priors, sampling::RandomStream& random) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(s.free.size()));
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    x(j) = priors[static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])].draw_theta(random);
  }
  return x;
}

/// A value in its prior's own coordinate: ln for a log-uniform or log-normal prior, else the value.
double in_prior_coordinate(const Prior& prior, double ln_value) {
  return prior.kind == PriorKind::LogUniform || prior.kind == PriorKind::LogNormal ? ln_value : std::exp(ln_value);
}

/// Draws from the priors alone, for the width each quantity has without the data.
constexpr int kPriorWidthDraws = 4000;
constexpr std::uint64_t kPriorWidthStream = 0x9E3779B97F4A7C15ULL;

/// The priors' draws of every free parameter (in its prior's own coordinate) and of every
/// derived quantity (ln; draws where one is not a positive number are left out of its column).
struct PriorQuantities {
  Eigen::MatrixXd parameters;
  std::vector<Eigen::VectorXd> derived;
};

PriorQuantities prior_quantities(const Setup& s, const std::vector<Prior>& priors, const Theta& theta,
                                 std::size_t derived_count, unsigned seed) {
  sampling::RandomStream random(seed ^ kPriorWidthStream);
  const auto k = static_cast<Eigen::Index>(s.free.size());
  PriorQuantities out{Eigen::MatrixXd(kPriorWidthDraws, k), {}};
  std::vector<std::vector<double>> columns(derived_count);
  for (Eigen::Index r = 0; r < kPriorWidthDraws; ++r) {
    const Eigen::VectorXd x = draw_free_from_priors(s, priors, random);
    for (Eigen::Index j = 0; j < k; ++j) {
      out.parameters(r, j) = in_prior_coordinate(priors[static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])], x(j));
    }
    if (derived_count == 0) continue;
    try {
      const std::vector<double> derived = detail::derived_at(s, with_free(s, theta, x));
      for (std::size_t c = 0; c < derived_count; ++c) columns[c].push_back(std::log(derived[c]));
    } catch (const std::exception&) {
      // not a positive number at this corner of the priors: the draw is left out
    }
  }
  for (const std::vector<double>& column : columns) {
    out.derived.push_back(Eigen::Map<const Eigen::VectorXd>(column.data(), static_cast<Eigen::Index>(column.size())));
  }
  return out;
}

/// What sample_posterior ran, as its outputs name it.
std::string sampler_algorithm(const PosteriorResult& p) {
  if (p.temperatures > 0) {
    return "parallel tempering (Vousden, Farr & Mandel 2016), " + std::to_string(p.temperatures) +
           " rungs from beta = 1 to the prior (beta = 0, independent draws), stretch moves (Goodman & Weare 2010); "
           "the posterior is the beta = 1 rung's";
  }
  return "ensemble of walkers, differential-evolution moves (ter Braak 2006) 0.8 and snooker moves (ter Braak & "
         "Vrugt 2008) 0.2";
}

/// Prior draws, the pilot of the ladder and the hot rungs' start, from a stream of their own.
constexpr std::uint64_t kPriorStream = 0x5DEECE66DULL;
/// Prior draws that measure how far below the best fit the prior's likelihoods lie.
constexpr int kPilotDraws = 256;
/// Prior draws tried for one start walker of a hot rung before it starts at the best fit instead.
constexpr int kStartDraws = 1000;
/// A tempered run (the evidence's, or a posterior's) is not stopped before this many updates (the
/// first half, burn-in, lets every rung forget its start). The rungs started around the best fit
/// begin narrower than their own distribution (a Gaussian ball where L^beta has heavier tails) and
/// widen slowly: after 500
/// steps of burn-in EDFM's ln Z on a synthetic set was still too high by +0.031 +- 0.012 over 20
/// seeds against quadrature of the same integral, after 1000 it was not (-0.011 +- 0.008;
/// bench/evidence_accuracy.cpp), and Biot-Stoll's on the shipped field data scattered by 0.09
/// between seeds against a stated 0.05 (0.035 after 1000). A tempered posterior of the lattice chain
/// on the shipped field data with a log-normal grain-size prior (sd of ln 0.3), stopped by the test
/// alone after 250 steps, gave d's 95 % interval an upper end 7 % below the prior's, which the
/// data leave nearly unchanged; after 1000, 2000 and 4000 steps it was within 2 %.
constexpr int kMinTemperedSteps = 2000;
/// Seconds of silence before a sampling run reports its progress, and between its lines.
constexpr double kProgressSeconds = 2.0;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Updates a converging run still needs, from its diagnostics: a kept half of at least 50 tau and
/// an ESS of 400 for the slowest quantity (2 x kept, since the first half is burn-in).
double steps_needed(const sampling::Diagnostics& d, const sampling::ConvergenceCriteria& c = {}) {
  const double tau = d.autocorrelation_time.maxCoeff();
  return 2.0 * std::max(c.min_steps_per_tau * tau, c.min_ess * tau / d.walkers);
}

std::string formatted(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char line[256];
  std::snprintf(line, sizeof line, pattern, a, b, c, d);
  return line;
}

/// Reports a run's progress every kProgressSeconds once it has run that long.
class ProgressReporter {
 public:
  explicit ProgressReporter(std::function<void(const std::string&)> sink) : sink_(std::move(sink)) {}
  void operator()(int steps, int cap, double steps_wanted, const std::string& state) {
    const double elapsed = seconds_since(started_);
    if (!sink_ || elapsed < kProgressSeconds || elapsed - last_ < kProgressSeconds) return;
    last_ = elapsed;
    const double wanted = std::min(static_cast<double>(cap), std::max(steps_wanted, static_cast<double>(steps)));
    const double left = (wanted - steps) * elapsed / steps;
    sink_(formatted("%.0f of at most %.0f steps, %.0f s; ", steps, cap, elapsed) + state +
          formatted("; about %.0f steps and %.0f s to go", wanted - steps, left));
  }

 private:
  std::function<void(const std::string&)> sink_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  double last_ = 0.0;
};

/// The model's derived quantities along every walker's kept draws, each draw computed once: a check
/// of the stop test adds the draws made since the last one and drops those the burn-in has passed
/// (burn-in only grows, so a dropped draw is never kept again).
class DerivedChains {
 public:
  DerivedChains(const detail::Setup& s, const Theta& theta, std::size_t quantities)
      : s_(s), theta_(theta), quantities_(static_cast<Eigen::Index>(quantities)) {}

  /// Per walker: kept steps x derived quantities (values) of the run so far.
  std::vector<Eigen::MatrixXd> update(const sampling::EnsembleRun& run) {
    const std::size_t walkers = run.chains.size();
    if (cache_.size() != walkers) cache_.assign(walkers, {});
    const Eigen::Index kept = run.chains.empty() ? 0 : run.chains.front().rows();
    const long first_kept = static_cast<long>(run.steps) - static_cast<long>(kept);
    const long width = static_cast<long>(quantities_);
    std::vector<Eigen::MatrixXd> out(walkers);
    for (std::size_t w = 0; w < walkers; ++w) {
      std::vector<double>& rows = cache_[w];  // row-major, from step first_
      const long dropped = std::min<long>(std::max(first_kept - first_, 0L) * width, std::ssize(rows));
      rows.erase(rows.begin(), rows.begin() + dropped);
      for (long step = first_kept + std::ssize(rows) / std::max(width, 1L); step < run.steps && width > 0; ++step) {
        const std::vector<double> q = at(run.chains[w].row(static_cast<Eigen::Index>(step - first_kept)).transpose());
        rows.insert(rows.end(), q.begin(), q.end());
      }
      out[w] = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(rows.data(), kept,
                                                                                                      quantities_);
    }
    first_ = std::max(first_, first_kept);
    return out;
  }

 private:
  std::vector<double> at(const Eigen::VectorXd& free_ln_values) const {
    return detail::derived_at(s_, with_free(s_, theta_, free_ln_values));
  }
  const detail::Setup& s_;
  Theta theta_;
  Eigen::Index quantities_;
  long first_ = 0;  ///< the step of every walker's first cached row
  std::vector<std::vector<double>> cache_;
};

/// The derived quantities the stop test watches beside the parameters: those that move with a free
/// parameter at the best fit (one that does not is a constant column, which has no R-hat).
std::vector<std::size_t> varying_quantities(const detail::Setup& s, const std::vector<detail::DerivedFunction>& derived_functions,
                                            const Theta& theta) {
  std::vector<std::size_t> out;
  for (std::size_t c = 0; c < derived_functions.size(); ++c) {
    const Eigen::VectorXd gradient = derived_functions[c].log_value(s, theta).v;
    for (const int i : s.free) {
      if (gradient(i) != 0.0) {
        out.push_back(c);
        break;
      }
    }
  }
  return out;
}

/// Diagnostics of the parameters (ln values, columns 0..k-1) and of the derived quantities
/// (values, columns k..) together, walker by walker, each column named.
sampling::Diagnostics diagnose_together(const sampling::EnsembleRun& run, const std::vector<Eigen::MatrixXd>& derived,
                                        std::vector<std::string> names) {
  std::vector<Eigen::MatrixXd> chains(run.chains.size());
  for (std::size_t w = 0; w < chains.size(); ++w) {
    chains[w].resize(run.chains[w].rows(), run.chains[w].cols() + derived[w].cols());
    chains[w] << run.chains[w], derived[w];
  }
  sampling::Diagnostics d = sampling::diagnose(chains, run.acceptance);
  d.names = std::move(names);
  return d;
}

/// Those diagnostics restricted to the parameters (the first k columns) and the derived quantities
/// in `watched`: what the stop test and the verdict judge.
sampling::Diagnostics watched_columns(const sampling::Diagnostics& d, std::size_t k,
                                      const std::vector<std::size_t>& watched) {
  std::vector<Eigen::Index> columns;
  for (std::size_t j = 0; j < k; ++j) columns.push_back(static_cast<Eigen::Index>(j));
  for (const std::size_t c : watched) columns.push_back(static_cast<Eigen::Index>(k + c));
  sampling::Diagnostics out = d;
  out.rhat = d.rhat(columns);
  out.autocorrelation_time = d.autocorrelation_time(columns);
  out.ess = d.ess(columns);
  out.names.clear();
  for (const Eigen::Index j : columns) out.names.push_back(d.names[static_cast<std::size_t>(j)]);
  return out;
}

/// The sampler's options that PosteriorOptions and EvidenceOptions share.
template <class Options>
sampling::EnsembleOptions ensemble_options(const Options& options) {
  sampling::EnsembleOptions ensemble;
  ensemble.walkers = options.walkers;
  ensemble.steps = options.steps;
  ensemble.seed = options.seed;
  ensemble.threads = options.threads;
  ensemble.check_every = options.check_every;
  return ensemble;
}

/// A tempering ladder and its start walkers for `density`: `temperatures` rungs evenly spaced in
/// ln beta from 1 down to 1/max_temperature, then beta = 0 (the prior, refreshed by independent
/// draws). The ladder reaches further where the prior's typical draws have ln L below the best fit's
/// by more than max_temperature, with the same number of rungs per decade: down to where they are
/// within e^1 of the best fit in L^beta_min, so that the last stone, prior draws weighted by
/// L^beta_min, has no dominant few. Rungs where the best fit is not yet e^dim likelier than a
/// typical prior draw start from prior draws; colder ones around the best fit, as wide as L^beta
/// there.
struct TemperedStart {
  sampling::TemperingOptions tempering;  ///< betas and ensemble set
  std::vector<std::vector<Eigen::VectorXd>> starts;
  double max_temperature = 0.0;
};

TemperedStart tempered_start(const Setup& s, const FitResult& best, const std::vector<Prior>& priors, const Theta& theta,
                             const sampling::PriorAndLikelihood& density, int temperatures, double max_temperature,
                             const sampling::EnsembleOptions& ensemble) {
  const auto k = static_cast<Eigen::Index>(s.free.size());
  sampling::RandomStream prior_random(ensemble.seed ^ kPriorStream);
  std::vector<double> pilot;
  for (int i = 0; i < kPilotDraws; ++i) pilot.push_back(density.log_likelihood(density.draw_prior(prior_random)));
  std::nth_element(pilot.begin(), pilot.begin() + kPilotDraws / 2, pilot.end());
  const double best_log_l = -0.5 * detail::chi2_at(s, theta);
  const double gap = std::isfinite(pilot[kPilotDraws / 2]) ? best_log_l - pilot[kPilotDraws / 2]
                                                             : std::numeric_limits<double>::infinity();
  TemperedStart out;
  out.max_temperature = max_temperature;
  int rungs = temperatures;
  if (gap > max_temperature) {
    out.max_temperature = std::isfinite(gap) ? gap : 1e3 * max_temperature;
    rungs = static_cast<int>(std::ceil((temperatures - 1) * std::log(out.max_temperature) / std::log(max_temperature))) + 1;
  }
  out.tempering.betas = sampling::evidence_ladder(rungs, out.max_temperature);
  out.tempering.ensemble = ensemble;
  const auto inside = [&](const Eigen::VectorXd& x) {
    return std::isfinite(density.log_prior(x)) && std::isfinite(density.log_likelihood(x));
  };
  for (const double beta : out.tempering.betas) {
    const std::vector<Eigen::VectorXd> ball = start_walkers(s, best, priors, theta, ensemble, inside, beta);
    if (beta * gap >= static_cast<double>(k)) {
      out.starts.push_back(ball);
      continue;
    }
    std::vector<Eigen::VectorXd> walkers;
    for (const Eigen::VectorXd& fallback : ball) {
      Eigen::VectorXd x = density.draw_prior(prior_random);
      for (int tries = 1; beta > 0.0 && !std::isfinite(density.log_likelihood(x)); ++tries) {
        x = tries < kStartDraws ? density.draw_prior(prior_random) : fallback;
      }
      walkers.push_back(x);
    }
    out.starts.push_back(walkers);
  }
  return out;
}

/// The curvature of -ln prior(theta) at theta, as the linearisation sees it: 1/sd^2 for a log-normal
/// prior, (value/sd)^2 for a normal one at its mean, 0 for the flat ones.
double prior_curvature(const Prior& p, double theta) {
  if (p.kind == PriorKind::LogNormal) return 1.0 / (p.b * p.b);
  if (p.kind == PriorKind::Normal) return std::pow(std::exp(theta) / p.b, 2);
  return 0.0;
}

/// The linearised posterior's precision in the free ln-parameters at theta: the data's J^T J plus
/// each prior's curvature, the smallest over `prior_sets` (the widest posterior of them).
Eigen::MatrixXd linearised_precision(const Setup& s, const Theta& theta, const std::vector<std::vector<Prior>>& prior_sets) {
  const Eigen::MatrixXd jacobian = detail::whitened_jacobian(s, theta);
  Eigen::MatrixXd precision = jacobian.transpose() * jacobian;
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const int i = s.free[j];
    double curvature = std::numeric_limits<double>::infinity();
    for (const std::vector<Prior>& priors : prior_sets) {
      curvature = std::min(curvature, prior_curvature(priors[static_cast<std::size_t>(i)], theta[i]));
    }
    precision(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)) += curvature;
  }
  return precision;
}

/// Whether a free parameter with a flat prior (uniform or log-uniform, the default) is left open by
/// the data and the other priors together: its sd in ln, in the linearised posterior at the best
/// fit, above determined_log_sigma (FitOptions: what the fit calls NOT DETERMINED). The linearised
/// posterior's precision is the data's J^T J plus the priors' curvature in ln(value): 1/sd^2 for a
/// log-normal prior, (value/sd)^2 for a normal one at its mean, 0 for the flat ones. Such a
/// parameter's posterior is closed by nothing but the data, and where they leave it open, by the
/// search bounds.
bool open_to_the_bounds(const Setup& s, const Theta& theta, const std::vector<Prior>& priors,
                        double determined_log_sigma) {
  const Eigen::MatrixXd precision = linearised_precision(s, theta, {priors});
  std::vector<bool> flat(s.free.size());
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const Prior& p = priors[static_cast<std::size_t>(s.free[j])];
    flat[j] = p.kind == PriorKind::Uniform || p.kind == PriorKind::LogUniform;
  }
  // Variances from the eigen-decomposition, a direction that nothing sees (an eigenvalue at
  // rounding level of the largest) counting as unbounded.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(precision);
  const Eigen::VectorXd lambda = eigen.eigenvalues().cwiseMax(1e-14 * eigen.eigenvalues().cwiseAbs().maxCoeff());
  const Eigen::VectorXd variance = eigen.eigenvectors().cwiseAbs2() * lambda.cwiseInverse();
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const double sd = std::sqrt(variance(static_cast<Eigen::Index>(j)));
    if (flat[j] && !(sd <= determined_log_sigma)) return true;
  }
  return false;
}

/// Updates per walker that a run so far kept (its burn-in dropped).
double kept_steps(const sampling::EnsembleRun& run) {
  return run.chains.empty() ? 0.0 : static_cast<double>(run.chains.front().rows());
}

/// The largest integrated autocorrelation time [steps] over every rung's k parameters and ln L: a
/// tempered run has mixed only when each rung has (walkers that creep along a ridge leave ln L
/// nearly unchanged, yet what the rung hands down still depends on where they started).
double slowest_rung_tau(const sampling::TemperedRun& run, Eigen::Index k) {
  double slowest = 0.0;
  for (std::size_t t = 0; t < run.levels.size(); ++t) {
    std::vector<double> taus{sampling::autocorrelation_time(run.log_likelihood[t])};
    for (int i = 0; i < static_cast<int>(k); ++i) {
      taus.push_back(sampling::autocorrelation_time(sampling::parameter_chains(run.levels[t].chains, i)));
    }
    for (const double tau : taus) {
      if (std::isfinite(tau)) slowest = std::max(slowest, tau);
    }
  }
  return slowest;
}

}  // namespace

sampling::PriorAndLikelihood evidence_integrand(const ObservationSet& data, const sediment::SedimentModel& model,
                                               const FitResult& best, const std::vector<Prior>& priors,
                                               const FitOptions& fit_options) {
  const auto s = std::make_shared<const Setup>(detail::make_setup(data, model, best.fitted, fit_options));
  const auto shared_priors = std::make_shared<const std::vector<Prior>>(priors);
  const Theta theta = best.fitted.log_values();
  require_prior_covers(*s, priors, theta);
  return {[s, shared_priors, theta](const Eigen::VectorXd& x) {
            return log_prior(s->parameters, *shared_priors, with_free(*s, theta, x));
          },
          [s, theta](const Eigen::VectorXd& x) {
            const double chi2 = detail::chi2_at(*s, with_free(*s, theta, x));
            return std::isfinite(chi2) ? -0.5 * chi2 : -std::numeric_limits<double>::infinity();
          },
          [s, shared_priors](sampling::RandomStream& random) { return draw_free_from_priors(*s, *shared_priors, random); }};
}

namespace {

/// The evidence by parallel tempering and stepping stones (EvidenceOptions).
ModelEvidence tempered_evidence(const ObservationSet& data, const sediment::SedimentModel& model, const FitResult& best,
                                const std::vector<Prior>& priors, const FitOptions& fit_options,
                                const EvidenceOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const Setup s = detail::make_setup(data, model, best.fitted, fit_options);
  const Theta theta = best.fitted.log_values();
  const auto k = static_cast<Eigen::Index>(s.free.size());
  require_prior_covers(s, priors, theta);
  const sampling::PriorAndLikelihood density = evidence_integrand(data, model, best, priors, fit_options);
  const sampling::EnsembleOptions ensemble = ensemble_options(options);
  TemperedStart ladder =
      tempered_start(s, best, priors, theta, density, options.temperatures, options.max_temperature, ensemble);
  sampling::TemperingOptions& tempering = ladder.tempering;
  // The ladder adapts during the first half of the burn-in at most (sample_tempered's rule), and the
  // burn-in is half of the run: a quarter of the cap.
  tempering.adapt_steps = std::min(options.adapt_steps, options.steps / 4);

  ProgressReporter report(options.progress);
  sampling::Evidence evidence;
  sampling::Convergence convergence;
  const auto judge = [&](const sampling::TemperedRun& run) {
    evidence = sampling::thermodynamic_evidence(run);
    const sampling::Diagnostics d = sampling::diagnose(run.levels[0]);
    convergence = sampling::assess_convergence(d);
    const double kept = run.steps - sampling::burn_in_steps(tempering.ensemble, run.steps);
    // Every rung must have mixed, not only the posterior's, and the ladder's series too.
    const double slowest = std::max(evidence.autocorrelation_time, slowest_rung_tau(run, k));
    const double per_tau = sampling::ConvergenceCriteria{}.min_steps_per_tau;
    const bool error_ok = evidence.uncertainty <= options.target_uncertainty && kept >= per_tau * slowest;
    const double wanted = std::max({steps_needed(d), run.steps * std::pow(evidence.uncertainty / options.target_uncertainty, 2),
                                    2.0 * per_tau * slowest});
    report(run.steps, options.steps, wanted,
           formatted("ln Z %.2f +- %.2f (target %.2f)", evidence.log_evidence, evidence.uncertainty,
                     options.target_uncertainty));
    return error_ok && convergence.converged && run.steps >= kMinTemperedSteps;
  };
  tempering.stop = judge;
  const sampling::TemperedRun run = sampling::sample_tempered(density, ladder.starts, tempering);
  const bool done = judge(run);
  // Posterior-predictive p of chi^2: replicated data at a draw theta have chi^2 ~ chi^2_n exactly
  // (Gaussian whitened residuals), so p = mean over draws of Q(n/2, chi^2(theta)/2).
  const double n = static_cast<double>(s.observations.size());
  double p_sum = 0.0;
  int draws = 0;
  for (const Eigen::VectorXd& walker_log_l : run.log_likelihood[0]) {
    for (Eigen::Index r = 0; r < walker_log_l.size(); ++r) {
      p_sum += upper_incomplete_gamma(0.5 * n, -walker_log_l(r));
      ++draws;
    }
  }
  ModelEvidence e;
  e.log_evidence = evidence.log_evidence;
  e.uncertainty = evidence.uncertainty;
  e.thermodynamic_integration = evidence.thermodynamic_integration;
  e.stone_overlap = evidence.stone_overlap;
  e.temperatures = static_cast<int>(tempering.betas.size());
  e.swap_acceptance.assign(run.swap_acceptance.data(), run.swap_acceptance.data() + run.swap_acceptance.size());
  e.max_temperature = ladder.max_temperature;
  e.steps = run.steps;
  e.predictive_p = draws > 0 ? p_sum / draws : 0.0;
  e.acceptance = run.levels[0].acceptance;
  e.converged = done;
  if (!done) {
    e.advice = formatted("stopped at the cap of %.0f steps per temperature with ln Z +- %.3f (target %.3f)",
                         run.steps, evidence.uncertainty, options.target_uncertainty) +
               (convergence.converged ? std::string(" and a converged posterior ensemble")
                                      : "; the posterior ensemble: " + convergence.advice);
  } else {
    e.advice = convergence.advice;
  }
  e.evaluations = run.evaluations + kPilotDraws;
  e.samples = sampling::pooled_samples(run.levels[0].chains).array().exp().matrix();
  e.wall_seconds = seconds_since(started);
  e.method = kTemperingMethod;
  return e;
}

}  // namespace

ModelEvidence model_evidence(const ObservationSet& data, const sediment::SedimentModel& model, const FitResult& best,
                             const std::vector<Prior>& priors, const FitOptions& fit_options,
                             const EvidenceOptions& options) {
  if (options.method == EvidenceMethod::Tempering) return tempered_evidence(data, model, best, priors, fit_options, options);
  ModelEvidence fast;
  fast.fallback_reason = "adaptive cubature asked for";
  if (options.method != EvidenceMethod::Cubature) {
    fast = importance_sampled_evidence(data, model, best, {priors}, fit_options, options).front();
  }
  if (fast.fallback_reason.empty()) return fast;
  std::string reason = fast.fallback_reason;
  int evaluations = fast.evaluations;
  double seconds = fast.wall_seconds;
  if (std::ssize(best.fitted.free_indices()) <= options.cubature_max_parameters) {
    ModelEvidence integrated = cubature_integrated_evidence(data, model, best, {priors}, fit_options, options,
                                                            {fast.samples}).front();
    integrated.evaluations += evaluations;
    integrated.wall_seconds += seconds;
    if (integrated.fallback_reason.empty()) {
      integrated.fallback_reason = reason;
      return integrated;
    }
    reason += "; " + integrated.fallback_reason;
    evaluations = integrated.evaluations;
    seconds = integrated.wall_seconds;
  }
  ModelEvidence e = tempered_evidence(data, model, best, priors, fit_options, options);
  e.fallback_reason = reason;
  e.evaluations += evaluations;
  e.wall_seconds += seconds;
  return e;
}

namespace {

/// What importance sampling's diagnostics allow (docs/sampling.md, "The evidence from the fit").
/// A best fit with chi^2 above this the models do not describe the data at all (ln L <= -500;
/// there the linearised posterior, which neglects the residuals times their curvature, is no guide).
constexpr double kHopelessChi2 = 1000.0;
/// A linearised posterior sd (in ln) above this share of a prior's range: a ridge or plateau that
/// the prior, not the data, closes.
constexpr double kRidgeShareOfRange = 0.25;
constexpr double kMaxParetoK = 0.7;       ///< Vehtari et al. 2024: above it the estimate is unreliable
constexpr double kMaxFarMass = 0.01;      ///< posterior mass beyond sampling::kFarDistance sd
/// The smallest kurtosis along a principal axis accepted (a Gaussian 3, a flat plateau 1.8, two
/// separated modes of similar weight towards 1).
constexpr double kMinAxisKurtosis = 2.0;
/// A posterior presses against a bound when more than kBoundMass of it lies within kBoundStrip of
/// its sd from the bound (a Gaussian cut 3 sd out has 0.5 % there, one cut at 2 sd 4.4 %, a plateau
/// that the bound cuts about 14 %).
constexpr double kBoundStrip = 0.5;
constexpr double kBoundMass = 0.02;
constexpr double kMaxStatedError = 0.05;  ///< the largest standard error of ln Z accepted
/// A defensive slab serves a posterior that strays from the linearised peak along its axis only:
/// across it the posterior's sd may exceed the linearised one by at most this factor.
constexpr double kMaxAcrossSpread = 2.0;
/// The resampled posterior draws' own stream.
constexpr std::uint64_t kResampleStream = 0x9E3779B97F4A7C15ULL;

/// From importance-weighted draws (ln-parameters, normalised ln weights): the predictive p (the
/// weighted chance of a chi^2 above each draw's) and the posterior draws [SI], resampled.
void finish_from_weighted_draws(ModelEvidence& e, const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_likelihood,
                                const Eigen::VectorXd& log_weights, double n, const EvidenceOptions& options) {
  double p_sum = 0.0;
  for (Eigen::Index i = 0; i < draws.rows(); ++i) {
    if (std::isfinite(log_weights(i))) p_sum += std::exp(log_weights(i)) * upper_incomplete_gamma(0.5 * n, -log_likelihood(i));
  }
  e.predictive_p = p_sum;
  if (std::isfinite(log_weights.maxCoeff())) {
    sampling::RandomStream random(options.seed ^ kResampleStream);
    e.samples = sampling::resample(draws, log_weights, options.posterior_draws, random).array().exp().matrix();
  }
}

/// Why the linearisation at the fit cannot centre the proposal for these priors ("" where it can).
std::string linearisation_refusal(const Setup& s, const FitResult& best, const Eigen::MatrixXd& precision,
                                  const std::vector<Prior>& priors) {
  if (best.chi2 > kHopelessChi2) {
    return formatted("the best fit's chi^2 is %.3g (above %.0f): the model does not describe the data", best.chi2,
                     kHopelessChi2);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(precision);
  if (!(eigen.eigenvalues().minCoeff() > 1e-14 * eigen.eigenvalues().cwiseAbs().maxCoeff())) {
    return "the data and priors leave a direction unseen at the best fit (a ridge)";
  }
  const Eigen::VectorXd sd = precision.inverse().diagonal().cwiseSqrt();
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const int i = s.free[j];
    const auto [lo, hi] = priors[static_cast<std::size_t>(i)].support();
    if (!(sd(static_cast<Eigen::Index>(j)) <= kRidgeShareOfRange * std::log(hi / lo))) {
      return "the linearised posterior's sd of ln " + s.parameters.spec[i].name +
             formatted(" is %.2f, over a quarter of its prior's range %.2f (a ridge or plateau the prior closes)",
                       sd(static_cast<Eigen::Index>(j)), std::log(hi / lo));
    }
  }
  return "";
}

/// A second mode counts where the Laplace approximation gives it at least this share of the
/// posterior (missing it would bias ln Z by about as much).
constexpr double kMinModeShare = 1e-3;

/// A mode of the posterior at a local minimum of chi^2 that the fit found (the fit itself or one of
/// FitResult::other_minima), with its linearised precision in the free ln-parameters (empty: no
/// Jacobian there) and its share of the posterior by the Laplace approximation, L pi (2 pi)^(k/2)
/// det(precision)^(-1/2) over the sum of the modes' (a direction unseen there: share 1).
struct FitMode {
  Theta theta;
  Eigen::MatrixXd precision;
  double share = 1.0;
};

/// The fit's modes inside the priors' support (the fit first), each with its share under the
/// widest of `prior_sets`.
std::vector<FitMode> fit_modes(const Setup& s, const FitResult& best, const std::vector<std::vector<Prior>>& prior_sets) {
  std::vector<std::pair<Theta, double>> minima{{best.fitted.log_values(), best.chi2}};
  for (const LocalMinimum& m : best.other_minima) {
    Theta theta;
    for (const double v : m.values) theta.push_back(std::log(v));
    minima.emplace_back(theta, m.chi2);
  }
  std::vector<FitMode> modes;
  std::vector<double> log_mass;
  for (const auto& [theta, chi2] : minima) {
    double lp = -std::numeric_limits<double>::infinity();
    for (const std::vector<Prior>& priors : prior_sets) lp = std::max(lp, log_prior(s.parameters, priors, theta));
    if (!std::isfinite(lp)) continue;
    FitMode mode{theta, {}, 1.0};
    double log_volume = std::numeric_limits<double>::infinity();
    try {
      mode.precision = linearised_precision(s, theta, prior_sets);
      const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mode.precision).eigenvalues();
      if (lambda.minCoeff() > 1e-14 * lambda.cwiseAbs().maxCoeff()) log_volume = -0.5 * lambda.array().log().sum();
    } catch (const std::runtime_error&) {
      mode.precision.resize(0, 0);
    }
    modes.push_back(std::move(mode));
    log_mass.push_back(-0.5 * chi2 + lp + log_volume);
  }
  const double top = *std::max_element(log_mass.begin(), log_mass.end());
  double sum = 0.0;
  for (const double m : log_mass) sum += std::isinf(top) ? (m == top) : std::exp(m - top);
  for (std::size_t j = 0; j < modes.size(); ++j) {
    modes[j].share = (std::isinf(top) ? (log_mass[j] == top) : std::exp(log_mass[j] - top)) / sum;
  }
  return modes;
}

/// Why a proposal around the fit alone misses posterior mass ("" where it does not): the fit found
/// another local minimum with a share of the posterior of kMinModeShare or more.
std::string other_mode_refusal(const Setup& s, const FitResult& best, const std::vector<Prior>& priors) {
  const std::vector<FitMode> modes = fit_modes(s, best, {priors});
  for (std::size_t j = 1; j < modes.size(); ++j) {
    if (modes[j].share < kMinModeShare) continue;
    std::string at;
    for (const int i : s.free) {
      at += (at.empty() ? "" : ", ") + s.parameters.spec[i].name +
            formatted(" %.3g", std::exp(modes[j].theta[static_cast<std::size_t>(i)]));
    }
    return "the fit found another local minimum of chi^2 (at " + at +
           formatted("), a second mode with %.1f %% of the posterior by the Laplace approximation", 100.0 * modes[j].share);
  }
  return "";
}

/// Why the stated error is too large to accept ("" where it is not).
std::string error_refusal(const sampling::ImportanceEstimate& e) {
  if (e.uncertainty <= kMaxStatedError) return "";
  return formatted("the standard error of ln Z reached only %.3f (at most %.2f accepted)", e.uncertainty, kMaxStatedError);
}

/// Why the weighted draws of one prior set cannot be trusted ("" where they can).
std::string importance_refusal(const Setup& s, const FitResult& best, const sampling::ImportanceRun& run,
                               const sampling::ImportanceEstimate& e, const std::vector<Prior>& priors) {
  if (!(e.pareto_k <= kMaxParetoK)) return formatted("Pareto k-hat of the importance weights %.2f (above 0.7)", e.pareto_k);
  if (e.far_mass > kMaxFarMass) {
    return formatted("%.1f %% of the posterior lies beyond %.0f sd of its mean (a far tail or another mode)",
                     100.0 * e.far_mass, sampling::kFarDistance);
  }
  // A defensive slab bounds the weights inside it, but a posterior broad across it, or going on past
  // its ends, can still hide mass from every diagnostic of the weights.
  if (e.slab_across_spread > kMaxAcrossSpread) {
    return formatted("the posterior's sd across the defensive slab is %.1f times the linearised one (more than "
                     "one direction strays from the fit's peak)", e.slab_across_spread);
  }
  if (e.slab_end_mass > kMaxFarMass) {
    return formatted("%.1f %% of the posterior lies at an end of the defensive slab (it goes on past where the "
                     "pilots looked)", 100.0 * e.slab_end_mass);
  }
  if (e.min_axis_kurtosis < kMinAxisKurtosis) {
    return formatted("the posterior's kurtosis along a principal axis is %.2f (a single peak has about 3): several "
                     "modes or a plateau", e.min_axis_kurtosis);
  }
  for (std::size_t j = 0; j < s.free.size(); ++j) {
    const int i = s.free[j];
    const auto jj = static_cast<Eigen::Index>(j);
    const auto [lo, hi] = priors[static_cast<std::size_t>(i)].support();
    const double strip = kBoundStrip * std::sqrt(e.covariance(jj, jj));
    double near_bound = 0.0;
    for (Eigen::Index r = 0; r < run.draws.rows(); ++r) {
      const double x = run.draws(r, jj);
      if (std::isfinite(e.log_weights(r)) && (x < std::log(lo) + strip || x > std::log(hi) - strip)) {
        near_bound += std::exp(e.log_weights(r));
      }
    }
    if (best.parameters[static_cast<std::size_t>(i)].at_bound || near_bound > kBoundMass) {
      return "the posterior of " + s.parameters.spec[i].name +
             formatted(" presses against a bound of its prior (%.1f %% of it within %.1f sd of the bound", 100.0 * near_bound,
                       kBoundStrip) +
             (best.parameters[static_cast<std::size_t>(i)].at_bound ? "; the best fit is at a bound)" : ")");
    }
  }
  return error_refusal(e);
}

}  // namespace

std::vector<ModelEvidence> importance_sampled_evidence(const ObservationSet& data, const sediment::SedimentModel& model,
                                                       const FitResult& best,
                                                       const std::vector<std::vector<Prior>>& prior_sets,
                                                       const FitOptions& fit_options, const EvidenceOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  if (prior_sets.empty()) throw std::invalid_argument("importance_sampled_evidence: no priors");
  const Setup s = detail::make_setup(data, model, best.fitted, fit_options);
  const Theta theta = best.fitted.log_values();
  const auto k = static_cast<Eigen::Index>(s.free.size());
  std::vector<ModelEvidence> out(prior_sets.size());
  std::vector<sampling::LogDensity> log_priors;
  std::vector<std::size_t> sampled;  // the sets the proposal serves
  std::vector<sampling::Support> supports;  // theirs, in the free ln-parameters
  // Without derivatives at the best fit there is no linearisation to build the proposal from.
  Eigen::MatrixXd precision;
  std::string no_jacobian;
  try {
    precision = linearised_precision(s, theta, prior_sets);
  } catch (const std::runtime_error& e) {
    no_jacobian = std::string("no linearisation at the best fit: ") + e.what();
  }
  sampling::LogDensity log_likelihood;
  for (std::size_t p = 0; p < prior_sets.size(); ++p) {
    const sampling::PriorAndLikelihood density = evidence_integrand(data, model, best, prior_sets[p], fit_options);
    log_likelihood = density.log_likelihood;
    out[p].fallback_reason =
        no_jacobian.empty() ? linearisation_refusal(s, best, precision, prior_sets[p]) : no_jacobian;
    if (out[p].fallback_reason.empty()) out[p].fallback_reason = other_mode_refusal(s, best, prior_sets[p]);
    out[p].method = kImportanceSamplingMethod;
    if (!out[p].fallback_reason.empty()) continue;
    log_priors.push_back(density.log_prior);
    sampled.push_back(p);
    sampling::Support support{Eigen::VectorXd(k), Eigen::VectorXd(k)};
    for (Eigen::Index j = 0; j < k; ++j) {
      const auto [lo, hi] = prior_sets[p][static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])].support();
      support.lower(j) = std::log(lo);
      support.upper(j) = std::log(hi);
    }
    supports.push_back(support);
  }
  if (sampled.empty()) return out;
  Eigen::VectorXd centre(k);
  for (Eigen::Index j = 0; j < k; ++j) centre(j) = theta[static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])];
  sampling::ImportanceOptions importance = options.importance;
  importance.seed = options.seed;
  importance.threads = options.threads;
  importance.supports = supports;
  const sampling::ImportanceRun run =
      sampling::importance_evidence(log_likelihood, log_priors, centre, precision.inverse(), importance);
  const double n = static_cast<double>(s.observations.size());
  for (std::size_t q = 0; q < sampled.size(); ++q) {
    const sampling::ImportanceEstimate& w = run.priors[q];
    ModelEvidence& e = out[sampled[q]];
    e.log_evidence = w.log_evidence;
    e.uncertainty = w.uncertainty;
    e.pareto_k = w.pareto_k;
    e.effective_draws = w.effective_draws;
    e.evaluations = run.evaluations;
    e.fallback_reason = importance_refusal(s, best, run, w, prior_sets[sampled[q]]);
    e.converged = e.fallback_reason.empty();
    e.advice = formatted("%.0f draws from a mixture of %.0f t distributions and %.0f defensive slabs",
                         static_cast<double>(run.draws.rows()), run.components - run.slabs, run.slabs) +
               (w.slab_axis >= 0 ? " (one along " + s.parameters.spec[s.free[static_cast<std::size_t>(w.slab_axis)]].name +
                                       formatted("; across it %.2f linearised sd", w.slab_across_spread) + ")"
                : w.slab_axis == sampling::kSlabAlongCombination ? std::string(" (one along a combination of parameters)")
                                                                 : std::string()) +
               formatted(", Pareto k-hat %.2f, %.0f effective draws", w.pareto_k, w.effective_draws);
    finish_from_weighted_draws(e, run.draws, run.log_likelihood, w.log_weights, n, options);
  }
  const double seconds = seconds_since(started);
  for (ModelEvidence& e : out) e.wall_seconds = seconds;
  return out;
}

namespace {

/// The cubature's map of one axis (docs/sampling.md, "Adaptive cubature").
/// Nodes per part of the map's piecewise-linear density.
constexpr int kMapNodes = 256;
/// The share of the map's density spread uniformly over the support, so that L pi / g is bounded
/// wherever the posterior is that the other parts did not foresee.
constexpr double kUniformShare = 0.2;
/// The t around the best fit: its scale in linearised sd, its reach in its own scales.
constexpr double kMapTScale = 2.0;
constexpr double kMapTReach = 40.0;
/// Hint draws used for the kernel density (every n-th where there are more).
constexpr int kMaxHintDraws = 1000;
/// The cubature's draws' own streams (its map's pilot, its map's final draws).
constexpr std::uint64_t kCubaturePilotStream = 0x2545F4914F6CDD1DULL;
constexpr std::uint64_t kCubatureDrawStream = 0xD1B54A32D192ED03ULL;
/// The smallest standard error of ln Z stated for the cubature: its embedded-rule estimate says
/// nothing of mass between its points, and against quadrature (bench_evidence_accuracy with the
/// cubature forced) it was off by up to 0.011 where that estimate said 0.001-0.002.
constexpr double kCubatureErrorFloor = 0.01;
/// The cubature and its draws' own estimate disagree beyond this many combined standard errors:
/// mass that one of them missed.
constexpr double kCrossCheckSigmas = 3.0;

double student_t4(double z) { return 0.375 * std::pow(1.0 + 0.25 * z * z, -2.5); }

/// `count` evenly spaced values from a to b, both included.
void add_nodes(std::vector<double>& nodes, double a, double b, int count) {
  for (int i = 0; i < count; ++i) nodes.push_back(a + (b - a) * i / (count - 1));
}

/// A t in the cubature's map: its centre and scale on one axis (ln values).
struct MapPeak {
  double centre, scale;
};

/// One axis's map over [lower, upper] (ln values): uniform floor, a t around each of `peaks` (equal
/// shares), and a Gaussian kernel density of `hint` (ln values; may be empty).
sampling::AxisMap axis_map(double lower, double upper, const std::vector<MapPeak>& peaks, const std::vector<double>& hint) {
  const double range = upper - lower;
  std::vector<double> nodes;
  add_nodes(nodes, lower, upper, kMapNodes);
  for (const MapPeak& t : peaks) {
    add_nodes(nodes, std::max(lower, t.centre - kMapTReach * t.scale), std::min(upper, t.centre + kMapTReach * t.scale),
              kMapNodes);
  }
  double bandwidth = 0.0;
  const double min_scale = std::min_element(peaks.begin(), peaks.end(), [](const MapPeak& a, const MapPeak& b) {
                             return a.scale < b.scale;
                           })->scale;
  if (hint.size() >= 2) {
    double mean = 0.0, square = 0.0;
    for (double h : hint) mean += h / static_cast<double>(hint.size());
    for (double h : hint) square += (h - mean) * (h - mean) / static_cast<double>(hint.size() - 1);
    // Silverman's rule, twice (smoother than the draws: the map must not miss what lies between them),
    // and never below a quarter of the narrowest t's scale.
    bandwidth = std::max(2.0 * 1.06 * std::sqrt(square) * std::pow(static_cast<double>(hint.size()), -0.2), 0.25 * min_scale);
    const auto [lo, hi] = std::minmax_element(hint.begin(), hint.end());
    add_nodes(nodes, std::max(lower, *lo - 5.0 * bandwidth), std::min(upper, *hi + 5.0 * bandwidth), kMapNodes);
  }
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> kept;
  for (double x : nodes) {
    if (kept.empty() || x > kept.back() + 1e-9 * range) kept.push_back(x);
  }
  kept.back() = upper;
  const double t_share = hint.size() >= 2 ? 0.5 * (1.0 - kUniformShare) : 1.0 - kUniformShare;
  std::vector<double> density;
  for (double x : kept) {
    double g = kUniformShare / range;
    for (const MapPeak& t : peaks) {
      g += t_share / static_cast<double>(peaks.size()) * student_t4((x - t.centre) / t.scale) / t.scale;
    }
    if (hint.size() >= 2) {
      double kernel = 0.0;
      for (double h : hint) kernel += std::exp(-0.5 * std::pow((x - h) / bandwidth, 2));
      g += t_share * kernel / (static_cast<double>(hint.size()) * bandwidth * std::sqrt(2.0 * std::numbers::pi));
    }
    density.push_back(g);
  }
  return {kept, density};
}

}  // namespace

std::vector<ModelEvidence> cubature_integrated_evidence(const ObservationSet& data, const sediment::SedimentModel& model,
                                                        const FitResult& best,
                                                        const std::vector<std::vector<Prior>>& prior_sets,
                                                        const FitOptions& fit_options, const EvidenceOptions& options,
                                                        const std::vector<Eigen::MatrixXd>& hints) {
  const auto started = std::chrono::steady_clock::now();
  if (prior_sets.empty()) throw std::invalid_argument("cubature_integrated_evidence: no priors");
  const Setup s = detail::make_setup(data, model, best.fitted, fit_options);
  const Theta theta = best.fitted.log_values();
  const auto k = static_cast<Eigen::Index>(s.free.size());
  std::vector<sampling::LogDensity> log_priors;
  std::vector<sampling::Support> supports;
  sampling::LogDensity log_likelihood;
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(k, std::numeric_limits<double>::infinity());
  Eigen::VectorXd upper = -lower;
  for (const std::vector<Prior>& priors : prior_sets) {
    const sampling::PriorAndLikelihood density = evidence_integrand(data, model, best, priors, fit_options);
    log_likelihood = density.log_likelihood;
    log_priors.push_back(density.log_prior);
    sampling::Support support{Eigen::VectorXd(k), Eigen::VectorXd(k)};
    for (Eigen::Index j = 0; j < k; ++j) {
      const auto [lo, hi] = priors[static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])].support();
      support.lower(j) = std::log(lo);
      support.upper(j) = std::log(hi);
    }
    lower = lower.cwiseMin(support.lower);
    upper = upper.cwiseMax(support.upper);
    supports.push_back(support);
  }
  // A t per mode of the fit's (the fit, and each other local minimum with kMinModeShare or more of
  // the posterior), scaled by the linearised posterior's sd per axis where it has derivatives;
  // else a tenth of the range.
  std::vector<FitMode> modes;
  for (FitMode& m : fit_modes(s, best, prior_sets)) {
    if (modes.empty() || m.share >= kMinModeShare) modes.push_back(std::move(m));
  }
  std::vector<Eigen::VectorXd> sds;
  for (const FitMode& m : modes) {
    Eigen::VectorXd sd = (upper - lower) / 10.0;
    if (m.precision.size() > 0) {
      const Eigen::VectorXd linear = m.precision.inverse().diagonal().cwiseSqrt();
      for (Eigen::Index j = 0; j < k; ++j) {
        if (std::isfinite(linear(j)) && linear(j) > 0.0) sd(j) = linear(j);
      }
    }
    sds.push_back(sd);
  }
  // Each axis's map from hint draws (ln values, rows).
  const auto maps_from = [&](const std::vector<Eigen::MatrixXd>& ln_hints) {
    std::vector<sampling::AxisMap> axes;
    for (Eigen::Index j = 0; j < k; ++j) {
      std::vector<double> hint;
      for (const Eigen::MatrixXd& h : ln_hints) {
        const Eigen::Index step =
            std::max<Eigen::Index>(1, h.rows() * static_cast<Eigen::Index>(ln_hints.size()) / kMaxHintDraws);
        for (Eigen::Index r = 0; r < h.rows(); r += step) hint.push_back(h(r, j));
      }
      const double range = upper(j) - lower(j);
      std::vector<MapPeak> peaks;
      for (std::size_t m = 0; m < modes.size(); ++m) {
        peaks.push_back({modes[m].theta[static_cast<std::size_t>(s.free[static_cast<std::size_t>(j)])],
                         std::clamp(kMapTScale * sds[m](j), 1e-6 * range, 0.25 * range)});
      }
      axes.push_back(axis_map(lower(j), upper(j), peaks, hint));
    }
    return axes;
  };
  std::vector<Eigen::MatrixXd> ln_hints;
  for (const Eigen::MatrixXd& h : hints) {
    if (h.rows() > 0) ln_hints.push_back(h.array().log().matrix());
  }
  // A first map from the fit and the hints; its own importance draws, resampled per prior, are
  // hints for the second: the map adapts once to where the posterior is.
  const sampling::MappedSample pilot =
      sampling::mapped_importance(log_likelihood, log_priors, maps_from(ln_hints), options.cubature_pilot_draws,
                                  options.seed ^ kCubaturePilotStream, options.threads);
  for (const sampling::ImportanceEstimate& w : pilot.priors) {
    if (!std::isfinite(w.log_weights.maxCoeff())) continue;
    sampling::RandomStream random(options.seed ^ kCubaturePilotStream ^ kResampleStream);
    ln_hints.push_back(sampling::resample(pilot.draws, w.log_weights, kMaxHintDraws, random));
  }
  const std::vector<sampling::AxisMap> axes = maps_from(ln_hints);
  sampling::CubatureOptions cubature = options.cubature;
  cubature.threads = options.threads;
  // The map's importance draws first: their ln Z sets the cubature's absolute error target.
  const sampling::MappedSample drawn = sampling::mapped_importance(
      log_likelihood, log_priors, axes, options.cubature_draws, options.seed ^ kCubatureDrawStream, options.threads);
  std::vector<double> reference;
  for (const sampling::ImportanceEstimate& w : drawn.priors) reference.push_back(w.log_evidence);
  const sampling::CubatureRun run =
      sampling::cubature_evidence(log_likelihood, log_priors, axes, -0.5 * best.chi2, supports, cubature, reference);
  const double n = static_cast<double>(s.observations.size());
  std::vector<ModelEvidence> out(prior_sets.size());
  for (std::size_t p = 0; p < prior_sets.size(); ++p) {
    const sampling::CubatureEstimate& c = run.priors[p];
    const sampling::ImportanceEstimate& w = drawn.priors[p];
    ModelEvidence& e = out[p];
    e.method = kCubatureMethod;
    e.log_evidence = c.log_evidence;
    e.uncertainty = std::max(c.uncertainty, kCubatureErrorFloor);
    e.pareto_k = w.pareto_k;
    e.effective_draws = w.effective_draws;
    e.evaluations = static_cast<int>(run.evaluations) + pilot.evaluations + drawn.evaluations;
    e.highest_drawn_log_likelihood = std::max(pilot.log_likelihood.maxCoeff(), drawn.log_likelihood.maxCoeff());
    const double gap = std::abs(w.log_evidence - c.log_evidence);
    const double combined = std::hypot(w.uncertainty, std::max(c.uncertainty, kCubatureErrorFloor));
    if (!run.converged) {
      e.fallback_reason = formatted("adaptive cubature did not reach a relative error of %.3f within %.0f evaluations",
                                    cubature.relative_error, static_cast<double>(cubature.max_evaluations));
    } else if (!(w.pareto_k <= kMaxParetoK)) {
      e.fallback_reason = formatted("the importance weights of adaptive cubature's map have Pareto k-hat %.2f (above "
                                    "0.7): the map misses part of the posterior, and the rule may too", w.pareto_k);
    } else if (!(gap <= kCrossCheckSigmas * combined)) {
      e.fallback_reason = formatted("adaptive cubature's ln Z %.3f and its map's importance draws' %.3f differ by "
                                    "more than 3 combined standard errors (%.3f)",
                                    c.log_evidence, w.log_evidence, combined);
    }
    e.converged = e.fallback_reason.empty();
    e.advice = formatted("%.0f sub-boxes, %.0f cubature evaluations; %.0f draws from its map give ln Z %.3f", run.boxes,
                         static_cast<double>(run.evaluations), static_cast<double>(drawn.draws.rows()), w.log_evidence) +
               formatted(" +- %.3f (Pareto k-hat %.2f, %.0f effective draws)", w.uncertainty, w.pareto_k,
                         w.effective_draws);
    finish_from_weighted_draws(e, drawn.draws, drawn.log_likelihood, w.log_weights, n, options);
  }
  const double seconds = seconds_since(started);
  for (ModelEvidence& e : out) e.wall_seconds = seconds;
  return out;
}

std::vector<Prior> widened(const std::vector<Prior>& priors, double factor) {
  std::vector<Prior> out = priors;
  for (Prior& p : out) {
    switch (p.kind) {
      case PriorKind::Normal:
      case PriorKind::LogNormal: p.b *= factor; break;
      case PriorKind::Uniform: {
        const double centre = 0.5 * (p.a + p.b), half = 0.5 * (p.b - p.a) * factor;
        p.a = std::max(p.lower, centre - half);
        p.b = std::min(p.upper, centre + half);
        break;
      }
      case PriorKind::LogUniform: {
        const double centre = 0.5 * (std::log(p.a) + std::log(p.b)), half = 0.5 * std::log(p.b / p.a) * factor;
        p.a = std::max(p.lower, std::exp(centre - half));
        p.b = std::min(p.upper, std::exp(centre + half));
        break;
      }
    }
    p.source += ", widened x" + std::to_string(static_cast<int>(factor));
  }
  return out;
}

PosteriorResult sample_posterior(const ObservationSet& data, const sediment::SedimentModel& model,
                                 const FitResult& best, const std::vector<Prior>& priors,
                                 const FitOptions& fit_options, const PosteriorOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const Setup s = detail::make_setup(data, model, best.fitted, fit_options);
  const Theta theta = best.fitted.log_values();
  const auto k = static_cast<Eigen::Index>(s.free.size());
  require_prior_covers(s, priors, theta);
  // ln posterior in the free ln-parameters: ln prior - chi^2 / 2 (the fit's Gaussian likelihood).
  const sampling::LogDensity log_posterior = [&](const Eigen::VectorXd& x) {
    const Theta t = with_free(s, theta, x);
    const double lp = log_prior(s.parameters, priors, t);
    if (!std::isfinite(lp)) return -std::numeric_limits<double>::infinity();
    const double chi2 = detail::chi2_at(s, t);
    return std::isfinite(chi2) ? lp - 0.5 * chi2 : -std::numeric_limits<double>::infinity();
  };
  sampling::EnsembleOptions ensemble = ensemble_options(options);
  ensemble.burn_in = options.burn_in;
  ensemble.moves = sampling::differential_moves();
  // The stop test and the verdict cover the derived quantities too (a derived quantity along a ridge can
  // mix more slowly than any parameter), each computed once per kept draw.
  const std::vector<detail::DerivedFunction> derived_functions = detail::derived_functions_for(s);
  const std::vector<std::size_t> watched = varying_quantities(s, derived_functions, theta);
  std::vector<std::string> names;
  for (const int i : s.free) names.push_back(s.parameters.spec[i].name);
  for (const detail::DerivedFunction& c : derived_functions) names.push_back(c.name);
  DerivedChains derived(s, theta, derived_functions.size());
  ProgressReporter report(options.progress);
  // The stop test: the posterior's ensemble has converged, and for a tempered run every rung has
  // mixed over >= 50 of its slowest tau (rung_tau; 0 for one ensemble).
  const double per_tau = sampling::ConvergenceCriteria{}.min_steps_per_tau;
  const auto judge = [&](const sampling::EnsembleRun& so_far, double rung_tau) {
    const sampling::Diagnostics d =
        watched_columns(diagnose_together(so_far, derived.update(so_far), names), s.free.size(), watched);
    report(so_far.steps, options.steps, std::max(steps_needed(d), 2.0 * per_tau * rung_tau),
           formatted("largest autocorrelation time %.1f steps, smallest ESS %.0f",
                     d.autocorrelation_time.maxCoeff(), d.ess.minCoeff()) +
               (rung_tau > 0.0 ? formatted(", slowest rung %.1f steps", rung_tau) : std::string()));
    return sampling::assess_convergence(d).converged && kept_steps(so_far) >= per_tau * rung_tau;
  };
  const int temperatures = options.temperatures >= 0 ? options.temperatures
                           : open_to_the_bounds(s, theta, priors, fit_options.determined_log_sigma)
                               ? PosteriorOptions::kAutoTemperatures
                               : 0;
  sampling::EnsembleRun run;
  double rung_tau = 0.0;
  int rungs = 0;
  if (temperatures < 2) {
    ensemble.stop = [&](const sampling::EnsembleRun& so_far) { return judge(so_far, 0.0); };
    run = sampling::sample(log_posterior, start_walkers(s, best, priors, theta, ensemble, [&](const Eigen::VectorXd& x) {
      return std::isfinite(log_posterior(x));
    }), ensemble);
  } else {
    // Parallel tempering moves every rung by the stretch move (sample_tempered).
    ensemble.moves = {};
    const sampling::PriorAndLikelihood density = evidence_integrand(data, model, best, priors, fit_options);
    TemperedStart ladder =
        tempered_start(s, best, priors, theta, density, temperatures, EvidenceOptions{}.max_temperature, ensemble);
    ladder.tempering.stop = [&](const sampling::TemperedRun& so_far) {
      return judge(so_far.levels[0], slowest_rung_tau(so_far, k)) && so_far.steps >= kMinTemperedSteps;
    };
    const sampling::TemperedRun tempered = sampling::sample_tempered(density, ladder.starts, ladder.tempering);
    run = tempered.levels[0];
    run.evaluations = tempered.evaluations + kPilotDraws;
    rung_tau = slowest_rung_tau(tempered, k);
    rungs = static_cast<int>(tempered.betas.size());
  }
  const std::vector<Eigen::MatrixXd> derived_chains = derived.update(run);
  // Every column: the parameters', then every derived quantity's.
  const sampling::Diagnostics diagnostics = diagnose_together(run, derived_chains, names);
  sampling::Convergence convergence =
      sampling::assess_convergence(watched_columns(diagnostics, s.free.size(), watched));
  const double kept = kept_steps(run);
  if (kept < per_tau * rung_tau) {
    convergence.advice = formatted("a rung of the tempering ladder has not mixed: its slowest autocorrelation time "
                                   "is %.0f steps, and the %.0f kept steps hold %.1f of them (50 wanted)",
                                   rung_tau, kept, kept / rung_tau) +
                         (convergence.converged ? std::string() : "; " + convergence.advice);
    convergence.converged = false;
  }

  PosteriorResult result;
  result.walkers = static_cast<int>(run.chains.size());
  result.steps = run.steps;
  result.steps_cap = options.steps;
  result.temperatures = rungs;
  result.evaluations = run.evaluations;
  result.acceptance = run.acceptance;
  result.converged = convergence.converged;
  result.advice = convergence.converged || options.check_every == 0
                      ? convergence.advice
                      : "stopped at the cap of " + std::to_string(run.steps) +
                            " steps (--steps) before converging: " + convergence.advice;
  const Eigen::MatrixXd pooled = sampling::pooled_samples(run.chains);  // ln values
  result.correlation = sampling::correlation_matrix(pooled);
  result.samples = pooled.array().exp().matrix();
  const Eigen::MatrixXd jacobian =
      detail::whitened_jacobian(s, with_free(s, theta, pooled.row(detail::central_draw(pooled)).transpose()));
  const detail::PriorControl control(pooled, jacobian.transpose() * jacobian);
  const PriorQuantities prior_alone = prior_quantities(s, priors, theta, derived_functions.size(), options.seed);
  for (Eigen::Index j = 0; j < k; ++j) {
    const int i = s.free[static_cast<std::size_t>(j)];
    const ParameterSpec& spec = s.parameters.spec[i];
    const Prior& prior = priors[static_cast<std::size_t>(i)];
    result.sample_names.push_back(spec.name);
    result.sample_units.push_back(spec.unit);
    result.priors.push_back(spec.name + ": " + prior.describe(spec.unit));
    PosteriorQuantity q = summarize(spec.name, spec.unit, result.samples.col(j), diagnostics.rhat(j), diagnostics.ess(j));
    const Eigen::VectorXd own = pooled.col(j).unaryExpr([&](double x) { return in_prior_coordinate(prior, x); });
    flag_prior_control(q, control, pooled.col(j), own, prior_alone.parameters.col(j),
                       profile_of(best, fit_options, spec.name));
    result.parameters.push_back(q);
  }

  // Derived quantities at every kept draw, walker by walker (their R-hat and ESS are columns k.. above).
  if (!derived_functions.empty()) {
    const Eigen::MatrixXd all = sampling::pooled_samples(derived_chains);
    for (std::size_t c = 0; c < derived_functions.size(); ++c) {
      const auto col = static_cast<Eigen::Index>(c);
      result.derived.push_back(summarize(derived_functions[c].name, derived_functions[c].unit, all.col(col),
                                              diagnostics.rhat(k + col), diagnostics.ess(k + col)));
      const Eigen::VectorXd ln_values = all.col(col).array().log().matrix();
      flag_prior_control(result.derived.back(), control, ln_values, ln_values, prior_alone.derived[c],
                         profile_of(best, fit_options, derived_functions[c].name));
    }
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

nlohmann::json posterior_report(const PosteriorResult& p) {
  nlohmann::json j;
  j["sampler"] = {{"algorithm", sampler_algorithm(p)},
                  {"temperatures", p.temperatures},
                  {"walkers", p.walkers},
                  {"steps", p.steps},
                  {"steps_cap", p.steps_cap},
                  {"burn_in", "first half"},
                  {"acceptance", p.acceptance},
                  {"evaluations", p.evaluations},
                  {"wall_seconds", p.wall_seconds}};
  j["converged"] = p.converged;
  j["advice"] = p.advice;
  j["priors"] = p.priors;
  const auto quantity = [](const PosteriorQuantity& q) {
    return nlohmann::json{{"unit", q.unit},
                          {"median", q.median},
                          {"credible_68", {q.lower_68, q.upper_68}},
                          {"credible_95", {q.lower_95, q.upper_95}},
                          {"split_rhat", q.split_rhat},
                          {"effective_samples", q.effective_samples},
                          {"prior_dominated", q.prior_dominated},
                          {"prior_share", q.prior_share}};
  };
  for (const auto& q : p.parameters) j["parameters"][q.name] = quantity(q);
  for (const auto& q : p.derived) j["combinations"][q.name] = quantity(q);
  j["correlation_of_ln_parameters"] = nlohmann::json::array();
  for (Eigen::Index r = 0; r < p.correlation.rows(); ++r) {
    std::vector<double> row;
    for (Eigen::Index c = 0; c < p.correlation.cols(); ++c) row.push_back(p.correlation(r, c));
    j["correlation_of_ln_parameters"].push_back(row);
  }
  return j;
}

void write_samples_csv(const std::filesystem::path& path, const Eigen::MatrixXd& samples,
                       const std::vector<std::string>& names, const std::vector<std::string>& units) {
  io::write_text_atomically(path, [&](std::ostream& out) {
    out << "# sedwave posterior samples: pooled kept draws of every walker (burn-in dropped), SI units:";
    for (std::size_t j = 0; j < names.size(); ++j) out << ' ' << names[j] << " [" << units[j] << "]";
    out << '\n';
    for (std::size_t j = 0; j < names.size(); ++j) out << (j ? "," : "") << names[j];
    out << '\n';
    out.precision(9);
    for (Eigen::Index r = 0; r < samples.rows(); ++r) {
      for (Eigen::Index c = 0; c < samples.cols(); ++c) out << (c ? "," : "") << samples(r, c);
      out << '\n';
    }
  });
}

void write_posterior_samples_csv(const std::filesystem::path& path, const PosteriorResult& p) {
  write_samples_csv(path, p.samples, p.sample_names, p.sample_units);
}

void write_posterior_samples_hdf5(const std::filesystem::path& path, const PosteriorResult& p) {
  std::vector<io::NamedColumn> columns;
  for (std::size_t j = 0; j < p.sample_names.size(); ++j) {
    const Eigen::VectorXd column = p.samples.col(static_cast<Eigen::Index>(j));
    columns.push_back({p.sample_names[j], p.sample_units[j], "posterior draws of " + p.sample_names[j],
                       std::vector<double>(column.data(), column.data() + column.size())});
  }
  std::string priors;
  for (const std::string& line : p.priors) priors += line + "\n";
  io::write_columns_hdf5(
      path,
      {{"title", "sedwave posterior samples"},
       {"layout", "one dataset per free parameter, shape {walkers, kept steps}: walker w's chain in row w, burn-in "
                  "dropped; values in the dataset's unit (SI)"},
       {"sampler", sampler_algorithm(p) + "; " + std::to_string(p.walkers) +
                       " walkers x " + std::to_string(p.steps) + " steps, first half burn-in"},
       {"priors", priors},
       {"converged", p.converged ? "yes" : "no: " + p.advice}},
      columns, static_cast<std::size_t>(p.walkers));
}

void write_posterior_marginals_csv(const std::filesystem::path& path, const PosteriorResult& p) {
  io::write_text_atomically(path, [&](std::ostream& out) {
    out << "# sedwave posterior marginals: 40-bin histograms of the pooled draws; edges in the parameter's unit, "
           "density in 1/unit (integrates to 1)\n"
        << "parameter,unit,lower,upper,density\n";
    out.precision(9);
    for (Eigen::Index c = 0; c < p.samples.cols(); ++c) {
      const sampling::Histogram h = sampling::marginal_histogram(p.samples.col(c), 40);
      for (Eigen::Index b = 0; b < h.density.size(); ++b) {
        out << p.sample_names[static_cast<std::size_t>(c)] << ',' << p.sample_units[static_cast<std::size_t>(c)] << ','
            << h.edges(b) << ',' << h.edges(b + 1) << ',' << h.density(b) << '\n';
      }
    }
  });
}

}  // namespace sedwave::inversion
