#pragma once
// Private: a C1 bicubic Hermite surface on a rectilinear grid. Node slopes f_x, f_y and the cross
// slope f_xy come from three-point finite differences (the derivative of the parabola through a node
// and its neighbours; one-sided parabolas at the ends; the secant for two nodes), which reproduces
// quadratics exactly. Along any grid line the surface and its normal derivative depend only on the
// data of that line, so neighbouring cells join with continuous value and gradient.
//
// Nodes marked unusable split rows and columns into independent segments, exactly as if the grid
// ended there; a cell with an unusable corner is never evaluated.
#include <cstddef>
#include <optional>
#include <vector>

namespace sedwave::forward::table {

/// Where a coordinate falls on one axis: between nodes lower and upper at fraction t of width.
/// On a single-node axis lower == upper, t = 0, width = 0.
struct AxisCell {
  std::size_t lower = 0;
  std::size_t upper = 0;
  double t = 0.0;
  double width = 0.0;
};

/// The cell containing v, or nothing outside [axis.front(), axis.back()]. A single-node axis
/// accepts only its node (to 1e-12 relative, so a value read back from text still matches).
[[nodiscard]] std::optional<AxisCell> locate(const std::vector<double>& axis, double v);

struct GridCell {
  AxisCell x;
  AxisCell y;
};

/// Value and gradient of an interpolant at one point.
struct SurfaceSample {
  double value = 0.0;
  double d_x = 0.0;
  double d_y = 0.0;
};

class HermiteSurface {
 public:
  /// values and usable are row-major [iy][ix]; only usable values are read.
  HermiteSurface(const std::vector<double>& x, const std::vector<double>& y, std::vector<double> values,
                 const std::vector<bool>& usable);

  /// The caller guarantees the cell's corners are usable.
  [[nodiscard]] SurfaceSample operator()(const GridCell& cell) const;

 private:
  [[nodiscard]] std::size_t at(std::size_t ix, std::size_t iy) const { return iy * nx_ + ix; }

  std::size_t nx_;
  std::vector<double> f_, f_x_, f_y_, f_xy_;
};

/// Bilinear interpolation of row-major [iy][ix] values in the cell (no derivatives).
[[nodiscard]] double bilinear(const GridCell& cell, const std::vector<double>& values, std::size_t nx);

}  // namespace sedwave::forward::table
