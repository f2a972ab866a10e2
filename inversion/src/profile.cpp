#include "profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sedwave::inversion::detail {
namespace {

/// Smallest and largest ln q over the box of free parameters (q is monotone in each ln-parameter,
/// as every profiled quantity is, so the extremes sit at corners).
std::pair<double, double> reachable_range(const Setup& s, const Theta& theta, const ProfiledQuantity& q) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const auto corners = 1u << s.free.size();
  for (unsigned mask = 0; mask < corners; ++mask) {
    Theta corner = theta;
    for (size_t k = 0; k < s.free.size(); ++k) {
      corner[s.free[k]] = (mask >> k) & 1u ? log_upper(s, s.free[k]) : log_lower(s, s.free[k]);
    }
    const double value = log_quantity(s, corner, q).a;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  return {lo, hi};
}

/// `from` moved so that ln q changes by dt along the least-constrained path (see profile.hpp),
/// clamped into the bounds; `from` itself when the Jacobian is not available there.
Theta predicted_start(const Setup& s, const Theta& from, const ProfiledQuantity& q, double dt) {
  Eigen::MatrixXd J;
  try {
    J = whitened_jacobian(s, from);
  } catch (const std::exception&) {
    return from;
  }
  const auto p = static_cast<Eigen::Index>(s.free.size());
  Eigen::MatrixXd H = J.transpose() * J;
  // Regularised so an unseen direction gets a large but finite weight: the step then follows it.
  const double scale = std::max(H.diagonal().maxCoeff(), 1e-300);
  H.diagonal().array() += 1e-10 * scale;
  const Eigen::VectorXd a = free_part(log_quantity(s, from, q).v, s.free);
  const Eigen::VectorXd h = H.ldlt().solve(a);
  const double norm = a.dot(h);
  Theta start = from;
  if (!(norm > 0.0) || !h.allFinite()) return start;
  for (Eigen::Index k = 0; k < p; ++k) {
    const int i = s.free[static_cast<size_t>(k)];
    start[i] = std::clamp(from[i] + h(k) * dt / norm, log_lower(s, i), log_upper(s, i));
  }
  return start;
}

/// chi^2 minimised with ln q held at t, from two starts (profile.hpp); theta returns the minimum.
/// The second start is tried only when the first ends above `enough`: below it, a lower minimum
/// would not change which side of the threshold t lies on.
double conditional_minimum(const Setup& s, Theta& theta, const ProfiledQuantity& q, double t, int max_iterations,
                           double enough) {
  const double dt = t - log_quantity(s, theta, q).a;
  const std::array<Theta, 2> starts{predicted_start(s, theta, q, dt), theta};
  LocalFit best{theta, false, "", std::numeric_limits<double>::infinity()};
  for (Theta start : starts) {
    LocalFit f;
    if (q.parameter >= 0) {
      start[q.parameter] = t;
      f = solve_local(s, start, max_iterations, q.parameter);
    } else {
      const Constraint constraint{q.derived, t};
      f = solve_local(s, start, max_iterations, -1, &constraint);
    }
    if (f.chi2 < best.chi2) best = f;
    if (best.chi2 < enough) break;
  }
  theta = best.theta;
  return best.chi2;
}

/// An orthonormal basis of the steps orthogonal to every column of `held` (each a direction the step
/// must not move along); every step where there are none.
Eigen::MatrixXd steps_orthogonal_to(const Eigen::MatrixXd& held) {
  const auto p = held.rows();
  if (held.cols() == 0 || !(held.squaredNorm() > 0.0)) return Eigen::MatrixXd::Identity(p, p);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(held, Eigen::ComputeFullU);
  Eigen::Index rank = 0;
  const double largest = svd.singularValues()(0);
  for (Eigen::Index k = 0; k < svd.singularValues().size(); ++k) rank += svd.singularValues()(k) > 1e-12 * largest;
  return svd.matrixU().rightCols(p - rank);
}

/// How far chi^2 ~ chi^2 + 2 g.delta + delta^T J^T J delta (g = J^T r, the Gauss-Newton model about
/// a point) falls over the steps delta = Z z. Along each principal direction of the curvature there
/// (eigenvalue c, g's component m) a step is taken at most 1 in ln units, as far as the profile
/// itself steps: the fall is m^2 / c within that, 2 |m| - c beyond. The cap keeps a direction the
/// data barely see (c ~ 0, m ~ the solver's tolerance) from promising a fall that only a step of
/// decades could bring.
double model_fall(const Eigen::MatrixXd& J, const Eigen::VectorXd& g, const Eigen::MatrixXd& Z) {
  if (Z.cols() == 0) return 0.0;
  constexpr double kLargestStep = 1.0;
  const Eigen::MatrixXd JZ = J * Z;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> curvature(JZ.transpose() * JZ);
  const Eigen::VectorXd along = curvature.eigenvectors().transpose() * (Z.transpose() * g);
  double fall = 0.0;
  for (Eigen::Index k = 0; k < along.size(); ++k) {
    const double c = std::max(curvature.eigenvalues()(k), 0.0), m = std::abs(along(k));
    fall += m < c * kLargestStep ? m * m / c : 2.0 * m * kLargestStep - c * kLargestStep * kLargestStep;
  }
  return fall;
}

}  // namespace

double fall_if_bounds_released(const Setup& s, const Theta& theta, const ProfiledQuantity* held) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(s.residual_count));
  Eigen::MatrixXd jacobian;
  if (!residuals_at(s, theta, r.data(), &jacobian) || !r.allFinite() || !jacobian.allFinite()) return 0.0;
  const auto p = static_cast<Eigen::Index>(s.free.size());
  Eigen::MatrixXd J(r.size(), p);
  for (Eigen::Index k = 0; k < p; ++k) J.col(k) = jacobian.col(s.free[static_cast<size_t>(k)]);
  const Eigen::VectorXd g = J.transpose() * r;  // half the gradient of chi^2
  // Directions every step keeps fixed: ln q's gradient (q held), then each parameter a bound holds
  // (on it, with chi^2 falling outwards; the held parameter is not one).
  constexpr double kOnBound = 1e-9;  // ln units: the solver leaves a bound parameter exactly on it
  Eigen::MatrixXd fixed(p, p + 1);
  Eigen::Index columns = 0;
  if (held) fixed.col(columns++) = free_part(log_quantity(s, theta, *held).v, s.free);
  const Eigen::Index unbound_columns = columns;
  for (Eigen::Index k = 0; k < p; ++k) {
    const int i = s.free[static_cast<size_t>(k)];
    if (held && held->parameter == i) continue;
    const bool on_lower = theta[i] <= log_lower(s, i) + kOnBound && g(k) > 0.0;
    const bool on_upper = theta[i] >= log_upper(s, i) - kOnBound && g(k) < 0.0;
    if (on_lower || on_upper) fixed.col(columns++) = Eigen::VectorXd::Unit(p, k);
  }
  if (columns == unbound_columns) return 0.0;
  // The fall with the bound parameters free to step beyond their bounds, less the fall without: what
  // the solver's tolerance leaves along the other directions is in both, and cancels.
  const double released = model_fall(J, g, steps_orthogonal_to(fixed.leftCols(unbound_columns)));
  const double bound = model_fall(J, g, steps_orthogonal_to(fixed.leftCols(columns)));
  const double fall = released - bound;
  return std::isfinite(fall) ? std::max(fall, 0.0) : 0.0;
}

namespace {

/// Walks from t towards the limit in steps of at most 1 (ln units) until Delta chi^2 >= 4.
template <typename DeltaChi2>
bool passes_two_sigma(double t, Theta theta, double limit, int side, DeltaChi2& delta_chi2) {
  while (side * (limit - t) > 1e-9) {
    t = side < 0 ? std::max(limit, t - 1.0) : std::min(limit, t + 1.0);
    if (delta_chi2(t, theta, 4.0) >= 4.0) return true;
  }
  return false;
}

}  // namespace

Differentiated log_quantity(const Setup& s, const Theta& theta, const ProfiledQuantity& q) {
  if (q.derived) return q.derived->log_value(s, theta);
  Differentiated own{theta[q.parameter], Eigen::VectorXd::Zero(static_cast<Eigen::Index>(theta.size()))};
  own.v(q.parameter) = 1.0;
  return own;
}

Profile profile(const Setup& s, const Theta& best, double chi2_min, const ProfiledQuantity& q, double linear_sigma,
                int max_iterations) {
  Profile result;
  const double t_best = log_quantity(s, best, q).a;
  const auto [reach_lo, reach_hi] = reachable_range(s, best, q);
  const double improvement = std::max(1e-3, 1e-9 * chi2_min);
  const double fall_at_best = fall_if_bounds_released(s, best, nullptr);
  auto delta_chi2 = [&](double t, Theta& theta, double threshold = 1.0) {
    const double chi2 = conditional_minimum(s, theta, q, t, max_iterations, chi2_min + threshold);
    if (chi2 < chi2_min - improvement && (!result.better || chi2 < result.better_chi2)) {
      result.better = theta;
      result.better_chi2 = chi2;
    }
    return chi2 - chi2_min;
  };
  for (int side : {-1, +1}) {
    const double limit = side < 0 ? reach_lo : reach_hi;
    double inside = t_best;
    Theta inside_theta = best;
    std::optional<double> outside;
    Theta outside_theta;
    double outside_delta = 0.0;
    double step = std::clamp(std::isfinite(linear_sigma) && linear_sigma > 0.0 ? linear_sigma : 0.1, 1e-6, 1.0);
    while (!outside) {
      double trial = inside + side * step;
      const bool at_limit = side * (trial - limit) >= 0.0;
      if (at_limit) trial = limit;
      Theta theta = inside_theta;
      if (const double delta = delta_chi2(trial, theta); delta >= 1.0) {
        outside = trial;
        outside_theta = std::move(theta);
        outside_delta = delta;
      } else if (at_limit) {
        break;  // open: chi^2 stays within 1 of its minimum up to the bound
      } else {
        inside = trial;
        inside_theta = theta;
        step = std::min(2.0 * step, 1.0);
      }
    }
    if (!outside) {
      result.bounded_at_2_sigma = false;
      continue;
    }
    // Bisection on Delta chi^2 = 1, each step from the nearest minimum inside, to 1 % of the
    // interval's half-width (a sound speed known to 0.04 % needs far finer steps than a grain size).
    const double tolerance = std::min(2e-3, 0.01 * std::abs(*outside - t_best));
    while (std::abs(*outside - inside) > tolerance) {
      const double middle = 0.5 * (inside + *outside);
      Theta theta = inside_theta;
      if (const double delta = delta_chi2(middle, theta); delta >= 1.0) {
        outside = middle;
        outside_theta = std::move(theta);
        outside_delta = delta;
      } else {
        inside = middle;
        inside_theta = theta;
      }
    }
    // Where the search bounds of the other parameters, not the data, raised most of chi^2 (a
    // ridge that runs on past another parameter's bound), the data leave this side open.
    if (fall_if_bounds_released(s, outside_theta, &q) - fall_at_best > 0.5 * outside_delta) {
      result.bounded_at_2_sigma = false;
      continue;
    }
    (side < 0 ? result.lower : result.upper) = 0.5 * (inside + *outside);
    // A profile can close at 1 sigma and still flatten out towards the bound (a weak preference for a
    // finite value, as noise can fake): demand that it pass Delta chi^2 = 4 before the bound, walking
    // there in the same bounded steps.
    if (!passes_two_sigma(inside, inside_theta, limit, side, delta_chi2)) result.bounded_at_2_sigma = false;
  }
  return result;
}

}  // namespace sedwave::inversion::detail
