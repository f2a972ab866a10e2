// A single row of beads (a 1D Hertz chain) against an independent Dormand-Prince 5(4) integration
// written here, Nesterenko's solitary-wave speed, and the convergence of the adaptive step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;
using sedwave::forward::plate::PlateEdges;
using sedwave::forward::plate::PlateMaterial;

double hertz_k() {  // k_h = (4/3) E* sqrt(R*) of two beads
  const double e_star = sedwave::forward::hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                                  steel.youngs_modulus, steel.poisson_ratio);
  return (4.0 / 3.0) * e_star * std::sqrt(0.5 * bead_radius);
}

// The chain's equations m y_i'' = k [delta_(i-1,i)]_+^(3/2) - k [delta_(i,i+1)]_+^(3/2) in the
// displacements from the initial (touching) state, delta_(i,i+1) = w_i - w_(i+1); state (w, w').
std::vector<double> chain_rhs(const std::vector<double>& s, double k, double m) {
  const std::size_t n = s.size() / 2;
  std::vector<double> ds(s.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) ds[i] = s[n + i];
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double overlap = s[i] - s[i + 1];
    if (overlap <= 0.0) continue;
    const double f = k * overlap * std::sqrt(overlap);
    ds[n + i] -= f / m;
    ds[n + i + 1] += f / m;
  }
  return ds;
}

// Dormand & Prince (1980) 5(4) with the usual step control (Hairer, Norsett & Wanner, Solving ODEs I,
// sec. II.4-5): error per component against atol_i + rtol |y_i|, factor 0.9 err^(-1/5) in [0.2, 5].
std::vector<double> dormand_prince(std::vector<double> y, double t_end, double k, double m,
                                   const std::vector<double>& atol, double rtol) {
  static constexpr double c[7] = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
  static constexpr double a[7][6] = {{},
                                     {1.0 / 5},
                                     {3.0 / 40, 9.0 / 40},
                                     {44.0 / 45, -56.0 / 15, 32.0 / 9},
                                     {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
                                     {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
                                     {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  static constexpr double b5[7] = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  static constexpr double b4[7] = {5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100,
                                   1.0 / 40};
  (void)c;  // autonomous system
  double t = 0.0, h = t_end * 1e-6;
  const std::size_t n = y.size();
  while (t < t_end) {
    h = std::min(h, t_end - t);
    std::array<std::vector<double>, 7> stage;
    for (int s = 0; s < 7; ++s) {
      std::vector<double> ys = y;
      for (int r = 0; r < s; ++r)
        for (std::size_t i = 0; i < n; ++i) ys[i] += h * a[s][r] * stage[static_cast<std::size_t>(r)][i];
      stage[static_cast<std::size_t>(s)] = chain_rhs(ys, k, m);
    }
    std::vector<double> y5 = y;
    double err = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double e = 0.0;
      for (std::size_t s = 0; s < 7; ++s) {
        y5[i] += h * b5[s] * stage[s][i];
        e += h * (b5[s] - b4[s]) * stage[s][i];
      }
      err = std::max(err, std::abs(e) / (atol[i] + rtol * std::abs(y5[i])));
    }
    if (err <= 1.0) {
      t += h;
      y = y5;
    }
    h *= std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0);
  }
  return y;
}

TEST(HertzChain, VelocityVerletAgreesWithDormandPrince) {
  const int n = 8;
  const double v0 = 1.0;
  auto grains = chain(n);
  grains[0].vy = v0;
  const double m = grains[0].mass, k = hertz_k();
  const double delta_max = std::pow(1.25 * 0.5 * m * v0 * v0 / k, 0.4);  // first collision's overlap
  const double t_end = 12.0 * 2.94 * delta_max / v0;                     // the pulse reaches the far end
  std::vector<double> y(2 * n, 0.0);
  y[static_cast<std::size_t>(n)] = v0;
  std::vector<double> atol(2 * n, 1e-13 * delta_max);
  for (int i = n; i < 2 * n; ++i) atol[static_cast<std::size_t>(i)] = 1e-13 * v0;
  const auto reference = dormand_prince(y, t_end, k, m, atol, 1e-12);

  // Errors measured: 1.7e-4, 5.3e-5, 1.4e-5 at 0.004, 0.002, 0.001 (order 1.7-1.9; the Hertz force's
  // delta^(3/2) onset is not smooth), 1.6e-7 at 1e-4.
  double previous = 0.0;
  for (const double tolerance : {0.004, 0.002, 0.001, 1e-4}) {
    GranularPlate run(grains, steel, std::nullopt, InterfaceContacts{}, StepControl{tolerance});
    run.advance_to(t_end);
    double err_x = 0.0, err_v = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto& g = run.grains()[static_cast<std::size_t>(i)];
      err_x = std::max(err_x, std::abs(g.y - grains[static_cast<std::size_t>(i)].y - reference[static_cast<std::size_t>(i)]));
      err_v = std::max(err_v, std::abs(g.vy - reference[static_cast<std::size_t>(n + i)]));
    }
    const double err = std::max(err_x / delta_max, err_v / v0);
    if (std::getenv("SEDWAVE_VERBOSE")) std::printf("tolerance %g: error %.3e of the pulse amplitude\n", tolerance, err);
    if (previous > 0.0) {
      EXPECT_GT(std::log2(previous / err) / std::log2(tolerance > 5e-4 ? 2.0 : 10.0), 1.5) << "order";
    }
    previous = err;
  }
  EXPECT_LT(previous, 3e-7);
}

struct Solitary {
  double speed;
  double force;
};
// The pulse from a striker at v0 into a chain of 40 beads: its speed between beads 15 and 30 (times of
// their velocity peaks) and its force amplitude between beads 20 and 21.
Solitary solitary_wave(double v0) {
  const int n = 40;
  auto grains = chain(n);
  grains[0].vy = v0;
  GranularPlate run(grains, steel, std::nullopt, InterfaceContacts{}, StepControl{0.02});
  std::array<double, 2> peak_time{}, peak_speed{};
  double force = 0.0;
  const double k = hertz_k();
  const double t_end = 40.0 * 2.0 * bead_radius / (0.5 * std::pow(v0, 0.2) * 300.0);  // generous
  while (run.time() < t_end) {
    run.step();
    const auto& g = run.grains();
    for (std::size_t s = 0; s < 2; ++s) {
      const auto& b = g[s == 0 ? 15 : 30];
      if (b.vy > peak_speed[s]) peak_speed[s] = b.vy, peak_time[s] = run.time();
    }
    const double overlap = 2.0 * bead_radius - (g[21].y - g[20].y);
    if (overlap > 0.0) force = std::max(force, k * overlap * std::sqrt(overlap));
  }
  return {15.0 * 2.0 * bead_radius / (peak_time[1] - peak_time[0]), force};
}

TEST(HertzChain, SolitaryWaveSpeedFollowsNesterenko) {
  // Nesterenko (2001, Dynamics of Heterogeneous Materials, sec. 1.3), in the form of Daraio et al.,
  // PRE 72, 016603 (2005), eq. 3: V_s = 0.6802 (2E / (d rho^(3/2) (1 - nu^2)))^(1/3) F_m^(1/6).
  const double d = 2.0 * bead_radius;
  const double prefactor = 0.6802 * std::cbrt(2.0 * steel.youngs_modulus /
                                              (d * std::pow(steel_density, 1.5) *
                                               (1.0 - steel.poisson_ratio * steel.poisson_ratio)));
  const Solitary slow = solitary_wave(0.1);
  const Solitary fast = solitary_wave(10.0);
  if (std::getenv("SEDWAVE_VERBOSE"))
    std::printf("V %g m/s at F %g N, V %g m/s at F %g N; Nesterenko %g, %g\n", slow.speed, slow.force, fast.speed,
                fast.force, prefactor * std::pow(slow.force, 1.0 / 6), prefactor * std::pow(fast.force, 1.0 / 6));
  EXPECT_NEAR(std::log(fast.speed / slow.speed) / std::log(fast.force / slow.force), 1.0 / 6.0, 2e-3);
  EXPECT_NEAR(slow.speed / (prefactor * std::pow(slow.force, 1.0 / 6)), 1.0, 0.02);
  EXPECT_NEAR(fast.speed / (prefactor * std::pow(fast.force, 1.0 / 6)), 1.0, 0.02);
}

}  // namespace
