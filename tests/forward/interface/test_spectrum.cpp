// The wavenumber analysis of an interface run: a pure tone along the line puts its energy at its own
// wavenumber with Parseval's total, and the variance's line fit is exact on a line.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sedwave/forward/experiment/interface_spectrum.hpp"

namespace {

using namespace sedwave::forward::experiment;

TEST(WavenumberSpread, ToneSitsAtItsWavenumberWithParsevalsEnergy) {
  const std::size_t n = 256;
  const double spacing = 1e-3, density = 2700.0, thickness = 5e-3;
  const double k0 = 2.0 * std::numbers::pi * 20.0 / (static_cast<double>(n) * spacing);  // bin 20
  InterfaceRun run;
  for (int s = 0; s < 3; ++s) {
    std::vector<double> vx(n), vy(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) vx[i] = (1.0 + s) * std::cos(k0 * spacing * static_cast<double>(i));
    run.line_vx.push_back(vx);
    run.line_vy.push_back(vy);
    run.series.time.push_back(1e-6 * s);
  }
  const WavenumberSpread spread = wavenumber_spread(run, density, thickness, spacing);
  for (std::size_t s = 0; s < 3; ++s) {
    double direct = 0.0;
    for (const double v : run.line_vx[s]) direct += 0.5 * density * thickness * spacing * v * v;
    EXPECT_NEAR(spread.line_energy[s] / direct, 1.0, 1e-12);
    const auto moments = spectrum_moments(spread.k, spread.energy[s]);
    EXPECT_NEAR(moments.mean / k0, 1.0, 1e-12);
    EXPECT_LT(moments.variance, 1e-20 * k0 * k0);
  }
}

TEST(WavenumberSpread, LineFitIsExactOnALine) {
  const std::vector<double> t{0.0, 1.0, 2.0, 5.0};
  std::vector<double> y;
  for (const double x : t) y.push_back(3.0 * x - 2.0);
  const LineFit f = fit_line(t, y);
  EXPECT_NEAR(f.slope, 3.0, 1e-14);
  EXPECT_NEAR(f.intercept, -2.0, 1e-14);
  EXPECT_NEAR(f.r_squared, 1.0, 1e-14);
}

}  // namespace
