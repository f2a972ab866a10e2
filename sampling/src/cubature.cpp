#include "sedwave/sampling/cubature.hpp"

#include "minus_infinity.hpp"

#include <cubature.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace sedwave::sampling {
namespace {

/// The cell [nodes[i], nodes[i + 1]] that holds x (x inside the nodes' span).
std::size_t cell_of(const std::vector<double>& edges, double x) {
  const auto it = std::upper_bound(edges.begin(), edges.end(), x);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - edges.begin() - 1, 0));
  return std::min(i, edges.size() - 2);
}

/// What the integrand of one sub-box needs: the columns active there (priors whose support holds
/// it) and the map of the sub-box's own unit cube onto its part of the axes' [0, 1].
struct BoxIntegrand {
  const LogDensity* log_likelihood = nullptr;
  const std::vector<LogDensity>* log_priors = nullptr;
  const std::vector<AxisMap>* axes = nullptr;
  std::vector<std::size_t> active;
  Eigen::VectorXd u_lower, u_upper;
  double log_scale = 0.0;
  int threads = 1;
  long evaluations = 0;
};

/// hcubature_v's integrand: L pi_p / prod g at each point, times the sub-box's volume in u.
int integrand_of_box(unsigned dim, std::size_t points, const double* u, void* data, unsigned columns, double* values) {
  auto& box = *static_cast<BoxIntegrand*>(data);
  const auto d = static_cast<Eigen::Index>(dim);
  const auto n = static_cast<Eigen::Index>(points);
  Eigen::MatrixXd x(d, n);
  Eigen::VectorXd log_volume_element = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd log_prior(static_cast<Eigen::Index>(columns), n);
  std::vector<Eigen::Index> to_evaluate;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < d; ++j) {
      const double width = box.u_upper(j) - box.u_lower(j);
      const AxisMap& axis = (*box.axes)[static_cast<std::size_t>(j)];
      x(j, i) = axis.at(box.u_lower(j) + width * u[i * d + j]);
      log_volume_element(i) += std::log(width) - std::log(axis.density(x(j, i)));
    }
    bool any = false;
    for (unsigned c = 0; c < columns; ++c) {
      log_prior(c, i) = (*box.log_priors)[box.active[c]](x.col(i));
      any = any || std::isfinite(log_prior(c, i));
    }
    if (any) to_evaluate.push_back(i);
  }
  Eigen::VectorXd log_likelihood = Eigen::VectorXd::Constant(n, kMinusInfinity);
  const auto m = static_cast<int>(to_evaluate.size());
#pragma omp parallel for schedule(dynamic) num_threads(box.threads) if (box.threads > 1)
  for (int k = 0; k < m; ++k) {
    const Eigen::Index i = to_evaluate[static_cast<std::size_t>(k)];
    const double v = (*box.log_likelihood)(x.col(i));
    log_likelihood(i) = std::isnan(v) ? kMinusInfinity : v;
  }
  box.evaluations += m;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (unsigned c = 0; c < columns; ++c) {
      const double log_value = log_likelihood(i) + log_prior(c, i) + log_volume_element(i) - box.log_scale;
      values[i * columns + c] = std::isfinite(log_value) ? std::exp(log_value) : 0.0;
    }
  }
  return 0;
}

/// Per axis, the u of every support's ends strictly inside (0, 1) and of `splits` equal pieces:
/// where sub-boxes meet.
std::vector<std::vector<double>> cuts_of(const std::vector<AxisMap>& axes, const std::vector<Support>& supports,
                                         int splits) {
  std::vector<std::vector<double>> cuts(axes.size());
  for (std::size_t j = 0; j < axes.size(); ++j) {
    for (int i = 0; i <= splits; ++i) cuts[j].push_back(static_cast<double>(i) / splits);
    for (const Support& s : supports) {
      const auto jj = static_cast<Eigen::Index>(j);
      for (const double end : {s.lower(jj), s.upper(jj)}) {
        if (end < axes[j].lower() - 1e-12 * std::abs(axes[j].lower()) ||
            end > axes[j].upper() + 1e-12 * std::abs(axes[j].upper())) {
          throw std::invalid_argument("cubature_evidence: a prior's support reaches outside the axes' box");
        }
        const double u = axes[j].cdf(end);
        if (u > 1e-12 && u < 1.0 - 1e-12) cuts[j].push_back(u);
      }
    }
    std::sort(cuts[j].begin(), cuts[j].end());
    cuts[j].erase(std::unique(cuts[j].begin(), cuts[j].end()), cuts[j].end());
  }
  return cuts;
}

bool inside(const Support& s, const Eigen::VectorXd& x) {
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    if (x(j) < s.lower(j) || x(j) > s.upper(j)) return false;
  }
  return true;
}

struct Box {
  Eigen::VectorXd u_lower, u_upper;
  std::vector<std::size_t> active;
};

/// Every sub-box with at least one prior active, those where most priors are active first.
std::vector<Box> boxes_of(const std::vector<AxisMap>& axes, const std::vector<Support>& supports, int splits) {
  const std::vector<std::vector<double>> cuts = cuts_of(axes, supports, splits);
  const auto d = static_cast<Eigen::Index>(axes.size());
  std::vector<Box> out;
  std::vector<std::size_t> index(axes.size(), 0);
  while (true) {
    Box b{Eigen::VectorXd(d), Eigen::VectorXd(d), {}};
    Eigen::VectorXd centre(d);
    for (Eigen::Index j = 0; j < d; ++j) {
      const auto& c = cuts[static_cast<std::size_t>(j)];
      b.u_lower(j) = c[index[static_cast<std::size_t>(j)]];
      b.u_upper(j) = c[index[static_cast<std::size_t>(j)] + 1];
      centre(j) = axes[static_cast<std::size_t>(j)].at(0.5 * (b.u_lower(j) + b.u_upper(j)));
    }
    for (std::size_t p = 0; p < supports.size(); ++p) {
      if (inside(supports[p], centre)) b.active.push_back(p);
    }
    if (!b.active.empty()) out.push_back(b);
    std::size_t j = 0;
    while (j < index.size() && ++index[j] + 1 == cuts[j].size()) index[j++] = 0;
    if (j == index.size()) break;
  }
  std::stable_sort(out.begin(), out.end(), [](const Box& a, const Box& b) { return a.active.size() > b.active.size(); });
  return out;
}

}  // namespace

AxisMap::AxisMap(std::vector<double> nodes, std::vector<double> density)
    : nodes_(std::move(nodes)), density_(std::move(density)) {
  if (nodes_.size() < 2 || density_.size() != nodes_.size()) {
    throw std::invalid_argument("AxisMap: at least two nodes, one density per node");
  }
  cdf_.assign(nodes_.size(), 0.0);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (!(density_[i] > 0.0) || !std::isfinite(density_[i]) || !std::isfinite(nodes_[i])) {
      throw std::invalid_argument("AxisMap: every density must be positive and finite, every node finite");
    }
    if (i > 0) {
      if (!(nodes_[i] > nodes_[i - 1])) throw std::invalid_argument("AxisMap: the nodes must increase strictly");
      cdf_[i] = cdf_[i - 1] + 0.5 * (density_[i] + density_[i - 1]) * (nodes_[i] - nodes_[i - 1]);
    }
  }
  const double total = cdf_.back();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    cdf_[i] /= total;
    density_[i] /= total;
  }
  cdf_.back() = 1.0;
}

double AxisMap::at(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  const std::size_t i = cell_of(cdf_, u);
  const double h = nodes_[i + 1] - nodes_[i];
  const double c = u - cdf_[i];
  // Solve h (d0 t + (d1 - d0) t^2 / 2) = c for t in [0, 1] (the stable root).
  const double a = 0.5 * h * (density_[i + 1] - density_[i]), b = h * density_[i];
  const double t = 2.0 * c / (b + std::sqrt(std::max(b * b + 4.0 * a * c, 0.0)));
  return std::clamp(nodes_[i] + h * t, nodes_[i], nodes_[i + 1]);
}

double AxisMap::density(double x) const {
  if (x < nodes_.front() || x > nodes_.back()) return 0.0;
  const std::size_t i = cell_of(nodes_, x);
  const double t = (x - nodes_[i]) / (nodes_[i + 1] - nodes_[i]);
  return density_[i] + t * (density_[i + 1] - density_[i]);
}

double AxisMap::cdf(double x) const {
  if (x <= nodes_.front()) return 0.0;
  if (x >= nodes_.back()) return 1.0;
  const std::size_t i = cell_of(nodes_, x);
  const double dx = x - nodes_[i];
  return cdf_[i] + dx * 0.5 * (density_[i] + density(x));  // the trapezoid is exact for a linear density
}

CubatureRun cubature_evidence(const LogDensity& log_likelihood, const std::vector<LogDensity>& log_priors,
                              const std::vector<AxisMap>& axes, double log_scale, const std::vector<Support>& supports,
                              const CubatureOptions& options, const std::vector<double>& reference_log_evidence) {
  if (log_priors.empty()) throw std::invalid_argument("cubature_evidence: no priors");
  if (axes.empty()) throw std::invalid_argument("cubature_evidence: no axes");
  if (!(options.relative_error > 0.0) || options.max_evaluations < 1 || options.threads < 1 || options.splits < 1) {
    throw std::invalid_argument("cubature_evidence: relative_error must be positive, max_evaluations, splits and "
                                "threads at least 1");
  }
  const auto d = static_cast<Eigen::Index>(axes.size());
  std::vector<Support> all = supports;
  for (std::size_t p = all.size(); p < log_priors.size(); ++p) {
    all.push_back({Eigen::VectorXd(d), Eigen::VectorXd(d)});
    for (Eigen::Index j = 0; j < d; ++j) {
      all.back().lower(j) = axes[static_cast<std::size_t>(j)].lower();
      all.back().upper(j) = axes[static_cast<std::size_t>(j)].upper();
    }
  }
  all.resize(log_priors.size());
  const std::vector<Box> boxes = boxes_of(axes, all, options.splits);
  std::vector<double> value(log_priors.size(), 0.0), error(log_priors.size(), 0.0);
  CubatureRun run;
  run.converged = true;
  for (const Box& box : boxes) {
    BoxIntegrand integrand{&log_likelihood, &log_priors, &axes, box.active, box.u_lower, box.u_upper,
                           log_scale, options.threads, 0};
    const auto columns = static_cast<unsigned>(integrand.active.size());
    // An absolute target from the reference where every active column has one, else relative.
    double absolute = std::numeric_limits<double>::infinity();
    for (std::size_t p : integrand.active) {
      const double reference = p < reference_log_evidence.size() ? reference_log_evidence[p] : NAN;
      absolute = std::isfinite(reference)
                     ? std::min(absolute, options.relative_error * std::exp(reference - log_scale) /
                                              static_cast<double>(boxes.size()))
                     : 0.0;
    }
    const double relative = absolute > 0.0 ? 0.0 : options.relative_error;
    std::vector<double> val(columns), err(columns);
    const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(d), ones = Eigen::VectorXd::Ones(d);
    const long left = options.max_evaluations - run.evaluations;
    if (left <= 0) {
      run.converged = false;
      break;
    }
    const int status = hcubature_v(columns, integrand_of_box, &integrand, static_cast<unsigned>(d), zeros.data(),
                                   ones.data(), static_cast<std::size_t>(left), absolute, relative, ERROR_INDIVIDUAL,
                                   val.data(), err.data());
    run.evaluations += integrand.evaluations;
    if (status != 0) throw std::runtime_error("cubature_evidence: hcubature failed");
    for (unsigned c = 0; c < columns; ++c) {
      value[integrand.active[c]] += val[c];
      error[integrand.active[c]] += err[c];
    }
  }
  run.boxes = static_cast<int>(boxes.size());
  for (std::size_t p = 0; p < log_priors.size(); ++p) {
    const bool positive = value[p] > 0.0;
    run.priors.push_back({positive ? std::log(value[p]) + log_scale : kMinusInfinity,
                          positive ? error[p] / value[p] : std::numeric_limits<double>::infinity()});
    if (!(positive && error[p] <= options.relative_error * value[p])) run.converged = false;
  }
  return run;
}

MappedSample mapped_importance(const LogDensity& log_likelihood, const std::vector<LogDensity>& log_priors,
                               const std::vector<AxisMap>& axes, int count, std::uint64_t seed, int threads) {
  if (log_priors.empty() || axes.empty() || count < 2) {
    throw std::invalid_argument("mapped_importance: priors, axes and at least two draws wanted");
  }
  RandomStream random(seed);
  const auto d = static_cast<Eigen::Index>(axes.size());
  MappedSample out{Eigen::MatrixXd(count, d), Eigen::VectorXd::Constant(count, kMinusInfinity), {}, 0};
  Eigen::VectorXd log_proposal = Eigen::VectorXd::Zero(count);
  Eigen::MatrixXd log_prior(count, static_cast<Eigen::Index>(log_priors.size()));
  std::vector<Eigen::Index> to_evaluate;
  for (Eigen::Index i = 0; i < count; ++i) {
    for (Eigen::Index j = 0; j < d; ++j) {
      const AxisMap& axis = axes[static_cast<std::size_t>(j)];
      out.draws(i, j) = axis.at(random.uniform());
      log_proposal(i) += std::log(axis.density(out.draws(i, j)));
    }
    bool any = false;
    for (std::size_t p = 0; p < log_priors.size(); ++p) {
      log_prior(i, static_cast<Eigen::Index>(p)) = log_priors[p](out.draws.row(i).transpose());
      any = any || std::isfinite(log_prior(i, static_cast<Eigen::Index>(p)));
    }
    if (any) to_evaluate.push_back(i);
  }
  const auto m = static_cast<int>(to_evaluate.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads) if (threads > 1)
  for (int k = 0; k < m; ++k) {
    const Eigen::Index i = to_evaluate[static_cast<std::size_t>(k)];
    const double v = log_likelihood(out.draws.row(i).transpose());
    out.log_likelihood(i) = std::isnan(v) ? kMinusInfinity : v;
  }
  out.evaluations = m;
  for (std::size_t p = 0; p < log_priors.size(); ++p) {
    Eigen::VectorXd log_w(count);
    for (Eigen::Index i = 0; i < count; ++i) {
      const double v = out.log_likelihood(i) + log_prior(i, static_cast<Eigen::Index>(p)) - log_proposal(i);
      log_w(i) = std::isfinite(v) ? v : kMinusInfinity;
    }
    out.priors.push_back(weighted_estimate(out.draws, log_w));
  }
  return out;
}

}  // namespace sedwave::sampling
