// Adaptive-cubature evidence (sampling/cubature.hpp) against closed forms: a Gaussian likelihood
// cut by a uniform prior, two separated modes, a ridge that only the prior closes, and a narrow and
// a widened prior integrated in one pass.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sedwave/sampling/cubature.hpp"

namespace sedwave::sampling {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

/// The integral over [a, b] of exp(-(x - m)^2 / (2 s^2)).
double gaussian_mass(double a, double b, double m, double s) {
  return s * std::sqrt(2.0 * std::numbers::pi) * (normal_cdf((b - m) / s) - normal_cdf((a - m) / s));
}

/// A flat prior on the box [lo, hi]^2, normalised.
LogDensity box_prior(double lo, double hi) {
  return [lo, hi](const Eigen::VectorXd& x) {
    return x.minCoeff() >= lo && x.maxCoeff() <= hi ? -2.0 * std::log(hi - lo) : kMinusInfinity;
  };
}

/// A map of [lo, hi]: a uniform floor (a fifth of the mass) and Gaussian bumps of width `width` at
/// `centres`, as the inversion puts them around a fit.
AxisMap map_of(double lo, double hi, const std::vector<double>& centres, double width) {
  std::vector<double> nodes, density;
  for (int i = 0; i <= 400; ++i) {
    const double x = lo + (hi - lo) * i / 400.0;
    double g = 0.2 / (hi - lo);
    for (double c : centres) g += 0.8 / static_cast<double>(centres.size()) * std::exp(-0.5 * std::pow((x - c) / width, 2)) / width;
    nodes.push_back(x);
    density.push_back(g);
  }
  return {nodes, density};
}

/// |estimate - exact| within 3 stated errors (and the stated error itself small).
void expect_within_stated(const CubatureEstimate& e, double exact_log_evidence) {
  EXPECT_LT(e.uncertainty, 0.01);
  EXPECT_NEAR(e.log_evidence, exact_log_evidence, 3.0 * e.uncertainty + 1e-4);
}

TEST(Cubature, AxisMapIsTheInverseOfItsCdfAndItsDensityIntegratesToOne) {
  const AxisMap map = map_of(-3.0, 5.0, {1.0}, 0.2);
  for (double u : {0.01, 0.2, 0.5, 0.77, 0.999}) EXPECT_NEAR(map.cdf(map.at(u)), u, 1e-12);
  double total = 0.0;
  for (int i = 0; i < 80000; ++i) total += map.density(-3.0 + (i + 0.5) * 1e-4) * 1e-4;
  EXPECT_NEAR(total, 1.0, 1e-6);
  EXPECT_THROW(AxisMap({0.0, 0.0}, {1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(AxisMap({0.0, 1.0}, {1.0, 0.0}), std::invalid_argument);
}

// A Gaussian likelihood whose peak lies half a sd inside a bound of a uniform prior: the posterior
// is pressed against the bound. Z = prod_j gaussian_mass / area.
TEST(Cubature, GaussianLikelihoodCutByAUniformPriorMatchesTheClosedForm) {
  const Eigen::Vector2d m{0.05, 2.0};
  const double s = 0.1;
  const LogDensity log_l = [&](const Eigen::VectorXd& x) { return -0.5 * (x - m).squaredNorm() / (s * s); };
  const std::vector<AxisMap> axes{map_of(0.0, 4.0, {m(0)}, 2 * s), map_of(0.0, 4.0, {m(1)}, 2 * s)};
  const CubatureRun run = cubature_evidence(log_l, {box_prior(0.0, 4.0)}, axes, 0.0, {});
  EXPECT_TRUE(run.converged);
  const double exact = std::log(gaussian_mass(0.0, 4.0, m(0), s) * gaussian_mass(0.0, 4.0, m(1), s) / 16.0);
  expect_within_stated(run.priors[0], exact);
}

// Two modes of equal weight far apart (25 sd); the map knows of both (as the refused importance
// draws do), and the rule must add them both.
TEST(Cubature, TwoSeparatedModesAreBothCounted) {
  const Eigen::Vector2d a{-2.0, -2.0}, b{2.5, 2.0};
  const double s = 0.15;
  const LogDensity log_l = [&](const Eigen::VectorXd& x) {
    const double la = -0.5 * (x - a).squaredNorm() / (s * s), lb = -0.5 * (x - b).squaredNorm() / (s * s);
    const double top = std::max(la, lb);
    return top + std::log(0.5 * std::exp(la - top) + 0.5 * std::exp(lb - top));
  };
  const std::vector<AxisMap> axes{map_of(-5.0, 5.0, {a(0), b(0)}, 2 * s), map_of(-5.0, 5.0, {a(1), b(1)}, 2 * s)};
  const CubatureRun run = cubature_evidence(log_l, {box_prior(-5.0, 5.0)}, axes, 0.0, {});
  EXPECT_TRUE(run.converged);
  expect_within_stated(run.priors[0], std::log(2.0 * std::numbers::pi * s * s / 100.0));
}

// L depends on x0 - x1 only: a ridge along the diagonal that only the unit-square prior closes.
// Z = integral_{-1}^{1} (1 - |t|) exp(-t^2 / (2 s^2)) dt.
TEST(Cubature, RidgeThatOnlyThePriorClosesMatchesTheClosedForm) {
  const double s = 0.05;
  const LogDensity log_l = [&](const Eigen::VectorXd& x) { return -0.5 * std::pow((x(0) - x(1)) / s, 2); };
  const std::vector<AxisMap> axes{map_of(0.0, 1.0, {0.5}, 0.3), map_of(0.0, 1.0, {0.5}, 0.3)};
  const CubatureRun run = cubature_evidence(log_l, {box_prior(0.0, 1.0)}, axes, 0.0, {});
  EXPECT_TRUE(run.converged);
  const double exact = s * std::sqrt(2.0 * std::numbers::pi) * (2.0 * normal_cdf(1.0 / s) - 1.0) -
                       2.0 * s * s * (1.0 - std::exp(-0.5 / (s * s)));
  expect_within_stated(run.priors[0], std::log(exact));
}

// A narrow prior [0.3, 0.7]^2 and the same widened to [0, 1]^2 in one pass over the wide box:
// each column matches its own closed form, and the narrow one is zero outside its support (its
// own sub-box, not a discontinuity inside one).
TEST(Cubature, NarrowAndWidenedPriorsInOnePassMatchTheirClosedForms) {
  const Eigen::Vector2d m{0.62, 0.45};
  const double s = 0.08;
  const LogDensity log_l = [&](const Eigen::VectorXd& x) { return -0.5 * (x - m).squaredNorm() / (s * s); };
  const std::vector<AxisMap> axes{map_of(0.0, 1.0, {m(0)}, 2 * s), map_of(0.0, 1.0, {m(1)}, 2 * s)};
  const Support narrow{Eigen::Vector2d{0.3, 0.3}, Eigen::Vector2d{0.7, 0.7}};
  const Support wide{Eigen::Vector2d{0.0, 0.0}, Eigen::Vector2d{1.0, 1.0}};
  const CubatureRun run =
      cubature_evidence(log_l, {box_prior(0.3, 0.7), box_prior(0.0, 1.0)}, axes, 0.0, {narrow, wide});
  EXPECT_TRUE(run.converged);
  const auto exact = [&](double lo, double hi) {
    return std::log(gaussian_mass(lo, hi, m(0), s) * gaussian_mass(lo, hi, m(1), s) / std::pow(hi - lo, 2));
  };
  expect_within_stated(run.priors[0], exact(0.3, 0.7));
  expect_within_stated(run.priors[1], exact(0.0, 1.0));
  // 4 x 4 equal pieces, each axis cut again at the narrow support's ends (where they fall inside a piece).
  EXPECT_GT(run.boxes, 16);
}

TEST(Cubature, ResultsAreTheSameForAnyThreadCount) {
  const Eigen::Vector2d m{0.2, -0.4};
  const LogDensity log_l = [&](const Eigen::VectorXd& x) { return -0.5 * (x - m).squaredNorm() / 0.01; };
  const std::vector<AxisMap> axes{map_of(-2.0, 2.0, {m(0)}, 0.2), map_of(-2.0, 2.0, {m(1)}, 0.2)};
  CubatureOptions one, two;
  two.threads = 2;
  const CubatureRun a = cubature_evidence(log_l, {box_prior(-2.0, 2.0)}, axes, 0.0, {}, one);
  const CubatureRun b = cubature_evidence(log_l, {box_prior(-2.0, 2.0)}, axes, 0.0, {}, two);
  EXPECT_EQ(a.priors[0].log_evidence, b.priors[0].log_evidence);
  EXPECT_EQ(a.evaluations, b.evaluations);
  const MappedSample x = mapped_importance(log_l, {box_prior(-2.0, 2.0)}, axes, 500, 7, 1);
  const MappedSample y = mapped_importance(log_l, {box_prior(-2.0, 2.0)}, axes, 500, 7, 2);
  EXPECT_EQ(x.priors[0].log_evidence, y.priors[0].log_evidence);
  // The map's own importance estimate agrees with the cubature (independent draws, its own error).
  EXPECT_NEAR(x.priors[0].log_evidence, a.priors[0].log_evidence, 4.0 * x.priors[0].uncertainty);
}

}  // namespace
}  // namespace sedwave::sampling
