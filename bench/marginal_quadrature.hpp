#pragma once
// Each free parameter's marginal 95 % central interval of a posterior with 2 or 3 free parameters,
// by brute-force quadrature of the same density that the sampler draws from
// (inversion::evidence_integrand: ln prior + ln L over the free ln-parameters): the midpoint rule on
// n^k cells, first over the whole prior box, then on the box of cells within e^-40 of the largest
// (widened by two cells), at a finer n. The marginal is the sum over the other axes; its quantiles
// are interpolated linearly inside a cell. A reference for bench/posterior_defaults.cpp, independent
// of any sampler: on a ridge that the priors bound, a sampler that stopped short of the ridge's far
// end gives narrower intervals.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/sampling/tempering.hpp"

namespace sedwave::bench {

struct MarginalBox {
  std::vector<double> lo, hi;  ///< per free parameter, ln units
};

struct MarginalIntervals {
  std::vector<double> lower_95, upper_95;  ///< per free parameter, ln units
  MarginalBox kept;                        ///< the cells within e^-40 of the largest, widened by two
  MarginalBox box;                         ///< the box these intervals integrated over
  /// Per free parameter: the interval's width moved by at most 5 % (and 0.05) between the last two
  /// grids. Where it moved more, the cells are coarser than the posterior (a ridge thinner than a
  /// cell, e.g. across kappa d gamma of the dry chain) and the width is no reference.
  std::vector<bool> resolved;
};

namespace detail {

/// The p-quantile of a density given as masses of n equal cells over [lo, hi], linear inside a cell.
inline double quantile_of_cells(const std::vector<double>& mass, double lo, double hi, double p) {
  const double h = (hi - lo) / static_cast<double>(mass.size());
  double total = 0.0;
  for (const double m : mass) total += m;
  double below = 0.0;
  for (std::size_t i = 0; i < mass.size(); ++i) {
    if (below + mass[i] >= p * total) return lo + h * (static_cast<double>(i) + (p * total - below) / mass[i]);
    below += mass[i];
  }
  return hi;
}

/// Cells first..last of width h from lo (those within e^-40 of the largest), widened by two cells
/// on each side and kept inside [lo, hi].
inline std::pair<double, double> kept_span(double lo, double hi, double h, int first, int last) {
  return {std::max(lo, lo + (first - 2) * h), std::min(hi, lo + (last + 3) * h)};
}

inline MarginalIntervals marginal_intervals_on(const sampling::PriorAndLikelihood& f, const MarginalBox& box, int n) {
  const std::size_t k = box.lo.size();
  std::size_t cells = 1;
  for (std::size_t a = 0; a < k; ++a) cells *= static_cast<std::size_t>(n);
  std::vector<double> h(k), values(cells);
  for (std::size_t a = 0; a < k; ++a) h[a] = (box.hi[a] - box.lo[a]) / n;
  const auto coordinate = [&](std::size_t cell, std::size_t a) {
    for (std::size_t b = k - 1; b > a; --b) cell /= static_cast<std::size_t>(n);
    return static_cast<int>(cell % static_cast<std::size_t>(n));
  };
  double peak = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd x(static_cast<Eigen::Index>(k));
  for (std::size_t cell = 0; cell < cells; ++cell) {
    for (std::size_t a = 0; a < k; ++a) {
      x(static_cast<Eigen::Index>(a)) = box.lo[a] + (coordinate(cell, a) + 0.5) * h[a];
    }
    const double lp = f.log_prior(x);
    values[cell] = std::isfinite(lp) ? lp + f.log_likelihood(x) : lp;
    peak = std::max(peak, values[cell]);
  }
  std::vector<std::vector<double>> marginal(k, std::vector<double>(static_cast<std::size_t>(n), 0.0));
  std::vector<int> first(k, n), last(k, -1);
  for (std::size_t cell = 0; cell < cells; ++cell) {
    const double weight = std::exp(values[cell] - peak);
    for (std::size_t a = 0; a < k; ++a) {
      const int i = coordinate(cell, a);
      marginal[a][static_cast<std::size_t>(i)] += weight;
      if (values[cell] >= peak - 40.0) {
        first[a] = std::min(first[a], i);
        last[a] = std::max(last[a], i);
      }
    }
  }
  MarginalIntervals out;
  out.box = box;
  for (std::size_t a = 0; a < k; ++a) {
    out.lower_95.push_back(quantile_of_cells(marginal[a], box.lo[a], box.hi[a], 0.025));
    out.upper_95.push_back(quantile_of_cells(marginal[a], box.lo[a], box.hi[a], 0.975));
    const auto [lo, hi] = kept_span(box.lo[a], box.hi[a], h[a], first[a], last[a]);
    out.kept.lo.push_back(lo);
    out.kept.hi.push_back(hi);
  }
  return out;
}

}  // namespace detail

/// `f` over the free parameters of `best` (2 or 3; their search bounds are the prior's support):
/// n_whole cells per axis over the whole box, then n_zoom and 3/2 n_zoom on the box that holds the
/// posterior (the finer grid's intervals, and whether the two agree).
inline MarginalIntervals marginal_intervals_by_quadrature(const sampling::PriorAndLikelihood& f,
                                                          const inversion::FitResult& best, int n_whole = 64,
                                                          int n_zoom = 80) {
  const std::vector<int> free = best.fitted.free_indices();
  if (free.size() < 2 || free.size() > 3) throw std::invalid_argument("marginal quadrature: 2 or 3 free parameters");
  MarginalBox box;
  for (const int i : free) {
    box.lo.push_back(std::log(best.fitted.spec[static_cast<std::size_t>(i)].lower));
    box.hi.push_back(std::log(best.fitted.spec[static_cast<std::size_t>(i)].upper));
  }
  const MarginalBox zoom = detail::marginal_intervals_on(f, box, n_whole).kept;
  const MarginalIntervals coarse = detail::marginal_intervals_on(f, zoom, n_zoom);
  MarginalIntervals fine = detail::marginal_intervals_on(f, zoom, 3 * n_zoom / 2);
  for (std::size_t a = 0; a < free.size(); ++a) {
    const double width = fine.upper_95[a] - fine.lower_95[a];
    const double moved = std::abs(width - (coarse.upper_95[a] - coarse.lower_95[a]));
    fine.resolved.push_back(moved <= std::max(0.05 * width, 0.05));
  }
  return fine;
}

namespace detail {

/// ln of the integral of exp(f) over axes b, c of `box` with axis a held at x_a: the midpoint rule on
/// n_coarse^2 cells, then on the cells within e^-40 of the largest (widened by two) at n_fine^2.
inline double log_slice_integral(const sampling::PriorAndLikelihood& f, const MarginalBox& box, std::size_t a,
                                 double x_a, int n_coarse, int n_fine) {
  const std::size_t b = (a + 1) % 3, c = (a + 2) % 3;
  Eigen::VectorXd x(3);
  x(static_cast<Eigen::Index>(a)) = x_a;
  const auto grid = [&](double lo_b, double hi_b, double lo_c, double hi_c, int n, double* keep) {
    const double hb = (hi_b - lo_b) / n, hc = (hi_c - lo_c) / n;
    std::vector<double> v(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    double peak = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        x(static_cast<Eigen::Index>(b)) = lo_b + (i + 0.5) * hb;
        x(static_cast<Eigen::Index>(c)) = lo_c + (j + 0.5) * hc;
        const double lp = f.log_prior(x);
        const double value = std::isfinite(lp) ? lp + f.log_likelihood(x) : lp;
        v[static_cast<std::size_t>(i * n + j)] = value;
        peak = std::max(peak, value);
      }
    }
    if (!std::isfinite(peak)) return -std::numeric_limits<double>::infinity();
    double sum = 0.0;
    int lo_i = n, hi_i = -1, lo_j = n, hi_j = -1;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double value = v[static_cast<std::size_t>(i * n + j)];
        sum += std::exp(value - peak);
        if (value >= peak - 40.0) {
          lo_i = std::min(lo_i, i);
          hi_i = std::max(hi_i, i);
          lo_j = std::min(lo_j, j);
          hi_j = std::max(hi_j, j);
        }
      }
    }
    if (keep) {
      std::tie(keep[0], keep[1]) = kept_span(lo_b, hi_b, hb, lo_i, hi_i);
      std::tie(keep[2], keep[3]) = kept_span(lo_c, hi_c, hc, lo_j, hi_j);
    }
    return peak + std::log(sum * hb * hc);
  };
  double keep[4];
  if (!std::isfinite(grid(box.lo[b], box.hi[b], box.lo[c], box.hi[c], n_coarse, keep))) {
    return -std::numeric_limits<double>::infinity();
  }
  return grid(keep[0], keep[1], keep[2], keep[3], n_fine, nullptr);
}

}  // namespace detail

/// For 3 free parameters: each one's 95 % interval from its marginal density at n_slices points
/// across `box` (e.g. MarginalIntervals::box), each point's density the 2D integral over the other
/// two parameters on a grid zoomed onto that slice (log_slice_integral). Finer where the posterior
/// is a thin sheet or tongue that a cube of cells cannot resolve.
inline MarginalIntervals marginal_intervals_by_slices(const sampling::PriorAndLikelihood& f, const MarginalBox& box,
                                                      int n_slices = 80, int n_coarse = 48, int n_fine = 160) {
  MarginalIntervals out;
  out.box = box;
  for (std::size_t a = 0; a < 3; ++a) {
    const double h = (box.hi[a] - box.lo[a]) / n_slices;
    std::vector<double> log_density(static_cast<std::size_t>(n_slices));
    double peak = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n_slices; ++i) {
      log_density[static_cast<std::size_t>(i)] =
          detail::log_slice_integral(f, box, a, box.lo[a] + (i + 0.5) * h, n_coarse, n_fine);
      peak = std::max(peak, log_density[static_cast<std::size_t>(i)]);
    }
    std::vector<double> mass;
    for (const double l : log_density) mass.push_back(std::exp(l - peak));
    out.lower_95.push_back(detail::quantile_of_cells(mass, box.lo[a], box.hi[a], 0.025));
    out.upper_95.push_back(detail::quantile_of_cells(mass, box.lo[a], box.hi[a], 0.975));
    out.resolved.push_back(true);
  }
  out.kept = box;
  return out;
}

}  // namespace sedwave::bench
