#include "hermite_surface.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sedwave::forward::table {
namespace {

/// Three-point slopes of f over one run of usable nodes [first, last] of a strided line.
/// `node(i)` maps position i along the line to the flat index.
template <typename Node>
void segment_slopes(const std::vector<double>& axis, const std::vector<double>& f, std::vector<double>& slope,
                    std::size_t first, std::size_t last, Node node) {
  const std::size_t n = last - first + 1;
  auto h = [&](std::size_t i) { return axis[i + 1] - axis[i]; };
  auto secant = [&](std::size_t i) { return (f[node(i + 1)] - f[node(i)]) / h(i); };
  if (n == 1) {
    slope[node(first)] = 0.0;
    return;
  }
  if (n == 2) {
    slope[node(first)] = slope[node(last)] = secant(first);
    return;
  }
  for (std::size_t i = first + 1; i < last; ++i) {
    slope[node(i)] = (h(i - 1) * secant(i) + h(i) * secant(i - 1)) / (h(i - 1) + h(i));
  }
  // One-sided: the derivative at the end of the parabola through the first (last) three nodes.
  const double h0 = h(first), h1 = h(first + 1);
  slope[node(first)] = ((2.0 * h0 + h1) * secant(first) - h0 * secant(first + 1)) / (h0 + h1);
  const double hl = h(last - 1), hm = h(last - 2);
  slope[node(last)] = ((2.0 * hl + hm) * secant(last - 1) - hl * secant(last - 2)) / (hl + hm);
}

/// Slopes along one line (length `count`), run by run of usable nodes.
template <typename Node>
void line_slopes(const std::vector<double>& axis, const std::vector<double>& f, const std::vector<bool>& usable,
                 std::vector<double>& slope, Node node) {
  const std::size_t count = axis.size();
  std::size_t i = 0;
  while (i < count) {
    if (!usable[node(i)]) {
      ++i;
      continue;
    }
    std::size_t last = i;
    while (last + 1 < count && usable[node(last + 1)]) ++last;
    segment_slopes(axis, f, slope, i, last, node);
    i = last + 1;
  }
}

/// Cubic Hermite on [0, 1] scaled to `width`: value and derivative per unit of the coordinate.
std::pair<double, double> hermite(const AxisCell& c, double f0, double f1, double d0, double d1) {
  if (c.lower == c.upper) return {f0, 0.0};  // single-node axis: constant along it
  const double t = c.t, t2 = t * t, t3 = t2 * t;
  const double value = (2.0 * t3 - 3.0 * t2 + 1.0) * f0 + (t3 - 2.0 * t2 + t) * c.width * d0 +
                       (3.0 * t2 - 2.0 * t3) * f1 + (t3 - t2) * c.width * d1;
  const double derivative = (6.0 * t2 - 6.0 * t) * (f0 - f1) / c.width + (3.0 * t2 - 4.0 * t + 1.0) * d0 +
                            (3.0 * t2 - 2.0 * t) * d1;
  return {value, derivative};
}

}  // namespace

std::optional<AxisCell> locate(const std::vector<double>& axis, double v) {
  if (axis.size() == 1) {
    if (std::abs(v - axis[0]) > 1e-12 * std::max(1.0, std::abs(axis[0]))) return std::nullopt;
    return AxisCell{};
  }
  if (!(v >= axis.front() && v <= axis.back())) return std::nullopt;
  const auto above = std::upper_bound(axis.begin(), axis.end(), v);
  const std::size_t lower = std::min(static_cast<std::size_t>(above - axis.begin()) - 1, axis.size() - 2);
  const double width = axis[lower + 1] - axis[lower];
  return AxisCell{lower, lower + 1, (v - axis[lower]) / width, width};
}

HermiteSurface::HermiteSurface(const std::vector<double>& x, const std::vector<double>& y, std::vector<double> values,
                               const std::vector<bool>& usable)
    : nx_(x.size()), f_(std::move(values)), f_x_(f_.size(), 0.0), f_y_(f_.size(), 0.0), f_xy_(f_.size(), 0.0) {
  const std::size_t ny = y.size();
  for (std::size_t iy = 0; iy < ny; ++iy) {
    line_slopes(x, f_, usable, f_x_, [&](std::size_t ix) { return at(ix, iy); });
  }
  for (std::size_t ix = 0; ix < nx_; ++ix) {
    line_slopes(y, f_, usable, f_y_, [&](std::size_t iy) { return at(ix, iy); });
  }
  // Cross slopes: the x-slopes of f_y, so that f_xy on a grid line depends on that line only.
  for (std::size_t iy = 0; iy < ny; ++iy) {
    line_slopes(x, f_y_, usable, f_xy_, [&](std::size_t ix) { return at(ix, iy); });
  }
}

SurfaceSample HermiteSurface::operator()(const GridCell& cell) const {
  const AxisCell& cx = cell.x;
  // Along x on the two bounding y lines: the value with its x-derivative, and the y-slope with its
  // x-derivative. Then along y between those lines.
  std::pair<double, double> g[2], gy[2];
  const std::size_t rows[2] = {cell.y.lower, cell.y.upper};
  for (int q = 0; q < 2; ++q) {
    const std::size_t a = at(cx.lower, rows[q]), b = at(cx.upper, rows[q]);
    g[q] = hermite(cx, f_[a], f_[b], f_x_[a], f_x_[b]);
    gy[q] = hermite(cx, f_y_[a], f_y_[b], f_xy_[a], f_xy_[b]);
  }
  const auto [value, d_y] = hermite(cell.y, g[0].first, g[1].first, gy[0].first, gy[1].first);
  const double d_x = hermite(cell.y, g[0].second, g[1].second, gy[0].second, gy[1].second).first;
  return {value, d_x, d_y};
}

double bilinear(const GridCell& cell, const std::vector<double>& values, std::size_t nx) {
  auto v = [&](std::size_t ix, std::size_t iy) { return values[iy * nx + ix]; };
  const double tx = cell.x.t, ty = cell.y.t;
  const double low = (1.0 - tx) * v(cell.x.lower, cell.y.lower) + tx * v(cell.x.upper, cell.y.lower);
  const double high = (1.0 - tx) * v(cell.x.lower, cell.y.upper) + tx * v(cell.x.upper, cell.y.upper);
  return (1.0 - ty) * low + ty * high;
}

}  // namespace sedwave::forward::table
