// Two frictional spheres with spin, an oblique impact that slides and then sticks, against an
// independent integration of the same two-body equations written here (Dormand-Prince, tight
// tolerances): final velocities, spins and the energy friction dissipated. The engine sums that
// energy from its own kicks, so its balance closes by construction; this checks the sum itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "dormand_prince.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;

Grain steel_sphere(double x, double y, double radius) {
  Grain g;
  g.x = x, g.y = y, g.radius = radius;
  g.mass = steel_density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  g.inertia = 0.4 * g.mass * radius * radius;
  return g;
}

struct PairLaw {
  double hertz;  // (4/3) E* sqrt(R*)
  double mu;
  double k_s;
};

// State (x, y, vx, vy, w) of sphere 1, the same of sphere 2, then D, the energy friction dissipated.
// Hertz normal force k delta^(3/2) along n = (p1 - p2)/|p1 - p2|; Coulomb-tanh friction
// F_t = -mu F_n tanh(k_s |s|) s/|s| on the slip of the contact point s = v_rel - (v_rel.n) n - (a1 w1 +
// a2 w2) t, t = (-n_y, n_x), lever arms a = r - delta/2 (docs/dem.md); torques -a (n x F_t)_z on both;
// D' = -F_t . s.
std::vector<double> pair_rhs(const std::vector<double>& s, const Grain& g1, const Grain& g2, const PairLaw& law) {
  std::vector<double> ds(s.size(), 0.0);
  for (const int o : {0, 5}) ds[o] = s[o + 2], ds[o + 1] = s[o + 3];
  const double dx = s[0] - s[5], dy = s[1] - s[6];
  const double d = std::hypot(dx, dy);
  const double overlap = g1.radius + g2.radius - d;
  if (overlap <= 0.0) return ds;
  const double nx = dx / d, ny = dy / d, tx = -ny, ty = nx;
  const double fn = law.hertz * std::pow(overlap, 1.5);
  const double a1 = g1.radius - 0.5 * overlap, a2 = g2.radius - 0.5 * overlap;
  const double slip = (s[2] - s[7]) * tx + (s[3] - s[8]) * ty - (a1 * s[4] + a2 * s[9]);
  const double ft = -law.mu * fn * std::tanh(law.k_s * slip);  // along t
  const double fx = fn * nx + ft * tx, fy = fn * ny + ft * ty;
  ds[2] = fx / g1.mass, ds[3] = fy / g1.mass, ds[4] = -a1 * ft / g1.inertia;
  ds[7] = -fx / g2.mass, ds[8] = -fy / g2.mass, ds[9] = -a2 * ft / g2.inertia;
  ds[10] = -ft * slip;
  return ds;
}

TEST(FrictionalPair, ObliqueImpactWithSpinMatchesAnIndependentIntegration) {
  const double r1 = bead_radius, r2 = 1.6 * bead_radius;
  Grain g1 = steel_sphere(0.3 * r2, 0.0, r1), g2 = steel_sphere(0.0, 0.0, r2);
  g1.y = std::sqrt((r1 + r2) * (r1 + r2) - g1.x * g1.x);  // touching, off-centre
  g1.vx = 0.3, g1.vy = -1.0, g1.spin = 150.0;
  g2.spin = -40.0;
  const InterfaceContacts contacts{0.3, 1e3, 1.0, true};
  const double e_star = sedwave::forward::hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                                  steel.youngs_modulus, steel.poisson_ratio);
  const PairLaw law{(4.0 / 3.0) * e_star * std::sqrt(r1 * r2 / (r1 + r2)), contacts.friction,
                    contacts.tanh_velocity_scale};
  // Johnson's head-on contact time (2.94 delta_max / v) for the whole approach speed, doubled.
  const double m = g1.mass * g2.mass / (g1.mass + g2.mass), v = std::hypot(g1.vx, g1.vy);
  const double t_end = 2.0 * 2.94 * std::pow(1.25 * m * v * v / law.hertz, 0.4) / v;

  std::vector<double> y{g1.x, g1.y, g1.vx, g1.vy, g1.spin, g2.x, g2.y, g2.vx, g2.vy, g2.spin, 0.0};
  const double kinetic = 0.5 * g1.mass * v * v + 0.5 * g1.inertia * g1.spin * g1.spin +
                         0.5 * g2.inertia * g2.spin * g2.spin;
  std::vector<double> atol(y.size(), 1e-12 * r1);
  for (const int i : {2, 3, 7, 8}) atol[static_cast<std::size_t>(i)] = 1e-12 * v;
  for (const int i : {4, 9}) atol[static_cast<std::size_t>(i)] = 1e-12 * v / r1;
  atol[10] = 1e-12 * kinetic;
  const auto reference = dormand_prince(
      y, t_end, [&](const std::vector<double>& s) { return pair_rhs(s, g1, g2, law); }, atol, 1e-11);

  GranularPlate run({g1, g2}, steel, std::nullopt, contacts, StepControl{0.01});
  run.advance_to(t_end);
  const auto& e1 = run.grains()[0];
  const auto& e2 = run.grains()[1];
  const double dissipated = run.energies().friction_work;
  const double err_v = std::max({std::abs(e1.vx - reference[2]), std::abs(e1.vy - reference[3]),
                                 std::abs(e2.vx - reference[7]), std::abs(e2.vy - reference[8])}) / v;
  const double err_w = std::max(std::abs(e1.spin - reference[4]) * r1, std::abs(e2.spin - reference[9]) * r2) / v;
  const double err_d = std::abs(dissipated - reference[10]) / reference[10];
  // The slip at the end (rolling contact points after the separation): the contact slid, then stuck.
  const double dx = reference[0] - reference[5], dy = reference[1] - reference[6], d = std::hypot(dx, dy);
  const double final_slip = (-(reference[2] - reference[7]) * dy + (reference[3] - reference[8]) * dx) / d -
                            (r1 * reference[4] + r2 * reference[9]);
  if (std::getenv("SEDWAVE_VERBOSE"))
    std::printf("dissipated %.6e J (%.3f of the kinetic energy), reference %.6e J; errors v %.2e, r w %.2e, "
                "D %.2e; steps %ld; spins %g %g rad/s, final slip %.2e m/s\n",
                dissipated, dissipated / kinetic, reference[10], err_v, err_w, err_d, run.steps(), reference[4],
                reference[9], final_slip);
  EXPECT_LT(std::abs(final_slip), 1e-2 * v) << "the contact stuck before it opened";
  EXPECT_GT(reference[10], 0.02 * kinetic) << "friction took a real share";
  EXPECT_LT(err_v, 1e-4);
  EXPECT_LT(err_w, 1e-4);
  EXPECT_LT(err_d, 1e-4);
}

}  // namespace
