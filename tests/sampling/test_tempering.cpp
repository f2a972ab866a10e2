// Parallel tempering: the posterior at beta = 1 and the log evidence by thermodynamic integration
// against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "sampling_test_support.hpp"
#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/summary.hpp"
#include "sedwave/sampling/tempering.hpp"

namespace sedwave::sampling {
namespace {

using testing::expect_refusal;

// ln N(x; mean, diag(sd^2)), normalised.
double log_normal_density(const Eigen::VectorXd& x, const Eigen::VectorXd& mean, const Eigen::VectorXd& sd) {
  const Eigen::ArrayXd z = (x - mean).array() / sd.array();
  return -0.5 * z.square().sum() - sd.array().log().sum() -
         0.5 * static_cast<double>(x.size()) * std::log(2.0 * std::numbers::pi);
}

// Gaussian prior N(0, diag(p^2)) and Gaussian likelihood N(m; theta, diag(s^2)) (as a function of
// theta): Z = N(m; 0, diag(p^2 + s^2)) and the posterior is N(m p^2 / (p^2 + s^2), p^2 s^2 / (p^2 + s^2))
// per parameter. The prior is 30 and 15 times wider than the likelihood: ln Z is far from 0.
struct GaussianProblem {
  Eigen::Vector2d prior_sd{3.0, 3.0};
  Eigen::Vector2d data{1.0, -1.0};
  Eigen::Vector2d noise_sd{0.1, 0.2};

  [[nodiscard]] PriorAndLikelihood density() const {
    return {[this](const Eigen::VectorXd& x) { return log_normal_density(x, Eigen::Vector2d::Zero(), prior_sd); },
            [this](const Eigen::VectorXd& x) { return log_normal_density(data, x, noise_sd); }};
  }
  [[nodiscard]] double log_evidence() const {
    const Eigen::Vector2d total_sd = (prior_sd.array().square() + noise_sd.array().square()).sqrt();
    return log_normal_density(data, Eigen::Vector2d::Zero(), total_sd);
  }
};

TEST(Tempering, LogEvidenceOfGaussianPriorAndLikelihood) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = geometric_ladder(32, 1e5);
  options.ensemble.steps = 3000;
  const TemperedRun run = sample_tempered(
      problem.density(), start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(1.0), options.ensemble),
      options);
  const Evidence evidence = thermodynamic_evidence(run);
  std::cout << "  ln Z " << evidence.log_evidence << " +- " << evidence.uncertainty << " (ladder "
            << evidence.discretisation << ", Monte Carlo " << evidence.monte_carlo << "); exact "
            << problem.log_evidence() << "; swap acceptance " << run.swap_acceptance.transpose() << '\n';
  EXPECT_NEAR(evidence.log_evidence, problem.log_evidence(), evidence.uncertainty);
  EXPECT_NEAR(evidence.log_evidence, problem.log_evidence(), 0.1);
  EXPECT_LT(evidence.uncertainty, 0.1);
  EXPECT_GT(run.swap_acceptance.minCoeff(), 0.05);
}

// The beta = 1 ensemble samples the posterior: its mean within 4 Monte Carlo standard errors.
TEST(Tempering, ColdestLevelSamplesThePosterior) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = geometric_ladder(8, 1e3);
  options.ensemble.steps = 3000;
  const TemperedRun run = sample_tempered(
      problem.density(), start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(1.0), options.ensemble),
      options);
  const Diagnostics diagnostics = diagnose(run.levels.front());
  const Eigen::Vector2d mean = pooled_samples(run.levels.front().chains).colwise().mean().transpose();
  for (int i = 0; i < 2; ++i) {
    const double p2 = problem.prior_sd(i) * problem.prior_sd(i);
    const double s2 = problem.noise_sd(i) * problem.noise_sd(i);
    const double posterior_sd = std::sqrt(p2 * s2 / (p2 + s2));
    EXPECT_NEAR(mean(i), problem.data(i) * p2 / (p2 + s2), 4.0 * posterior_sd / std::sqrt(diagnostics.ess(i)));
  }
  EXPECT_EQ(run.evaluations, 8 * 16 * (3000 + 1));
}

// Two well-separated modes of equal weight, N(-4, 0.5^2) and N(+4, 0.5^2), walkers started in one:
// the plain sampler never leaves it; the tempered one finds the other and weighs them equally.
TEST(Tempering, HotLevelsCarryWalkersBetweenModes) {
  const LogDensity two_modes = [](const Eigen::VectorXd& x) {
    const double a = -0.5 * std::pow((x(0) + 4.0) / 0.5, 2);
    const double b = -0.5 * std::pow((x(0) - 4.0) / 0.5, 2);
    return std::max(a, b) + std::log1p(std::exp(std::min(a, b) - std::max(a, b))) - 0.5 * x(1) * x(1);
  };
  const LogDensity flat_prior = [](const Eigen::VectorXd& x) {
    return (x.array().abs() < 20.0).all() ? 0.0 : -std::numeric_limits<double>::infinity();
  };
  TemperingOptions options;
  options.betas = geometric_ladder(10, 1e3);
  options.ensemble.steps = 4000;
  const auto start = start_ball(Eigen::Vector2d(4.0, 0.0), Eigen::Vector2d(0.3, 0.3), options.ensemble);

  const EnsembleRun plain = sample(two_modes, start, options.ensemble);
  EXPECT_GT(pooled_samples(plain.chains).col(0).minCoeff(), 0.0) << "the plain sampler crossed the valley";

  const TemperedRun tempered = sample_tempered({flat_prior, two_modes}, start, options);
  const Eigen::VectorXd x = pooled_samples(tempered.levels.front().chains).col(0);
  const double left_fraction = (x.array() < 0.0).cast<double>().mean();
  std::cout << "  fraction of posterior draws in the left mode: " << left_fraction << '\n';
  EXPECT_NEAR(left_fraction, 0.5, 0.1);
}

// The ensembles of all temperatures are evaluated half by half in one batch, shared among threads;
// the draws come first, so the run must be the same bit for bit whatever the thread count.
TEST(Tempering, ThreadsDoNotChangeTheRun) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = geometric_ladder(6, 1e3);
  options.ensemble.steps = 150;
  const auto start = start_ball(problem.data, Eigen::Vector2d(0.1, 0.1), options.ensemble);
  const TemperedRun serial = sample_tempered(problem.density(), start, options);
  options.ensemble.threads = 2;
  const TemperedRun threaded = sample_tempered(problem.density(), start, options);
  for (std::size_t t = 0; t < serial.levels.size(); ++t) {
    for (std::size_t k = 0; k < serial.levels[t].chains.size(); ++k) {
      EXPECT_EQ(serial.levels[t].chains[k], threaded.levels[t].chains[k]);
    }
  }
  EXPECT_EQ(serial.swap_acceptance, threaded.swap_acceptance);
  EXPECT_EQ(thermodynamic_evidence(serial).log_evidence, thermodynamic_evidence(threaded).log_evidence);
}

// <ln L>_beta never decreases with beta, so ln Z = integral_0^1 <ln L>_beta d beta can never exceed
// <ln L> at beta = 1. A hot level whose ln L scatters wildly (an ensemble far from converged) must
// not let the end correction of the trapezoid rule (its variance term) push ln Z above that.
TEST(Tempering, EvidenceStaysBelowTheColdMeanWhateverTheHotVariances) {
  TemperedRun run;
  run.betas = {1.0, 0.1};
  run.log_likelihood.resize(2);
  for (int walker = 0; walker < 8; ++walker) {
    run.log_likelihood[0].push_back(Eigen::VectorXd::Constant(100, -1.0));
    Eigen::VectorXd scattered(100);
    for (Eigen::Index k = 0; k < scattered.size(); ++k) scattered(k) = (k + walker) % 2 == 0 ? -1001.0 : 999.0;
    run.log_likelihood[1].push_back(scattered);
  }
  const Evidence evidence = thermodynamic_evidence(run);
  EXPECT_LE(evidence.log_evidence, -1.0 + 1e-12);
  EXPECT_GE(evidence.log_evidence, -1.0 - 1e-12);  // both levels have mean -1: so has every beta
}

TEST(Tempering, RefusesABadLadder) {
  const GaussianProblem problem;
  TemperingOptions options;
  const auto start = start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), options.ensemble);
  options.betas = {0.5, 0.1};
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"beta = 1"});
  options.betas = {1.0, 0.1, 0.2};
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"inverse temperature 2", "descend"});
  options.betas = {1.0, 0.0};
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"> 0"});
  options.betas.clear();
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered({problem.density().log_prior, {}}, start, options); },
                                        {"log likelihood"});
}

}  // namespace
}  // namespace sedwave::sampling
