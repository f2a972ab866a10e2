#include "sedwave/sampling/importance.hpp"

#include "minus_infinity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <stdexcept>
#include <string>
#include <utility>

namespace sedwave::sampling {
namespace {

/// A multivariate t distribution: location, Cholesky factor of the scale matrix, degrees of freedom.
struct StudentT {
  Eigen::VectorXd location;
  Eigen::MatrixXd cholesky;  ///< lower
  int nu = 4;
  double log_normaliser = 0.0;

  StudentT(Eigen::VectorXd mu, const Eigen::MatrixXd& scale, int dof) : location(std::move(mu)), nu(dof) {
    const Eigen::LLT<Eigen::MatrixXd> llt(scale);
    if (llt.info() != Eigen::Success) throw std::invalid_argument("importance_evidence: a scale matrix is not positive definite");
    cholesky = llt.matrixL();
    const auto d = static_cast<double>(location.size());
    log_normaliser = std::lgamma(0.5 * (nu + d)) - std::lgamma(0.5 * nu) - 0.5 * d * std::log(nu * std::numbers::pi) -
                     cholesky.diagonal().array().log().sum();
  }
  [[nodiscard]] double log_density(const Eigen::VectorXd& x) const {
    const double distance2 = cholesky.triangularView<Eigen::Lower>().solve(x - location).squaredNorm();
    return log_normaliser - 0.5 * (nu + static_cast<double>(location.size())) * std::log1p(distance2 / nu);
  }
  /// mu + L z / sqrt(g / nu), z standard normal, g ~ chi^2_nu (a sum of nu squared normals).
  [[nodiscard]] Eigen::VectorXd draw(RandomStream& random) const {
    Eigen::VectorXd z(location.size());
    for (Eigen::Index i = 0; i < z.size(); ++i) z(i) = random.normal();
    double g = 0.0;
    for (int i = 0; i < nu; ++i) g += std::pow(random.normal(), 2);
    return location + cholesky * z / std::sqrt(g / nu);
  }
};

/// The defensive component (after Hesterberg 1995, Technometrics 37, 185): uniform along one
/// principal axis of the posterior (its flattest: a plateau, a cut at a bound, two modes along it),
/// a t across it. With a share a of the mixture no weight L pi / q exceeds (L pi / t) (hi - lo) / a,
/// however the posterior is shaped along that axis between lo and hi.
struct Slab {
  Eigen::VectorXd mean;
  Eigen::MatrixXd axes;  ///< orthonormal columns; the first is the uniform one
  int parameter = kSlabAlongCombination;  ///< the coordinate that first axis is, if it is one
  bool lo_cut = false, hi_cut = false;     ///< that end is where the axis leaves the support
  double lo = 0.0, hi = 0.0;
  /// The t across, centred per equal segment of [lo, hi] on the posterior's own centre there (a
  /// plateau's cross-section need not stay on one line); none in one dimension.
  std::optional<StudentT> across;
  std::vector<Eigen::VectorXd> centres;

  [[nodiscard]] std::size_t segment(double along) const {
    const auto n = static_cast<double>(centres.size());
    return static_cast<std::size_t>(std::clamp(std::floor((along - lo) / (hi - lo) * n), 0.0, n - 1.0));
  }
  [[nodiscard]] double log_density(const Eigen::VectorXd& x) const {
    const Eigen::VectorXd z = axes.transpose() * (x - mean);
    if (!(z(0) >= lo && z(0) <= hi)) return kMinusInfinity;
    if (!across) return -std::log(hi - lo);
    return -std::log(hi - lo) + across->log_density(z.tail(z.size() - 1) - centres[segment(z(0))]);
  }
  [[nodiscard]] Eigen::VectorXd draw(RandomStream& random) const {
    Eigen::VectorXd z(mean.size());
    z(0) = lo + (hi - lo) * random.uniform();
    if (across) z.tail(z.size() - 1) = centres[segment(z(0))] + across->draw(random);
    return mean + axes * z;
  }
};

/// An equal mixture of t components and slabs.
struct Mixture {
  std::vector<StudentT> t;
  std::vector<Slab> slabs;

  [[nodiscard]] std::size_t size() const { return t.size() + slabs.size(); }
  /// Component c (the t's first, then the slabs).
  [[nodiscard]] Eigen::VectorXd draw(std::size_t c, RandomStream& random) const {
    return c < t.size() ? t[c].draw(random) : slabs[c - t.size()].draw(random);
  }
  [[nodiscard]] double log_density(const Eigen::VectorXd& x) const;
};

double log_sum_exp(const Eigen::VectorXd& v) {
  const double peak = v.maxCoeff();
  if (!std::isfinite(peak)) return peak;
  return peak + std::log((v.array() - peak).exp().sum());
}

/// ln of the equal mixture's density.
double Mixture::log_density(const Eigen::VectorXd& x) const {
  Eigen::VectorXd each(static_cast<Eigen::Index>(size()));
  for (std::size_t c = 0; c < t.size(); ++c) each(static_cast<Eigen::Index>(c)) = t[c].log_density(x);
  for (std::size_t c = 0; c < slabs.size(); ++c) each(static_cast<Eigen::Index>(t.size() + c)) = slabs[c].log_density(x);
  return log_sum_exp(each) - std::log(static_cast<double>(size()));
}

/// Draws of the equal mixture (component c for draw i = i mod components: stratified, the same
/// proportions as the mixture), their log priors and log likelihoods (the latter evaluated in parallel).
struct Batch {
  std::vector<Eigen::VectorXd> x;
  std::vector<std::vector<double>> log_prior;  ///< [prior][draw]
  std::vector<double> log_likelihood;
  std::vector<double> log_proposal;
  int evaluations = 0;
};

Batch draw_batch(const Mixture& components, int count, const LogDensity& log_likelihood,
                 const std::vector<LogDensity>& log_priors, RandomStream& random, int threads) {
  Batch b;
  b.log_prior.assign(log_priors.size(), std::vector<double>(static_cast<std::size_t>(count)));
  b.log_likelihood.assign(static_cast<std::size_t>(count), kMinusInfinity);
  b.log_proposal.resize(static_cast<std::size_t>(count));
  std::vector<int> to_evaluate;
  for (int i = 0; i < count; ++i) {
    const auto u = static_cast<std::size_t>(i);
    b.x.push_back(components.draw(u % components.size(), random));
    b.log_proposal[u] = components.log_density(b.x.back());
    bool any = false;
    for (std::size_t p = 0; p < log_priors.size(); ++p) {
      b.log_prior[p][u] = log_priors[p](b.x.back());
      any = any || std::isfinite(b.log_prior[p][u]);
    }
    if (any) to_evaluate.push_back(i);
  }
  const auto n = static_cast<int>(to_evaluate.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads) if (threads > 1)
  for (int j = 0; j < n; ++j) {
    const auto u = static_cast<std::size_t>(to_evaluate[static_cast<std::size_t>(j)]);
    const double v = log_likelihood(b.x[u]);
    b.log_likelihood[u] = std::isnan(v) ? kMinusInfinity : v;
  }
  b.evaluations = n;
  return b;
}

void append(Batch& all, const Batch& more) {
  all.x.insert(all.x.end(), more.x.begin(), more.x.end());
  if (all.log_prior.empty()) all.log_prior.resize(more.log_prior.size());
  for (std::size_t p = 0; p < more.log_prior.size(); ++p) {
    all.log_prior[p].insert(all.log_prior[p].end(), more.log_prior[p].begin(), more.log_prior[p].end());
  }
  all.log_likelihood.insert(all.log_likelihood.end(), more.log_likelihood.begin(), more.log_likelihood.end());
  all.log_proposal.insert(all.log_proposal.end(), more.log_proposal.begin(), more.log_proposal.end());
  all.evaluations += more.evaluations;
}

/// The pilots' proposal density as the balance heuristic has it (Veach & Guibas 1995; Owen & Zhou
/// 2000, JASA 95, 135): every draw weighted against the equal mixture of all the rounds' mixtures
/// (each round drew as many), not only its own. Unbiased still, and a poor first round no longer
/// dominates the weights once a better one has drawn.
void balance(Batch& pilots, const std::vector<Mixture>& rounds) {
  Eigen::VectorXd each(static_cast<Eigen::Index>(rounds.size()));
  for (std::size_t i = 0; i < pilots.x.size(); ++i) {
    for (std::size_t r = 0; r < rounds.size(); ++r) each(static_cast<Eigen::Index>(r)) = rounds[r].log_density(pilots.x[i]);
    pilots.log_proposal[i] = log_sum_exp(each) - std::log(static_cast<double>(rounds.size()));
  }
}

/// The estimate from draws (rows) and their log weights L pi / q (-inf: zero).
ImportanceEstimate estimate_of_weights(const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_w) {
  const Eigen::Index n = draws.rows();
  ImportanceEstimate e;
  // k-hat from the Pareto-smoothed tail judges the weights; the estimate itself uses the raw
  // weights, whose mean is unbiased.
  e.pareto_k = pareto_smooth(log_w).k;
  const double peak = log_w.maxCoeff();
  if (!std::isfinite(peak)) {
    e.log_evidence = kMinusInfinity;
    e.uncertainty = std::numeric_limits<double>::infinity();
    e.pareto_k = std::numeric_limits<double>::infinity();
    e.log_weights = log_w;
    return e;
  }
  const Eigen::ArrayXd w = (log_w.array() - peak).exp();
  const double mean = w.mean();
  const double variance = (w - mean).square().sum() / static_cast<double>(n - 1);
  const double relative_error2 = variance / (static_cast<double>(n) * mean * mean);
  e.log_evidence = peak + std::log(mean) + 0.5 * relative_error2;
  e.uncertainty = std::sqrt(relative_error2);
  e.effective_draws = w.sum() * w.sum() / w.square().sum();
  const Eigen::ArrayXd p = w / w.sum();
  e.log_weights = log_w.array() - peak - std::log(w.sum());
  const auto dim = static_cast<Eigen::Index>(draws.cols());
  e.mean = Eigen::VectorXd::Zero(dim);
  for (Eigen::Index i = 0; i < n; ++i) e.mean += p(i) * draws.row(i).transpose();
  e.covariance = Eigen::MatrixXd::Zero(dim, dim);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::VectorXd d = draws.row(i).transpose() - e.mean;
    e.covariance += p(i) * d * d.transpose();
  }
  // Shape: far mass and the kurtosis along each principal axis, in the posterior's own metric.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> axes(e.covariance);
  const Eigen::VectorXd sd = axes.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  Eigen::VectorXd fourth = Eigen::VectorXd::Zero(dim);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd z = axes.eigenvectors().transpose() * (draws.row(i).transpose() - e.mean);
    z = z.cwiseQuotient(sd);
    if (z.norm() > kFarDistance) e.far_mass += p(i);
    fourth += p(i) * z.array().pow(4).matrix();
  }
  e.min_axis_kurtosis = fourth.minCoeff();
  return e;
}

/// One prior's estimate from a batch, weighted by L pi / q.
ImportanceEstimate estimate(const Batch& b, std::size_t prior) {
  const auto n = static_cast<Eigen::Index>(b.x.size());
  Eigen::VectorXd log_w(n);
  Eigen::MatrixXd draws(n, b.x.front().size());
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double lp = b.log_prior[prior][u];
    log_w(i) = std::isfinite(lp) && std::isfinite(b.log_likelihood[u]) ? lp + b.log_likelihood[u] - b.log_proposal[u]
                                                                       : kMinusInfinity;
    draws.row(i) = b.x[u].transpose();
  }
  return estimate_of_weights(draws, log_w);
}

void check(const std::vector<LogDensity>& log_priors, const Eigen::VectorXd& centre, const Eigen::MatrixXd& covariance,
           const ImportanceOptions& o) {
  if (log_priors.empty()) throw std::invalid_argument("importance_evidence: no prior to integrate");
  if (centre.size() < 1 || covariance.rows() != centre.size() || covariance.cols() != centre.size()) {
    throw std::invalid_argument("importance_evidence: centre and covariance must have the same dimension");
  }
  if (o.pilot_draws < 100 || o.draws < 100 || o.max_draws < o.draws || o.degrees_of_freedom < 1 ||
      !(o.pilot_scale > 0.0) || !(o.adapted_scale > 0.0) || !(o.target_uncertainty > 0.0) ||
      std::isnan(o.draw_on_below_pareto_k)) {
    throw std::invalid_argument("importance_evidence: pilot_draws and draws must be >= 100, max_draws >= draws, "
                                "degrees_of_freedom >= 1, the scales and the target positive, "
                                "draw_on_below_pareto_k a number");
  }
}

/// Generalized Pareto fit to exceedances x (ascending, > 0) by Zhang & Stephens (2009): the
/// posterior mean of b = -k/sigma over a grid, then k; with Vehtari et al.'s prior (k pulled
/// towards 0.5 with weight 10 draws). Returns {k, sigma}.
std::pair<double, double> generalized_pareto_fit(const std::vector<double>& x) {
  const auto n = static_cast<int>(x.size());
  const int m = 30 + static_cast<int>(std::sqrt(static_cast<double>(n)));
  const double quartile = x[static_cast<std::size_t>(std::max(0, static_cast<int>(n / 4.0 + 0.5) - 1))];
  std::vector<double> b(static_cast<std::size_t>(m)), log_likelihood(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const auto u = static_cast<std::size_t>(j);
    b[u] = 1.0 / x.back() + (1.0 - std::sqrt(m / (j + 0.5))) / (3.0 * quartile);
    double k = 0.0;
    for (const double xi : x) k += std::log1p(-b[u] * xi);
    k /= n;  // this is -k in the usual sign
    log_likelihood[u] = n * (std::log(-b[u] / k) - k - 1.0);
  }
  double b_mean = 0.0, total = 0.0;
  for (int j = 0; j < m; ++j) {
    double s = 0.0;
    for (int i = 0; i < m; ++i) s += std::exp(log_likelihood[static_cast<std::size_t>(i)] - log_likelihood[static_cast<std::size_t>(j)]);
    const double weight = 1.0 / s;
    if (weight < 10.0 * std::numeric_limits<double>::epsilon()) continue;
    b_mean += weight * b[static_cast<std::size_t>(j)];
    total += weight;
  }
  b_mean /= total;
  double k = 0.0;
  for (const double xi : x) k += std::log1p(-b_mean * xi);
  k /= n;
  const double sigma = -k / b_mean;
  k = (n * k + 10.0 * 0.5) / (n + 10.0);
  return {k, sigma};
}

/// The generalized Pareto quantile function at p.
double generalized_pareto_quantile(double p, double k, double sigma) {
  if (std::abs(k) < 1e-12) return -sigma * std::log1p(-p);
  return sigma * std::expm1(-k * std::log1p(-p)) / k;
}

/// The support's bound on coordinate j (+-inf where it has none).
double lower_bound(const Support& s, Eigen::Index j) {
  return j < s.lower.size() ? s.lower(j) : -std::numeric_limits<double>::infinity();
}
double upper_bound(const Support& s, Eigen::Index j) {
  return j < s.upper.size() ? s.upper(j) : std::numeric_limits<double>::infinity();
}

/// Whether a prior's posterior, as the pilots weigh it, is not a single Gaussian-like peak inside its
/// support: too few effective draws to place a t there, mass far out, a flat or split principal
/// axis, or its mean within kDefendWithinSd sd of a bound.
bool needs_defence(const ImportanceEstimate& e, const Support& support, double dim) {
  if (!(e.effective_draws >= 10.0 * (dim + 1.0)) || e.far_mass > 0.01 || e.min_axis_kurtosis < kDefendBelowKurtosis) {
    return true;
  }
  for (Eigen::Index j = 0; j < e.mean.size(); ++j) {
    const double reach = kDefendWithinSd * std::sqrt(e.covariance(j, j));
    if (e.mean(j) - reach < lower_bound(support, j) || e.mean(j) + reach > upper_bound(support, j)) return true;
  }
  return false;
}

/// The slab along one principal axis of one prior's weighted posterior `e`: along it, the span of the draws where L pi lies within kHighDensityDepth of its largest
/// value, widened by its width on each side and cut to the support; across it, a t with the posterior's covariance
/// scaled by `scale`^2. None where that covariance is not positive definite.
/// The slab's t across it: each of kSlabSegments segments centred on the weighted mean of the
/// draws there that `high_density` marks (1: within kHighDensityDepth of the largest L pi; the
/// t's far draws, though they may hold effective draws, say nothing of where the posterior is)
/// where they hold at least 10 effective draws, else on the nearest such segment's; the scale matrix
/// the weighted covariance of those draws about their centres times `scale`^2.
void place_across(Slab& slab, const Batch& b, const ImportanceEstimate& e, const Eigen::VectorXd& high_density,
                  double scale, int nu) {
  const auto k = slab.mean.size() - 1;
  const std::size_t n = kSlabSegments;
  slab.centres.assign(n, Eigen::VectorXd::Zero(k));
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  std::vector<Eigen::VectorXd> z(b.x.size());
  std::vector<std::size_t> at(b.x.size(), 0);
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    const double w = std::exp(e.log_weights(static_cast<Eigen::Index>(i)));
    z[i] = slab.axes.transpose() * (b.x[i] - slab.mean);
    if (!(w > 0.0) || !(high_density(static_cast<Eigen::Index>(i)) > 0.0) || z[i](0) < slab.lo || z[i](0) > slab.hi) continue;
    at[i] = slab.segment(z[i](0));
    slab.centres[at[i]] += w * z[i].tail(k);
    sum[at[i]] += w, sum2[at[i]] += w * w;
  }
  std::vector<bool> placed(n);
  for (std::size_t s = 0; s < n; ++s) {
    placed[s] = sum[s] > 0.0 && sum[s] * sum[s] >= 10.0 * sum2[s];
    if (placed[s]) slab.centres[s] /= sum[s];
  }
  if (std::none_of(placed.begin(), placed.end(), [](bool p) { return p; })) {
    std::fill(slab.centres.begin(), slab.centres.end(), Eigen::VectorXd::Zero(k));
    placed.assign(n, true);
  }
  for (std::size_t s = 0; s < n; ++s) {
    if (placed[s]) continue;
    std::size_t nearest = 0;
    for (std::size_t t = 0; t < n; ++t) {
      const auto distance = [&](std::size_t u) { return u > s ? u - s : s - u; };
      if (placed[t] && (!placed[nearest] || distance(t) < distance(nearest))) nearest = t;
    }
    slab.centres[s] = slab.centres[nearest];
  }
  Eigen::MatrixXd spread = Eigen::MatrixXd::Zero(k, k);
  double total = 0.0;
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    const double w = std::exp(e.log_weights(static_cast<Eigen::Index>(i)));
    if (!(w > 0.0) || z[i](0) < slab.lo || z[i](0) > slab.hi) continue;
    const Eigen::VectorXd d = z[i].tail(k) - slab.centres[at[i]];
    spread += w * d * d.transpose();
    total += w;
  }
  spread /= total;
  if (Eigen::LLT<Eigen::MatrixXd>(spread).info() != Eigen::Success) {
    spread = (slab.axes.rightCols(k).transpose() * e.covariance * slab.axes.rightCols(k)).eval();
  }
  slab.across.emplace(Eigen::VectorXd::Zero(k), Eigen::MatrixXd(scale * scale * spread), nu);
}

std::optional<Slab> defensive_slab(const Batch& b, std::size_t prior, const ImportanceEstimate& e, const Support& support,
                                   const Eigen::MatrixXd& linearised, double scale, int nu) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(e.covariance);
  if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 0.0)) return std::nullopt;
  const auto dim = e.mean.size();
  Eigen::VectorXd fourth = Eigen::VectorXd::Zero(dim);
  Eigen::VectorXd value = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(b.x.size()), kMinusInfinity);
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    if (!std::isfinite(e.log_weights(r))) continue;
    value(r) = b.log_prior[prior][i] + b.log_likelihood[i];
    const Eigen::VectorXd z = eigen.eigenvectors().transpose() * (b.x[i] - e.mean);
    fourth += std::exp(e.log_weights(r)) * z.array().pow(4).matrix().cwiseQuotient(eigen.eigenvalues().cwiseAbs2());
  }
  // The flattest axis where one is flatter than a single peak's; else the one along which the
  // posterior reaches farthest beyond the linearisation's guess (`linearised`).
  Eigen::Index flat = 0;
  if (fourth.minCoeff(&flat) >= kDefendBelowKurtosis) {
    const Eigen::MatrixXd& u = eigen.eigenvectors();
    const Eigen::VectorXd guess = (u.transpose() * linearised * u).diagonal();
    eigen.eigenvalues().cwiseQuotient(guess).maxCoeff(&flat);
  }
  Slab slab;
  slab.mean = e.mean;
  slab.axes.resize(dim, dim);
  // An axis within kSnapCosine of a coordinate runs along that parameter itself: a plateau that a
  // prior closes runs along its parameter, and the prior's bound then cuts the slab square.
  Eigen::Index parameter = 0;
  const Eigen::MatrixXd& principal = eigen.eigenvectors();
  if (principal.col(flat).cwiseAbs().maxCoeff(&parameter) >= kSnapCosine) {
    slab.axes.col(0) = Eigen::VectorXd::Unit(dim, parameter);
    slab.parameter = static_cast<int>(parameter);
    for (Eigen::Index j = 0, c = 1; j < dim; ++j) {
      if (j != parameter) slab.axes.col(c++) = Eigen::VectorXd::Unit(dim, j);
    }
  } else {
    slab.axes.col(0) = principal.col(flat);
    for (Eigen::Index j = 0, c = 1; j < dim; ++j) {
      if (j != flat) slab.axes.col(c++) = principal.col(j);
    }
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const double peak = value.maxCoeff();
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    if (value(static_cast<Eigen::Index>(i)) < peak - kHighDensityDepth) continue;
    const double along = slab.axes.col(0).dot(b.x[i] - e.mean);
    lo = std::min(lo, along), hi = std::max(hi, along);
  }
  // Widened by its width on each side (the pilots may not yet have reached the end of a plateau),
  // then cut where the axis through the mean leaves the support.
  const double width = hi - lo;
  slab.lo = lo - width;
  slab.hi = hi + width;
  for (Eigen::Index j = 0; j < dim; ++j) {
    const double v = slab.axes(j, 0);
    if (std::abs(v) < 1e-12) continue;
    const double a = (lower_bound(support, j) - e.mean(j)) / v, c = (upper_bound(support, j) - e.mean(j)) / v;
    if (std::min(a, c) >= slab.lo) slab.lo = std::min(a, c), slab.lo_cut = true;
    if (std::max(a, c) <= slab.hi) slab.hi = std::max(a, c), slab.hi_cut = true;
  }
  if (!(slab.hi > slab.lo)) return std::nullopt;
  if (dim > 1) place_across(slab, b, e, (value.array() >= peak - kHighDensityDepth).cast<double>(), scale, nu);
  return slab;
}

/// The posterior's largest sd across the slab (along any of its other axes) over the linearised
/// posterior's (`linearised`) along the same axis.
double across_spread(const Slab& slab, const ImportanceEstimate& e, const Eigen::MatrixXd& linearised) {
  const auto k = slab.mean.size() - 1;
  if (k == 0) return 0.0;
  const Eigen::MatrixXd across = slab.axes.rightCols(k);
  const Eigen::VectorXd posterior = (across.transpose() * e.covariance * across).diagonal();
  const Eigen::VectorXd guess = (across.transpose() * linearised * across).diagonal();
  return posterior.cwiseQuotient(guess).cwiseSqrt().maxCoeff();
}

/// The posterior's weighted mass in the slab's outermost segments at the ends that the support
/// did not cut: beyond the pilots' high-density span by half that span.
double end_mass(const Slab& slab, const Batch& b, const ImportanceEstimate& e) {
  double mass = 0.0;
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    const double w = std::exp(e.log_weights(static_cast<Eigen::Index>(i)));
    if (!(w > 0.0)) continue;
    const double along = slab.axes.col(0).dot(b.x[i] - slab.mean);
    const double segment = (slab.hi - slab.lo) / kSlabSegments;
    if ((!slab.lo_cut && along < slab.lo + segment) || (!slab.hi_cut && along > slab.hi - segment)) mass += w;
  }
  return mass;
}

}  // namespace

ImportanceEstimate weighted_estimate(const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_weights) {
  if (draws.rows() != log_weights.size() || draws.rows() < 2) {
    throw std::invalid_argument("weighted_estimate: one log weight per draw, at least two draws");
  }
  return estimate_of_weights(draws, log_weights);
}

ParetoSmoothed pareto_smooth(const Eigen::VectorXd& log_weights) {
  ParetoSmoothed out{log_weights, std::numeric_limits<double>::infinity()};
  const double peak = log_weights.maxCoeff();
  if (!std::isfinite(peak)) return out;
  const auto s = static_cast<double>(log_weights.size());
  const auto tail = static_cast<Eigen::Index>(std::ceil(std::min(0.2 * s, 3.0 * std::sqrt(s))));
  std::vector<Eigen::Index> order(static_cast<std::size_t>(log_weights.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return log_weights(a) < log_weights(b); });
  const Eigen::Index cut = log_weights.size() - tail - 1;
  if (cut < 0) return out;
  const double threshold = log_weights(order[static_cast<std::size_t>(cut)]) - peak;
  if (!std::isfinite(threshold)) return out;
  std::vector<Eigen::Index> in_tail;
  std::vector<double> exceedance;
  for (Eigen::Index r = cut + 1; r < log_weights.size(); ++r) {
    const Eigen::Index i = order[static_cast<std::size_t>(r)];
    if (log_weights(i) - peak > threshold) {
      in_tail.push_back(i);
      exceedance.push_back(std::exp(log_weights(i) - peak) - std::exp(threshold));
    }
  }
  if (in_tail.size() <= 4) return out;
  const auto [k, sigma] = generalized_pareto_fit(exceedance);
  out.k = k;
  if (!std::isfinite(k)) return out;
  const auto m = static_cast<double>(in_tail.size());
  for (std::size_t z = 0; z < in_tail.size(); ++z) {
    const double smoothed = std::log(generalized_pareto_quantile((static_cast<double>(z) + 0.5) / m, k, sigma) +
                                     std::exp(threshold));
    out.log_weights(in_tail[z]) = peak + std::min(0.0, smoothed);
  }
  return out;
}

ImportanceRun importance_evidence(const LogDensity& log_likelihood, const std::vector<LogDensity>& log_priors,
                                  const Eigen::VectorXd& centre, const Eigen::MatrixXd& covariance,
                                  const ImportanceOptions& options) {
  check(log_priors, centre, covariance, options);
  RandomStream random(options.seed);
  const int nu = options.degrees_of_freedom;
  const StudentT first(centre, options.pilot_scale * options.pilot_scale * covariance, nu);
  Mixture components{{first}, {}};
  // Two rounds: a pilot from the current mixture, then one adapted component per prior at its
  // posterior's weighted moments from every pilot so far (skipped where they saw too little of that
  // posterior to place it: the first t then serves alone), and with options.defensive a slab for a
  // prior whose posterior is not a single Gaussian-like peak inside its support. Each pilot's
  // weights use its own q (with options.defensive, the balance heuristic over both rounds).
  Batch pilots;
  const auto dim = static_cast<double>(centre.size());
  std::vector<int> defended(log_priors.size(), kNoSlab);  // per prior: its slab's axis
  std::vector<std::size_t> slab_of(log_priors.size(), 0);  // and its index among the slabs
  std::vector<Mixture> rounds;  // each pilot's mixture
  for (int round = 0; round < 2; ++round) {
    append(pilots, draw_batch(components, options.pilot_draws, log_likelihood, log_priors, random, options.threads));
    rounds.push_back(components);
    if (options.defensive) balance(pilots, rounds);
    components = Mixture{{first}, {}};
    for (std::size_t p = 0; p < log_priors.size(); ++p) {
      const ImportanceEstimate e = estimate(pilots, p);
      const Support support = p < options.supports.size() ? options.supports[p] : Support{};
      // Once a round has seen a prior's posterior stray from a peak, later rounds keep its slab (a
      // pilot that has not yet reached a plateau's end can make it look like a peak again).
      const bool before = defended[p] != kNoSlab;
      defended[p] = kNoSlab;
      if (options.defensive && std::isfinite(e.log_evidence) && (before || needs_defence(e, support, dim))) {
        if (std::optional<Slab> slab = defensive_slab(pilots, p, e, support, covariance, options.adapted_scale, nu)) {
          components.slabs.push_back(std::move(*slab));
          defended[p] = components.slabs.back().parameter;
          slab_of[p] = components.slabs.size() - 1;
        }
      }
      if (!(e.effective_draws >= 10.0 * (dim + 1.0))) continue;
      const Eigen::LLT<Eigen::MatrixXd> llt(e.covariance);
      if (llt.info() != Eigen::Success) continue;
      components.t.emplace_back(e.mean, options.adapted_scale * options.adapted_scale * e.covariance, nu);
    }
  }
  const Batch& pilot = pilots;
  Batch all = draw_batch(components, options.draws, log_likelihood, log_priors, random, options.threads);
  ImportanceRun run;
  const auto largest_error = [&] {
    run.priors.clear();
    double worst = 0.0;
    for (std::size_t p = 0; p < log_priors.size(); ++p) {
      run.priors.push_back(estimate(all, p));
      run.priors.back().slab_axis = defended[p];
      if (defended[p] != kNoSlab) {
        run.priors.back().slab_end_mass = end_mass(components.slabs[slab_of[p]], all, run.priors.back());
        run.priors.back().slab_across_spread = across_spread(components.slabs[slab_of[p]], run.priors.back(), covariance);
      }
      if (run.priors.back().pareto_k <= options.draw_on_below_pareto_k) worst = std::max(worst, run.priors.back().uncertainty);
    }
    return worst;
  };
  // More draws from the same mixture while the error of some prior whose k-hat allows an estimate
  // exceeds the target: as many as the error says are needed (it falls as 1/sqrt(N)), at least
  // another `draws`.
  for (double worst = largest_error();
       worst > options.target_uncertainty && static_cast<int>(all.x.size()) < options.max_draws;
       worst = largest_error()) {
    const double wanted = static_cast<double>(all.x.size()) * std::pow(worst / options.target_uncertainty, 2);
    const int more = std::min(options.max_draws - static_cast<int>(all.x.size()),
                              std::max(options.draws, static_cast<int>(std::ceil(wanted)) - static_cast<int>(all.x.size())));
    append(all, draw_batch(components, more, log_likelihood, log_priors, random, options.threads));
  }
  run.draws.resize(static_cast<Eigen::Index>(all.x.size()), centre.size());
  for (std::size_t i = 0; i < all.x.size(); ++i) run.draws.row(static_cast<Eigen::Index>(i)) = all.x[i].transpose();
  run.log_likelihood = Eigen::Map<const Eigen::VectorXd>(all.log_likelihood.data(), static_cast<Eigen::Index>(all.log_likelihood.size()));
  run.evaluations = pilot.evaluations + all.evaluations;
  run.components = static_cast<int>(components.size());
  run.slabs = static_cast<int>(components.slabs.size());
  return run;
}

Eigen::MatrixXd resample(const Eigen::MatrixXd& draws, const Eigen::VectorXd& log_weights, int count,
                         RandomStream& random) {
  if (draws.rows() != log_weights.size() || draws.rows() == 0 || count < 1) {
    throw std::invalid_argument("resample: one weight per draw and at least one draw wanted");
  }
  const double peak = log_weights.maxCoeff();
  if (!std::isfinite(peak)) throw std::invalid_argument("resample: every weight is zero");
  const Eigen::ArrayXd w = (log_weights.array() - peak).exp();
  const double total = w.sum();
  Eigen::MatrixXd out(count, draws.cols());
  const double u = random.uniform();
  double cumulative = w(0) / total;
  Eigen::Index i = 0;
  for (int r = 0; r < count; ++r) {
    const double target = (r + u) / count;
    while (cumulative < target && i + 1 < draws.rows()) cumulative += w(++i) / total;
    out.row(r) = draws.row(i);
  }
  return out;
}

}  // namespace sedwave::sampling
