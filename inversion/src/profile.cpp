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
    double step = std::clamp(std::isfinite(linear_sigma) && linear_sigma > 0.0 ? linear_sigma : 0.1, 1e-6, 1.0);
    while (!outside) {
      double trial = inside + side * step;
      const bool at_limit = side * (trial - limit) >= 0.0;
      if (at_limit) trial = limit;
      Theta theta = inside_theta;
      if (delta_chi2(trial, theta) >= 1.0) {
        outside = trial;
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
      if (delta_chi2(middle, theta) >= 1.0) {
        outside = middle;
      } else {
        inside = middle;
        inside_theta = theta;
      }
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
