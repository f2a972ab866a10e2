#pragma once
// The log evidence of a two-parameter inversion by brute-force quadrature of the same integral that
// model_evidence estimates (inversion::evidence_integrand): the midpoint rule in the free
// ln-parameters, first on a 200 x 200 grid over the whole prior, then twice zoomed onto the box of
// cells whose integrand is within e^-60 of the largest (widened by two cells, and always holding the
// best fit +- 10 linearised sigma), then on that box at n x n and 2n x 2n. Shared by
// bench/evidence_accuracy.cpp (every model family, many seeds) and tests/inversion/test_coverage.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/sampling/tempering.hpp"

namespace sedwave::bench {

namespace detail {

struct Box {
  double lo[2], hi[2];
};

// ln of the integral of exp(f) over the box by the midpoint rule on n x n cells; with `keep`, also
// the box of cells within `window` of the largest value (widened by two cells); with `marginals`,
// the integrand summed over the other axis, per cell of each axis (relative to the largest cell).
inline double log_integral(const sampling::PriorAndLikelihood& f, const Box& box, int n, Box* keep = nullptr,
                    double window = 60.0, std::vector<double>* marginals = nullptr) {
  const double h0 = (box.hi[0] - box.lo[0]) / n, h1 = (box.hi[1] - box.lo[1]) / n;
  std::vector<double> values(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  double peak = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd x(2);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      x << box.lo[0] + (i + 0.5) * h0, box.lo[1] + (j + 0.5) * h1;
      const double lp = f.log_prior(x);
      const double v = std::isfinite(lp) ? lp + f.log_likelihood(x) : lp;
      values[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)] = v;
      peak = std::max(peak, v);
    }
  }
  double sum = 0.0;
  int lo_i = n, hi_i = -1, lo_j = n, hi_j = -1;
  if (marginals) marginals[0].assign(static_cast<std::size_t>(n), 0.0), marginals[1].assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double v = values[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
      sum += std::exp(v - peak);
      if (marginals) {
        marginals[0][static_cast<std::size_t>(i)] += std::exp(v - peak);
        marginals[1][static_cast<std::size_t>(j)] += std::exp(v - peak);
      }
      if (v >= peak - window) {
        lo_i = std::min(lo_i, i), hi_i = std::max(hi_i, i), lo_j = std::min(lo_j, j), hi_j = std::max(hi_j, j);
      }
    }
  }
  if (keep) {
    keep->lo[0] = std::max(box.lo[0], box.lo[0] + (lo_i - 2) * h0);
    keep->hi[0] = std::min(box.hi[0], box.lo[0] + (hi_i + 3) * h0);
    keep->lo[1] = std::max(box.lo[1], box.lo[1] + (lo_j - 2) * h1);
    keep->hi[1] = std::min(box.hi[1], box.lo[1] + (hi_j + 3) * h1);
  }
  return peak + std::log(sum * h0 * h1);
}

// The shares of the mass of separated modes of a marginal (cells in order): a local maximum is a
// mode of its own where the marginal between it and every higher mode falls below half its
// height; the modes are divided at the lowest cell between neighbours. One mode: {1}.
inline std::vector<double> mode_shares(const std::vector<double>& m) {
  const auto n = static_cast<std::ptrdiff_t>(m.size());
  std::vector<std::ptrdiff_t> peaks;
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if ((i == 0 || m[static_cast<std::size_t>(i)] > m[static_cast<std::size_t>(i - 1)]) &&
        (i == n - 1 || m[static_cast<std::size_t>(i)] >= m[static_cast<std::size_t>(i + 1)])) {
      peaks.push_back(i);
    }
  }
  std::sort(peaks.begin(), peaks.end(), [&](auto a, auto b) { return m[static_cast<std::size_t>(a)] > m[static_cast<std::size_t>(b)]; });
  const auto lowest_between = [&](std::ptrdiff_t a, std::ptrdiff_t b) {
    if (a > b) std::swap(a, b);
    return std::min_element(m.begin() + a, m.begin() + b + 1) - m.begin();
  };
  std::vector<std::ptrdiff_t> modes;
  for (const std::ptrdiff_t p : peaks) {
    const bool separate = std::all_of(modes.begin(), modes.end(), [&](std::ptrdiff_t q) {
      return m[static_cast<std::size_t>(lowest_between(p, q))] < 0.5 * m[static_cast<std::size_t>(p)];
    });
    if (separate) modes.push_back(p);
  }
  std::sort(modes.begin(), modes.end());
  double total = 0.0;
  for (double v : m) total += v;
  std::vector<double> shares;
  std::ptrdiff_t from = 0;
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const std::ptrdiff_t to = k + 1 < modes.size() ? lowest_between(modes[k], modes[k + 1]) : n;
    double part = 0.0;
    for (std::ptrdiff_t i = from; i < to; ++i) part += m[static_cast<std::size_t>(i)];
    shares.push_back(part / total);
    from = to;
  }
  return shares;
}

inline Box hull(Box a, const Box& b) {
  for (int k = 0; k < 2; ++k) a.lo[k] = std::min(a.lo[k], b.lo[k]), a.hi[k] = std::max(a.hi[k], b.hi[k]);
  return a;
}

}  // namespace detail

struct QuadratureEvidence {
  double log_evidence = 0.0;  ///< on the 2n x 2n grid
  double refinement = 0.0;    ///< |2n x 2n - n x n|: the reference's own error
  /// Per free parameter, the mass shares of the separated modes of its marginal (2n x 2n grid), in
  /// the order of the parameter's values; {1} for a single mode.
  std::vector<double> mode_shares[2];
};

/// `f` over the two free parameters of `best` (their search bounds are the prior's support).
inline QuadratureEvidence quadrature_evidence(const sampling::PriorAndLikelihood& f, const inversion::FitResult& best,
                                              int n = 300) {
  using detail::Box;
  const std::vector<int> idx = best.fitted.free_indices();
  Box box{}, around_best{};
  for (int k = 0; k < 2; ++k) {
    const auto& spec = best.fitted.spec[idx[static_cast<std::size_t>(k)]];
    box.lo[k] = std::log(spec.lower);
    box.hi[k] = std::log(spec.upper);
    const auto& r = best.parameters[static_cast<std::size_t>(idx[static_cast<std::size_t>(k)])];
    const double sigma = r.log_sigma > 0.0 && std::isfinite(r.log_sigma) ? r.log_sigma : 0.1;
    around_best.lo[k] = std::max(box.lo[k], std::log(spec.value) - 10.0 * sigma);
    around_best.hi[k] = std::min(box.hi[k], std::log(spec.value) + 10.0 * sigma);
  }
  Box zoom{};
  (void)detail::log_integral(f, box, 200, &zoom);
  zoom = detail::hull(zoom, around_best);
  for (int pass = 0; pass < 2; ++pass) {
    Box next{};
    (void)detail::log_integral(f, zoom, 200, &next);
    zoom = detail::hull(next, around_best);
  }
  const double coarse = detail::log_integral(f, zoom, n);
  std::vector<double> marginals[2];
  const double fine = detail::log_integral(f, zoom, 2 * n, nullptr, 60.0, marginals);
  return {fine, std::abs(fine - coarse), {detail::mode_shares(marginals[0]), detail::mode_shares(marginals[1])}};
}

}  // namespace sedwave::bench
