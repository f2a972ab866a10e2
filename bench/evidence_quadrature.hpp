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
// the box of cells within `window` of the largest value (widened by two cells).
inline double log_integral(const sampling::PriorAndLikelihood& f, const Box& box, int n, Box* keep = nullptr,
                    double window = 60.0) {
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
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double v = values[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j)];
      sum += std::exp(v - peak);
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

inline Box hull(Box a, const Box& b) {
  for (int k = 0; k < 2; ++k) a.lo[k] = std::min(a.lo[k], b.lo[k]), a.hi[k] = std::max(a.hi[k], b.hi[k]);
  return a;
}

}  // namespace detail

struct QuadratureEvidence {
  double log_evidence = 0.0;  ///< on the 2n x 2n grid
  double refinement = 0.0;    ///< |2n x 2n - n x n|: the reference's own error
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
  const double fine = detail::log_integral(f, zoom, 2 * n);
  return {fine, std::abs(fine - coarse)};
}

}  // namespace sedwave::bench
