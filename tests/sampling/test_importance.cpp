// Importance-sampling evidence (sampling/importance.hpp) against closed forms, and the diagnostics
// that say when it does not apply.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "sampling_test_support.hpp"
#include "sedwave/sampling/importance.hpp"

namespace sedwave::sampling {
namespace {

/// A flat prior on the box [-half, half]^2, normalised.
LogDensity box_prior(double half) {
  return [half](const Eigen::VectorXd& x) {
    return x.cwiseAbs().maxCoeff() <= half ? -2.0 * std::log(2.0 * half) : -std::numeric_limits<double>::infinity();
  };
}

struct Correlated {
  Eigen::Vector2d mean{0.3, -0.2};
  Eigen::Matrix2d covariance{{0.09, 0.05}, {0.05, 0.04}};
  /// ln of the Gaussian likelihood's integral (its normalisation), 2 pi sqrt(det C).
  [[nodiscard]] double log_integral() const { return std::log(2.0 * std::numbers::pi * std::sqrt(covariance.determinant())); }
};

// Two priors from the same evaluations: a box of half-width 10 and one of 5, both far wider than
// the likelihood (15 sigma and more), so Z = integral of L / box area for each.
TEST(Importance, EvidenceOfAGaussianLikelihoodUnderTwoPriorsIsHonestOverSeeds) {
  const Correlated g;
  const LogDensity log_l = testing::gaussian_log_density(g.mean, g.covariance);
  const double exact_wide = g.log_integral() - std::log(400.0), exact_narrow = g.log_integral() - std::log(100.0);
  // The proposal's start: a deliberately poor linearisation (centre off by a sigma, round scale).
  const Eigen::Vector2d centre{0.6, 0.0};
  const Eigen::Matrix2d scale = 0.05 * Eigen::Matrix2d::Identity();
  const int seeds = 20;
  int within[2] = {0, 0};
  double sum[2] = {0.0, 0.0};
  for (int seed = 1; seed <= seeds; ++seed) {
    const ImportanceRun run = importance_evidence(log_l, {box_prior(10.0), box_prior(5.0)}, centre, scale,
                                                  {.seed = static_cast<std::uint64_t>(seed)});
    const double exact[2] = {exact_wide, exact_narrow};
    for (int p = 0; p < 2; ++p) {
      const ImportanceEstimate& e = run.priors[static_cast<std::size_t>(p)];
      EXPECT_LE(e.uncertainty, 0.025);
      EXPECT_LT(e.pareto_k, 0.5);
      const double d = e.log_evidence - exact[p];
      within[p] += std::abs(d) <= 2.0 * e.uncertainty;
      sum[p] += d;
    }
    EXPECT_LE(run.evaluations, 800 + 9600);
  }
  for (int p = 0; p < 2; ++p) {
    EXPECT_GE(within[p], 18) << "prior " << p;
    // The mean difference within 3 standard errors of 0 (a per-run error of at most 0.025).
    EXPECT_LT(std::abs(sum[p] / seeds), 3.0 * 0.025 / std::sqrt(seeds)) << "prior " << p;
  }
}

TEST(Importance, PosteriorMomentsAndResampledDrawsMatchTheGaussian) {
  const Correlated g;
  const ImportanceRun run =
      importance_evidence(testing::gaussian_log_density(g.mean, g.covariance), {box_prior(10.0)}, g.mean, g.covariance);
  const ImportanceEstimate& e = run.priors[0];
  EXPECT_LT((e.mean - g.mean).norm(), 0.02);
  EXPECT_LT((e.covariance - g.covariance).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_LT(e.far_mass, 0.01);  // a 2-D Gaussian has e^-8 = 0.03 % beyond 4 sigma
  EXPECT_NEAR(e.min_axis_kurtosis, 3.0, 0.3);
  RandomStream random(7);
  const Eigen::MatrixXd draws = resample(run.draws, e.log_weights, 4000, random);
  const Eigen::Vector2d mean = draws.colwise().mean();
  EXPECT_LT((mean - g.mean).norm(), 0.03);
}

TEST(Importance, ThreadsDoNotChangeTheResult) {
  const Correlated g;
  const LogDensity log_l = testing::gaussian_log_density(g.mean, g.covariance);
  const ImportanceRun one = importance_evidence(log_l, {box_prior(10.0)}, g.mean, g.covariance, {.threads = 1});
  const ImportanceRun two = importance_evidence(log_l, {box_prior(10.0)}, g.mean, g.covariance, {.threads = 2});
  EXPECT_EQ(one.priors[0].log_evidence, two.priors[0].log_evidence);
  EXPECT_EQ(one.priors[0].uncertainty, two.priors[0].uncertainty);
  EXPECT_EQ(one.draws, two.draws);
  // And with a defensive slab (a plateau in x1 the box closes).
  const LogDensity plateau = [](const Eigen::VectorXd& x) { return -0.5 * std::pow(x(1) / 0.1, 2); };
  const ImportanceOptions slab{.defensive = true, .supports = {{Eigen::Vector2d::Constant(-2.0), Eigen::Vector2d::Constant(2.0)}}};
  ImportanceOptions slab_two = slab;
  slab_two.threads = 2;
  const Eigen::Matrix2d narrow = 0.01 * Eigen::Matrix2d::Identity();
  const ImportanceRun three = importance_evidence(plateau, {box_prior(2.0)}, Eigen::Vector2d::Zero(), narrow, slab);
  const ImportanceRun four = importance_evidence(plateau, {box_prior(2.0)}, Eigen::Vector2d::Zero(), narrow, slab_two);
  EXPECT_EQ(three.slabs, 1);
  EXPECT_EQ(three.priors[0].log_evidence, four.priors[0].log_evidence);
  EXPECT_EQ(three.draws, four.draws);
}

// A ridge the linearisation did not see: the likelihood fixes x1 + x2 only, the box prior closes
// x1 - x2 ten thousand proposal sigmas out. The weights' tail says so.
TEST(Importance, ARidgeTheProposalDoesNotKnowOfIsFlagged) {
  const LogDensity ridge = [](const Eigen::VectorXd& x) { return -0.5 * std::pow((x(0) + x(1)) / 0.1, 2); };
  const ImportanceRun run =
      importance_evidence(ridge, {box_prior(10.0)}, Eigen::Vector2d::Zero(), 0.005 * Eigen::Matrix2d::Identity());
  const ImportanceEstimate& e = run.priors[0];
  EXPECT_TRUE(e.pareto_k > 0.7 || e.far_mass > 0.01 || e.min_axis_kurtosis < 2.0)
      << "k " << e.pareto_k << ", far mass " << e.far_mass << ", kurtosis " << e.min_axis_kurtosis;
}

// A proposal far narrower than the posterior (a unit Gaussian, proposal sd 0.05): k-hat far above
// 0.7, so no draws beyond the first block are spent on an estimate that will be refused; with the
// cut-off lifted, the same run draws on to max_draws towards its target error.
TEST(Importance, NoMoreDrawsWhereKHatRefusesTheEstimate) {
  const LogDensity gaussian = [](const Eigen::VectorXd& x) { return -0.5 * x.squaredNorm(); };
  ImportanceOptions options;
  options.target_uncertainty = 1e-4;
  const ImportanceRun refused =
      importance_evidence(gaussian, {box_prior(10.0)}, Eigen::Vector2d::Zero(), 0.0025 * Eigen::Matrix2d::Identity(), options);
  ASSERT_GT(refused.priors[0].pareto_k, 0.7);
  EXPECT_EQ(refused.draws.rows(), options.draws);
  options.draw_on_below_pareto_k = std::numeric_limits<double>::infinity();
  const ImportanceRun drawn_on =
      importance_evidence(gaussian, {box_prior(10.0)}, Eigen::Vector2d::Zero(), 0.0025 * Eigen::Matrix2d::Identity(), options);
  EXPECT_EQ(drawn_on.draws.rows(), options.max_draws);
}

// Two equal modes 8 sigma apart, the proposal centred on one: the adapted mixture covers both, and
// the kurtosis across them is far below a single peak's 3. (A mode far
// beyond the heavy tails' reach, with nothing between, is invisible to any proposal around the
// other: docs/sampling.md.)
TEST(Importance, ASecondModeIsFlagged) {
  const LogDensity two_modes = [](const Eigen::VectorXd& x) {
    const double a = -0.5 * (x - Eigen::Vector2d{-0.4, 0.0}).squaredNorm() / 0.01;
    const double b = -0.5 * (x - Eigen::Vector2d{0.4, 0.0}).squaredNorm() / 0.01;
    return std::max(a, b) + std::log1p(std::exp(std::min(a, b) - std::max(a, b)));
  };
  const ImportanceRun run =
      importance_evidence(two_modes, {box_prior(10.0)}, Eigen::Vector2d{-0.4, 0.0}, 0.01 * Eigen::Matrix2d::Identity());
  const ImportanceEstimate& e = run.priors[0];
  EXPECT_LT(e.min_axis_kurtosis, 1.5);
}

/// The support of box_prior(half) in two dimensions.
Support box_support(double half) { return {Eigen::Vector2d::Constant(-half), Eigen::Vector2d::Constant(half)}; }

/// ln Z over `seeds` seeds within 2 stated sigmas of `exact` in all but one, the mean difference
/// within 3 standard errors (of the largest stated error) of 0, and every run's slab along `axis`.
void expect_honest(const LogDensity& log_l, double half, const Eigen::Vector2d& centre, const Eigen::Matrix2d& scale,
                   double exact, int axis) {
  const int seeds = 10;
  int within = 0;
  double sum = 0.0, largest = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const ImportanceRun run = importance_evidence(
        log_l, {box_prior(half)}, centre, scale,
        {.defensive = true, .supports = {box_support(half)}, .seed = static_cast<std::uint64_t>(seed)});
    const ImportanceEstimate& e = run.priors[0];
    EXPECT_EQ(e.slab_axis, axis) << "seed " << seed;
    EXPECT_LE(e.pareto_k, 0.7) << "seed " << seed;
    EXPECT_LE(run.evaluations, 1600 + 9600);
    within += std::abs(e.log_evidence - exact) <= 2.0 * e.uncertainty;
    sum += e.log_evidence - exact;
    largest = std::max(largest, e.uncertainty);
  }
  EXPECT_GE(within, seeds - 1);
  EXPECT_LT(std::abs(sum / seeds), 3.0 * largest / std::sqrt(seeds));
}

// Two equal modes 8 sigma apart along x1, the linearisation centred on one: the defensive slab
// runs along x1 and spans both, and ln Z is the closed form's (two Gaussians' integrals over the
// box's area).
TEST(Importance, TwoModesAlongAParameterAreIntegratedThroughTheSlab) {
  const double sigma = 0.1;
  const LogDensity two_modes = [sigma](const Eigen::VectorXd& x) {
    const double a = -0.5 * (x - Eigen::Vector2d{-0.4, 0.0}).squaredNorm() / (sigma * sigma);
    const double b = -0.5 * (x - Eigen::Vector2d{0.4, 0.0}).squaredNorm() / (sigma * sigma);
    return std::max(a, b) + std::log1p(std::exp(std::min(a, b) - std::max(a, b)));
  };
  const double exact = std::log(2.0 * 2.0 * std::numbers::pi * sigma * sigma) - std::log(400.0);
  expect_honest(two_modes, 10.0, Eigen::Vector2d{-0.4, 0.0}, sigma * sigma * Eigen::Matrix2d::Identity(), exact, 0);
}

// A plateau the prior's bound closes: the likelihood sees x2 only (sd 0.1) and x1 not at all, over
// the prior's box [-2, 2]^2; the linearisation at the centre guesses a sd of 0.1 in x1 as well, 20
// of them short of the bound. The slab runs along x1 to the bounds.
TEST(Importance, APlateauThePriorClosesIsIntegratedThroughTheSlab) {
  const double sigma = 0.1, half = 2.0;
  const LogDensity plateau = [sigma](const Eigen::VectorXd& x) { return -0.5 * std::pow(x(1) / sigma, 2); };
  const double exact = std::log(2.0 * half * std::sqrt(2.0 * std::numbers::pi) * sigma) - std::log(4.0 * half * half);
  expect_honest(plateau, half, Eigen::Vector2d::Zero(), sigma * sigma * Eigen::Matrix2d::Identity(), exact, 0);
}

TEST(Importance, ParetoKOfExponentialAndParetoTails) {
  // Weights w = u^(-k) for uniform u have a Pareto tail of shape k exactly.
  RandomStream random(3);
  for (const double k : {0.2, 0.9}) {
    Eigen::VectorXd log_w(4000);
    for (Eigen::Index i = 0; i < log_w.size(); ++i) log_w(i) = -k * std::log(1.0 - random.uniform());
    EXPECT_NEAR(pareto_smooth(log_w).k, k, 0.15) << "k " << k;
  }
}

TEST(Importance, RefusesBadInput) {
  const LogDensity flat = [](const Eigen::VectorXd&) { return 0.0; };
  testing::expect_refusal<std::invalid_argument>(
      [&] { (void)importance_evidence(flat, {}, Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity()); }, {"no prior"});
  testing::expect_refusal<std::invalid_argument>(
      [&] { (void)importance_evidence(flat, {flat}, Eigen::Vector2d::Zero(), -Eigen::Matrix2d::Identity()); },
      {"positive definite"});
}

}  // namespace
}  // namespace sedwave::sampling
