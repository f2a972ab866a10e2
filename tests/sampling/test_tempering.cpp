// Parallel tempering: the posterior at beta = 1 and the log evidence by thermodynamic integration
// against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <vector>

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
            [this](const Eigen::VectorXd& x) { return log_normal_density(data, x, noise_sd); },
            [this](RandomStream& random) {
              return Eigen::VectorXd(Eigen::Vector2d(prior_sd(0) * random.normal(), prior_sd(1) * random.normal()));
            }};
  }
  [[nodiscard]] double log_evidence() const {
    const Eigen::Vector2d total_sd = (prior_sd.array().square() + noise_sd.array().square()).sqrt();
    return log_normal_density(data, Eigen::Vector2d::Zero(), total_sd);
  }
};

TEST(Tempering, LogEvidenceOfGaussianPriorAndLikelihood) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = evidence_ladder(32, 1e5);
  options.ensemble.steps = 3000;
  const TemperedRun run = sample_tempered(
      problem.density(), start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(1.0), options.ensemble),
      options);
  const Evidence evidence = thermodynamic_evidence(run);
  std::cout << "  ln Z " << evidence.log_evidence << " +- " << evidence.uncertainty << " (thermodynamic integration "
            << evidence.thermodynamic_integration << " +- " << evidence.discretisation << " ladder); exact "
            << problem.log_evidence() << "; swap acceptance " << run.swap_acceptance.transpose() << '\n';
  EXPECT_NEAR(evidence.log_evidence, problem.log_evidence(), 3.0 * evidence.uncertainty);
  EXPECT_NEAR(evidence.log_evidence, problem.log_evidence(), 0.1);
  EXPECT_LT(evidence.uncertainty, 0.1);
  EXPECT_NEAR(evidence.thermodynamic_integration, problem.log_evidence(), 0.1);
  EXPECT_GT(run.swap_acceptance.minCoeff(), 0.05);
}

// A nonlinear, non-Gaussian problem with the shape of an inversion: y(t) = a exp(-b t) at 12 times,
// 5 % noise, a flat prior on (ln a, ln b) over [-3, 3]^2, where chi^2 at the prior's corners is
// ~10^5 times its minimum (the likelihood is far narrower than the prior, and ln L over the prior
// spans decades). Its ln Z by brute-force quadrature on a fine grid is the reference.
struct DecayProblem {
  static constexpr double kHalfWidth = 3.0;
  static constexpr int kTimes = 12;
  Eigen::VectorXd times = Eigen::VectorXd::LinSpaced(kTimes, 0.0, 1.0);
  Eigen::VectorXd data;
  double noise = 0.05;

  DecayProblem() {
    RandomStream random(99);
    data = (1.5 * (-0.7 * times.array()).exp()).matrix();
    for (Eigen::Index i = 0; i < data.size(); ++i) data(i) += noise * random.normal();
  }
  [[nodiscard]] double log_likelihood(double ln_a, double ln_b) const {
    const Eigen::ArrayXd residual = (data.array() - std::exp(ln_a) * (-std::exp(ln_b) * times.array()).exp()) / noise;
    return -0.5 * residual.square().sum() - kTimes * std::log(noise * std::sqrt(2.0 * std::numbers::pi));
  }
  [[nodiscard]] PriorAndLikelihood density() const {
    const double log_prior = -2.0 * std::log(2.0 * kHalfWidth);
    return {[log_prior](const Eigen::VectorXd& x) {
              return (x.array().abs() <= kHalfWidth).all() ? log_prior : -std::numeric_limits<double>::infinity();
            },
            [this](const Eigen::VectorXd& x) { return log_likelihood(x(0), x(1)); },
            [](RandomStream& random) {
              return Eigen::VectorXd(Eigen::Vector2d(kHalfWidth * (2.0 * random.uniform() - 1.0),
                                                     kHalfWidth * (2.0 * random.uniform() - 1.0)));
            }};
  }
  // Midpoint rule on an n x n grid over the prior, summed as log-sum-exp; the posterior's sd (~0.02
  // in ln a) spans several cells at n = 2000, where the rule for a smooth peak is exact to far below
  // 1e-3 (checked against n = 1000 below).
  [[nodiscard]] double quadrature(int n) const {
    const double h = 2.0 * kHalfWidth / n;
    std::vector<double> terms;
    double peak = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        terms.push_back(log_likelihood(-kHalfWidth + (i + 0.5) * h, -kHalfWidth + (j + 0.5) * h));
        peak = std::max(peak, terms.back());
      }
    }
    double sum = 0.0;
    for (const double t : terms) sum += std::exp(t - peak);
    return peak + std::log(sum * h * h / (4.0 * kHalfWidth * kHalfWidth));
  }
};

struct SeedStudy {
  int runs = 0, within_two_sigma = 0;
  double sum = 0.0, sum_squares = 0.0, sum_sigma = 0.0;
  void add(double difference, double sigma) {
    ++runs;
    sum_sigma += sigma;
    within_two_sigma += std::abs(difference) <= 2.0 * sigma;
    sum += difference;
    sum_squares += difference * difference;
  }
  [[nodiscard]] double mean() const { return sum / runs; }
  [[nodiscard]] double standard_error() const {
    return std::sqrt((sum_squares - runs * mean() * mean()) / (runs - 1.0) / runs);
  }
  [[nodiscard]] double fraction_within() const { return static_cast<double>(within_two_sigma) / runs; }
};

// The stated error is honest: over 20 seeds, |ln Z - exact| <= 2 sigma_stated in >= 90 % of runs, and
// the mean difference is within 2 standard errors of 0 (no bias beyond the noise).
void expect_honest_evidence(const PriorAndLikelihood& density, double exact, const std::vector<double>& betas,
                            const Eigen::Vector2d& start, int steps, int adapt_steps = 0, int seeds = 20) {
  SeedStudy study;
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(seeds); ++seed) {
    TemperingOptions options;
    options.betas = betas;
    options.adapt_steps = adapt_steps;
    options.ensemble.steps = steps;
    options.ensemble.seed = seed;
    // Hot rungs from prior draws, cold ones in a small ball at the likelihood's peak.
    RandomStream prior_random(seed + 1000);
    std::vector<std::vector<Eigen::VectorXd>> starts;
    for (const double beta : betas) {
      std::vector<Eigen::VectorXd> walkers = start_ball(start, Eigen::Vector2d(0.01, 0.01), options.ensemble);
      if (beta < 1e-3) {
        for (Eigen::VectorXd& w : walkers) w = density.draw_prior(prior_random);
      }
      starts.push_back(walkers);
    }
    const Evidence evidence = thermodynamic_evidence(sample_tempered(density, starts, options));
    study.add(evidence.log_evidence - exact, evidence.uncertainty);
    EXPECT_GT(evidence.stone_overlap, 0.1) << "seed " << seed;
  }
  std::cout << "  " << study.runs << " seeds: " << study.within_two_sigma << " within 2 sigma; mean ln Z - exact "
            << study.mean() << " +- " << study.standard_error() << "; scatter "
            << study.standard_error() * std::sqrt(study.runs) << ", mean stated error " << study.sum_sigma / study.runs
            << '\n';
  EXPECT_GE(study.fraction_within(), 0.9);
  EXPECT_LE(std::abs(study.mean()), 2.0 * study.standard_error());
}

TEST(Tempering, EvidenceErrorIsHonestForAGaussian) {
  const GaussianProblem problem;
  expect_honest_evidence(problem.density(), problem.log_evidence(), evidence_ladder(16, 1e4), problem.data, 1000);
}

TEST(Tempering, EvidenceErrorIsHonestAgainstQuadrature) {
  const DecayProblem problem;
  const double exact = problem.quadrature(2000);
  EXPECT_NEAR(exact, problem.quadrature(1000), 1e-3) << "the reference itself is not converged";
  expect_honest_evidence(problem.density(), exact, evidence_ladder(24, 1e6),
                         Eigen::Vector2d(std::log(1.5), std::log(0.7)), 1000);
}

// With the ladder adapted during the burn-in the evidence stays honest: the kept steps all use the
// final ladder, and stepping stones hold for any ladder.
TEST(Tempering, EvidenceErrorIsHonestWithAnAdaptedLadder) {
  const DecayProblem problem;
  expect_honest_evidence(problem.density(), problem.quadrature(2000), evidence_ladder(24, 1e6),
                         Eigen::Vector2d(std::log(1.5), std::log(0.7)), 2000, 500);
}

// VFM16's adaptation evens out the swap rates of a geometric ladder: on the decay problem the
// rates of a fixed ladder spread widely between its cold and hot ends; after 1000 adapted steps
// the spread over the kept steps is at most half of that, the slowest pair swaps more often, and
// beta = 1, the smallest beta > 0 and beta = 0 stay where they were.
TEST(Tempering, AdaptedLadderEvensOutTheSwapRates) {
  const DecayProblem problem;
  TemperingOptions options;
  options.betas = evidence_ladder(12, 1e6);
  options.ensemble.steps = 3000;
  const auto start = start_ball(Eigen::Vector2d(std::log(1.5), std::log(0.7)), Eigen::Vector2d(0.01, 0.01),
                                options.ensemble);
  const TemperedRun fixed = sample_tempered(problem.density(), start, options);
  options.adapt_steps = 500;
  const TemperedRun adapted = sample_tempered(problem.density(), start, options);
  // The pairs among beta > 0: the last pair, to the prior's rung, is not adapted.
  const auto finite_pairs = [](const TemperedRun& run) { return run.swap_acceptance.head(run.swap_acceptance.size() - 1); };
  const auto spread = [&](const TemperedRun& run) { return finite_pairs(run).maxCoeff() - finite_pairs(run).minCoeff(); };
  std::cout << "  swap rates, fixed ladder:   " << fixed.swap_acceptance.transpose() << "\n  swap rates, adapted ladder: "
            << adapted.swap_acceptance.transpose() << '\n';
  EXPECT_LT(spread(adapted), 0.5 * spread(fixed));
  EXPECT_GT(finite_pairs(adapted).minCoeff(), finite_pairs(fixed).minCoeff());
  EXPECT_EQ(adapted.betas.front(), 1.0);
  EXPECT_EQ(adapted.betas[adapted.betas.size() - 2], options.betas[options.betas.size() - 2]);
  EXPECT_EQ(adapted.betas.back(), 0.0);
  for (std::size_t i = 1; i < adapted.betas.size(); ++i) EXPECT_LT(adapted.betas[i], adapted.betas[i - 1]);
  EXPECT_NE(adapted.betas, options.betas);
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

  const TemperedRun tempered = sample_tempered({flat_prior, two_modes, {}}, start, options);
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
  options.betas = evidence_ladder(6, 1e3);
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
  // The ladder's adaptation uses only the swaps, drawn in the same order for any thread count.
  options.adapt_steps = 30;
  const TemperedRun adapted_threaded = sample_tempered(problem.density(), start, options);
  options.ensemble.threads = 1;
  const TemperedRun adapted_serial = sample_tempered(problem.density(), start, options);
  EXPECT_EQ(adapted_serial.betas, adapted_threaded.betas);
  EXPECT_NE(adapted_serial.betas, serial.betas);
  EXPECT_EQ(thermodynamic_evidence(adapted_serial).log_evidence, thermodynamic_evidence(adapted_threaded).log_evidence);
}

// <ln L>_beta never decreases with beta, so ln Z = integral_0^1 <ln L>_beta d beta can never exceed
// <ln L> at beta = 1. A hot level whose ln L scatters wildly (an ensemble far from converged) must
// not let the end correction of the trapezoid rule (its variance term) push the thermodynamic
// integral above that.
TEST(Tempering, EvidenceStaysBelowTheColdMeanWhateverTheHotVariances) {
  TemperedRun run;
  run.betas = {1.0, 0.1, 0.0};
  run.log_likelihood.resize(3);
  for (int walker = 0; walker < 8; ++walker) {
    run.log_likelihood[0].push_back(Eigen::VectorXd::Constant(100, -1.0));
    Eigen::VectorXd scattered(100);
    for (Eigen::Index k = 0; k < scattered.size(); ++k) scattered(k) = (k + walker) % 2 == 0 ? -1001.0 : 999.0;
    run.log_likelihood[1].push_back(scattered);
    run.log_likelihood[2].push_back(Eigen::VectorXd::Constant(100, -1.0));
  }
  const Evidence evidence = thermodynamic_evidence(run);
  EXPECT_LE(evidence.thermodynamic_integration, -1.0 + 1e-12);
  EXPECT_GE(evidence.thermodynamic_integration, -1.0 - 1e-12);  // both levels have mean -1: so has every beta
}

// The evidence needs the prior's own rung: a ladder that stops above beta = 0 is refused.
TEST(Tempering, EvidenceNeedsTheBetaZeroRung) {
  TemperedRun run;
  run.betas = {1.0, 0.1};
  run.log_likelihood.assign(2, std::vector<Eigen::VectorXd>(8, Eigen::VectorXd::Constant(10, -1.0)));
  expect_refusal<std::invalid_argument>([&] { (void)thermodynamic_evidence(run); }, {"beta = 0", "evidence_ladder"});
}

// A run length that adapts: the stop test is asked every check_every steps with the run so far
// (its first half as burn-in), and the run ends at its first yes.
TEST(Tempering, StopsWhenTheStopTestSaysSo) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = evidence_ladder(6, 1e3);
  options.ensemble.steps = 10000;
  options.ensemble.check_every = 100;
  std::vector<int> asked;
  options.stop = [&asked](const TemperedRun& so_far) {
    asked.push_back(so_far.steps);
    EXPECT_EQ(so_far.levels.front().chains.front().rows(), so_far.steps - so_far.steps / 2);
    return so_far.steps >= 300;
  };
  const TemperedRun run = sample_tempered(problem.density(), start_ball(problem.data, Eigen::Vector2d(0.1, 0.1),
                                                                        options.ensemble), options);
  EXPECT_EQ(asked, (std::vector<int>{100, 200, 300}));
  EXPECT_EQ(run.steps, 300);
  EXPECT_EQ(run.levels.front().chains.front().rows(), 150);
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
  options.betas = {1.0, 0.0, 0.0};
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"> 0"});
  options.betas.clear();
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered({problem.density().log_prior, {}, {}}, start, options); },
                                        {"log likelihood"});
  options.ensemble.steps = 100;
  options.adapt_steps = 30;
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"adapt_steps = 30", "burn-in of 50"});
}

// The evidence's accuracy was established with the stretch move on every rung; other moves are refused.
TEST(Tempering, RefusesMovesOtherThanTheStretch) {
  const GaussianProblem problem;
  TemperingOptions options;
  options.betas = evidence_ladder(4, 100.0);
  options.ensemble.moves = differential_moves();
  const auto start = start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), options.ensemble);
  expect_refusal<std::invalid_argument>([&] { (void)sample_tempered(problem.density(), start, options); },
                                        {"stretch move only"});
}

}  // namespace
}  // namespace sedwave::sampling
