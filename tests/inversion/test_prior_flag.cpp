// The prior-controlled flag (posterior.hpp, PosteriorQuantity::prior_dominated): the prior's share
// of a quantity's posterior variance against its closed form for a Gaussian posterior, and the
// flag's rates on synthetic sets whose answer is known by design (bench/prior_flag_study.hpp; the
// full study is bench/prior_flag_rates.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prior_control.hpp"
#include "prior_flag_study.hpp"

namespace sedwave::inversion::detail {
namespace {

/// Draws of N(0, sigma).
Eigen::MatrixXd gaussian_draws(const Eigen::MatrixXd& sigma, int count, unsigned seed) {
  const Eigen::LLT<Eigen::MatrixXd> root(sigma);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd draws(count, sigma.rows());
  for (int r = 0; r < count; ++r) {
    Eigen::VectorXd z(sigma.rows());
    for (Eigen::Index i = 0; i < z.size(); ++i) z(i) = normal(rng);
    draws.row(r) = (root.matrixL() * z).transpose();
  }
  return draws;
}

// A Gaussian likelihood of information F and a Gaussian prior of information P give the posterior
// covariance Sigma = (F + P)^-1, and the prior's share of the variance of a linear quantity a.theta
// is a^T Sigma P Sigma a / a^T Sigma a (the posterior precision split as F + P). Here the data see
// theta_1 - theta_2 and theta_2 - theta_3 but not theta_1 + theta_2 + theta_3 (a ridge, as
// kappa d gamma); the prior is log-normal with sd_ln 1, 2 and 0.5.
TEST(PriorControl, SharesMatchTheGaussianClosedForm) {
  Eigen::MatrixXd jacobian(2, 3);
  jacobian << 10.0, -10.0, 0.0, 0.0, 30.0, -30.0;
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  const Eigen::Vector3d prior_sd(1.0, 2.0, 0.5);
  const Eigen::MatrixXd prior_information = prior_sd.array().square().inverse().matrix().asDiagonal();
  const Eigen::MatrixXd sigma = (information + prior_information).inverse();
  const Eigen::MatrixXd draws = gaussian_draws(sigma, 40000, 5);
  const PriorControl control(draws, information);
  Eigen::MatrixXd quantities(4, 3);  // each parameter, and theta_1 - theta_2 (which the data see)
  quantities << 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, -1, 0;
  for (Eigen::Index q = 0; q < quantities.rows(); ++q) {
    const Eigen::VectorXd a = quantities.row(q).transpose();
    const double expected = a.dot(sigma * prior_information * sigma * a) / a.dot(sigma * a);
    EXPECT_NEAR(control.prior_share(draws * a), expected, 0.02) << "quantity " << q;
  }
  // The premise: each parameter lies mostly along the unseen ridge, the seen derived quantity does not.
  EXPECT_GT(control.prior_share(draws.col(0)), 0.9);
  EXPECT_LT(control.prior_share(draws * quantities.row(3).transpose()), 0.1);
}

// With a flat prior the data make every interval: the share is zero up to Monte Carlo error.
TEST(PriorControl, AFlatPriorHasNoShare) {
  Eigen::MatrixXd information(2, 2);
  information << 4.0, 1.0, 1.0, 9.0;
  const Eigen::MatrixXd draws = gaussian_draws(information.inverse(), 40000, 6);
  const PriorControl control(draws, information);
  EXPECT_LT(control.prior_share(draws.col(0)), 0.03);
  EXPECT_LT(control.prior_share(draws.col(1)), 0.03);
}

// One quantity, Gaussian prior sd 1 and likelihood sd 1/2: the posterior variance is 1/(1 + 4) = 0.2,
// the prior's share of its precision 1/5. Its width against the prior's, squared, is that share; a
// marginal as wide as its prior has share 1.
TEST(PriorControl, WidthShareMatchesTheGaussianClosedForm) {
  const Eigen::MatrixXd prior = gaussian_draws(Eigen::MatrixXd::Identity(1, 1), 40000, 7);
  const Eigen::MatrixXd posterior = gaussian_draws(Eigen::MatrixXd::Constant(1, 1, 0.2), 40000, 8);
  EXPECT_NEAR(prior_width_share(posterior.col(0), prior.col(0)), 0.2, 0.01);
  EXPECT_NEAR(prior_width_share(prior.col(0), gaussian_draws(Eigen::MatrixXd::Identity(1, 1), 40000, 9).col(0)), 1.0,
              0.03);
  EXPECT_EQ(prior_width_share(posterior.col(0), Eigen::VectorXd::Zero(100)), 0.0) << "a prior without spread";
}

// The same against the likelihood alone: a profile interval of half-width 1/2 (the likelihood's sd)
// and a credible one of half-width sqrt(0.2) give 1 - 0.2 / 0.25 = 1/5; an open profile gives 1.
TEST(PriorControl, ProfileShareMatchesTheGaussianClosedForm) {
  const double c = std::exp(std::sqrt(0.2)), p = std::exp(0.5);
  EXPECT_NEAR(prior_share_against_profile(1.0 / c, c, 1.0 / p, p), 0.2, 1e-12);
  EXPECT_EQ(prior_share_against_profile(1.0 / c, c, std::nullopt, p), 1.0) << "open below";
  EXPECT_EQ(prior_share_against_profile(1.0 / c, c, 1.0 / p, std::nullopt), 1.0) << "open above";
  EXPECT_EQ(prior_share_against_profile(1.0 / p, p, 1.0 / c, c), 0.0) << "a credible interval wider than the profile";
  EXPECT_EQ(prior_share_against_profile(2.0, 2.0, 2.0, 2.0), 0.0) << "a quantity known exactly";
}

}  // namespace
}  // namespace sedwave::inversion::detail

namespace sedwave::bench {
namespace {

// The small version of bench/prior_flag_rates: every one of kappa, d, gamma flagged on at least
// 11 of 12 ridge sets, and any of them on at most 1 of 12 well-determined sets. (Were the true
// rates 0.75 and 0.25, these would pass with probability 0.16 and 0.16.)
TEST(PriorFlag, FlagsRidgesAndSparesWellDeterminedSets) {
  constexpr int kSets = 12;
  constexpr unsigned kSeed = 3;
  constexpr int kSteps = 1500;
  int ridge = 0, determined = 0;
  for (int i = 0; i < kSets; ++i) {
    // Without the fits' profiles: the posterior's own tests, and a quicker test.
    ridge += set_flagged(FlagSet::Ridge, run_flag_set(FlagSet::Ridge, kSeed, i, kSteps, FlagPriors::Default, false));
    determined += set_flagged(FlagSet::WellDetermined,
                              run_flag_set(FlagSet::WellDetermined, kSeed, i, kSteps, FlagPriors::Default, false));
  }
  EXPECT_GE(ridge, kSets - 1);
  EXPECT_LE(determined, 1);
}

}  // namespace
}  // namespace sedwave::bench
