// The stretch-move ensemble sampler against targets with known moments (statistical tests, fixed
// seeds; tolerances are 4 Monte Carlo standard errors computed from the run's own effective sample
// size, so a correct sampler fails them with probability ~1e-4 per comparison).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "sampling_test_support.hpp"
#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/summary.hpp"

namespace sedwave::sampling {
namespace {

using testing::expect_refusal;
using testing::gaussian_log_density;

constexpr double kStandardErrors = 4.0;

// Sampled mean and covariance against the analytic ones. Monte Carlo standard errors with the
// smallest ESS of the run: mean_i sqrt(S_ii / ESS); covariance S_ij sqrt((S_ii S_jj + S_ij^2) / ESS)
// (the variance of a sample covariance of normal draws, Anderson 2003, An Introduction to
// Multivariate Statistical Analysis, 3rd ed., section 3.4).
void expect_gaussian_moments(const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance,
                             const EnsembleOptions& options) {
  const EnsembleRun run =
      sample(gaussian_log_density(mean, covariance),
             start_ball(mean, covariance.diagonal().cwiseSqrt() * 0.1, options), options);
  const Diagnostics diagnostics = diagnose(run);
  const double ess = diagnostics.ess.minCoeff();
  std::cout << "  dim " << mean.size() << ": acceptance " << run.acceptance << ", smallest ESS " << ess
            << ", largest R-hat " << diagnostics.rhat.maxCoeff() << '\n';
  const Convergence convergence = assess_convergence(diagnostics);
  EXPECT_TRUE(convergence.converged) << convergence.advice;
  ASSERT_GT(ess, 400.0);
  const Eigen::MatrixXd samples = pooled_samples(run.chains);
  const Eigen::VectorXd sampled_mean = samples.colwise().mean().transpose();
  const Eigen::MatrixXd sampled_covariance = covariance_matrix(samples);
  for (Eigen::Index i = 0; i < mean.size(); ++i) {
    EXPECT_NEAR(sampled_mean(i), mean(i), kStandardErrors * std::sqrt(covariance(i, i) / ess)) << "mean " << i;
    for (Eigen::Index j = 0; j < mean.size(); ++j) {
      const double error =
          std::sqrt((covariance(i, i) * covariance(j, j) + covariance(i, j) * covariance(i, j)) / ess);
      EXPECT_NEAR(sampled_covariance(i, j), covariance(i, j), kStandardErrors * error) << "covariance " << i << j;
    }
  }
}

// A thin ridge: correlation 0.99 between parameters of scales 1 and 100 (affine invariance makes it
// no harder than a round Gaussian).
TEST(Ensemble, CorrelatedGaussian2D) {
  Eigen::Vector2d mean(1.0, -20.0);
  Eigen::Matrix2d covariance;
  covariance << 1.0, 0.99 * 100.0, 0.99 * 100.0, 1.0e4;
  EnsembleOptions options;
  options.steps = 4000;
  expect_gaussian_moments(mean, covariance, options);
}

TEST(Ensemble, CorrelatedGaussian5D) {
  Eigen::VectorXd mean(5);
  mean << 0.0, 1.0, -2.0, 3.0, 10.0;
  Eigen::MatrixXd mixing(5, 5);
  mixing << 1.0, 0.0, 0.0, 0.0, 0.0,  //
      0.8, 0.6, 0.0, 0.0, 0.0,        //
      -0.5, 0.3, 0.4, 0.0, 0.0,       //
      2.0, -1.0, 0.5, 0.3, 0.0,       //
      0.1, 0.2, 0.3, 0.4, 5.0;
  const Eigen::MatrixXd covariance = mixing * mixing.transpose();
  EnsembleOptions options;
  options.steps = 8000;
  options.seed = 7;
  expect_gaussian_moments(mean, covariance, options);
}

// The 68.27 % and 95 % central intervals of N(3, 2^2): endpoints at 3 -+ 2 and 3 -+ 1.96 * 2 within
// 4 standard errors of a quantile, sqrt(p (1 - p) / ESS) / phi(z_p) sigma; the normal mass inside
// each sampled interval within 4 sqrt(m (1 - m) / ESS) of m (the mass between two order statistics
// is Beta distributed with that spread).
TEST(Ensemble, CentralIntervalsOfA1DGaussianHoldTheRightMass) {
  const double mu = 3.0;
  const double sigma = 2.0;
  EnsembleOptions options;
  options.steps = 6000;
  const EnsembleRun run = sample([&](const Eigen::VectorXd& x) { return -0.5 * std::pow((x(0) - mu) / sigma, 2); },
                                 start_ball(Eigen::VectorXd::Constant(1, mu), Eigen::VectorXd::Constant(1, 0.5), options),
                                 options);
  const double ess = diagnose(run).ess(0);
  ASSERT_GT(ess, 400.0);
  const ParameterSummary summary = summarize(pooled_samples(run.chains)).front();
  const auto normal_cdf = [&](double x) { return 0.5 * std::erfc(-(x - mu) / (sigma * std::sqrt(2.0))); };
  const auto normal_pdf = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI); };
  struct Case {
    Interval interval;
    double mass;
    double z;
  };
  for (const Case& c : {Case{summary.central68, 0.6826894921370859, 1.0}, Case{summary.central95, 0.95, 1.959963985}}) {
    const double tail = 0.5 * (1.0 - c.mass);
    const double endpoint_error = kStandardErrors * std::sqrt(tail * (1.0 - tail) / ess) / normal_pdf(c.z) * sigma;
    EXPECT_NEAR(c.interval.lower, mu - c.z * sigma, endpoint_error);
    EXPECT_NEAR(c.interval.upper, mu + c.z * sigma, endpoint_error);
    const double mass = normal_cdf(c.interval.upper) - normal_cdf(c.interval.lower);
    EXPECT_NEAR(mass, c.mass, kStandardErrors * std::sqrt(c.mass * (1.0 - c.mass) / ess));
  }
  EXPECT_NEAR(summary.median, mu, kStandardErrors * std::sqrt(0.25 / ess) / normal_pdf(0.0) * sigma);
}

// Goodman & Weare's Rosenbrock density (GW10 eq. 21): p ~ exp(-(100 (x2 - x1^2)^2 + (1 - x1)^2) / 20).
// Integrating x2 out: x1 ~ N(1, 10) and x2 | x1 ~ N(x1^2, 0.1), so E x1 = 1, var x1 = 10,
// E x2 = 11, var x2 = E x1^4 - 121 + 0.1 = 240.1. A long curved banana with a heavy x2 tail: tau is
// thousands of updates, so a run of test length is not converged by the criteria (R-hat is
// printed, as is the advice) but must follow the banana without diverging, keep the walkers
// together (R-hat < 1.3) and reproduce these moments within 4 standard errors of its own ESS.
TEST(Ensemble, RosenbrockBananaIsFollowed) {
  const LogDensity rosenbrock = [](const Eigen::VectorXd& x) {
    return -(100.0 * std::pow(x(1) - x(0) * x(0), 2) + std::pow(1.0 - x(0), 2)) / 20.0;
  };
  EnsembleOptions options;
  options.walkers = 32;
  options.steps = 60000;
  options.burn_in = 10000;  // started on the ridge near the mode (1, 1)
  options.seed = 3;
  const EnsembleRun run = sample(rosenbrock, start_ball(Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.1, 0.1), options),
                                 options);
  const Diagnostics diagnostics = diagnose(run);
  const Convergence convergence = assess_convergence(diagnostics);
  std::cout << "  Rosenbrock: R-hat " << diagnostics.rhat.transpose() << ", tau "
            << diagnostics.autocorrelation_time.transpose() << ", ESS " << diagnostics.ess.transpose()
            << ", acceptance " << run.acceptance << "\n  " << convergence.advice;
  const Eigen::MatrixXd samples = pooled_samples(run.chains);
  ASSERT_TRUE(samples.allFinite());
  EXPECT_LT(samples.cwiseAbs().maxCoeff(), 1e3);
  EXPECT_LT(diagnostics.rhat.maxCoeff(), 1.3);
  if (!convergence.converged) {
    EXPECT_NE(convergence.advice.find("more steps"), std::string::npos);
  }
  const Eigen::Vector2d mean = samples.colwise().mean().transpose();
  EXPECT_NEAR(mean(0), 1.0, kStandardErrors * std::sqrt(10.0 / diagnostics.ess(0)));
  EXPECT_NEAR(mean(1), 11.0, kStandardErrors * std::sqrt(240.1 / diagnostics.ess(1)));
}

TEST(Ensemble, SameSeedSameSamples) {
  EnsembleOptions options;
  options.steps = 200;
  const LogDensity density = gaussian_log_density(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  const auto start = start_ball(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), options);
  const EnsembleRun first = sample(density, start, options);
  const EnsembleRun second = sample(density, start, options);
  ASSERT_EQ(first.chains.size(), second.chains.size());
  for (std::size_t k = 0; k < first.chains.size(); ++k) {
    EXPECT_EQ(first.chains[k], second.chains[k]);
    EXPECT_EQ(first.log_density[k], second.log_density[k]);
  }
  EXPECT_EQ(first.evaluations, second.evaluations);
  options.seed = 2;
  EXPECT_NE(sample(density, start, options).chains.front(), first.chains.front());
}

/// The run on 1 thread and on 3 gives the same chains bit for bit, with the same number of
/// evaluations (every draw is made before the evaluations are shared out); returns the 1-thread run.
EnsembleRun expect_samples_independent_of_threads(const LogDensity& density,
                                                  const std::vector<Eigen::VectorXd>& start, EnsembleOptions options) {
  options.threads = 1;
  EnsembleRun serial = sample(density, start, options);
  options.threads = 3;
  const EnsembleRun threaded = sample(density, start, options);
  for (std::size_t k = 0; k < serial.chains.size(); ++k) EXPECT_EQ(serial.chains[k], threaded.chains[k]);
  EXPECT_EQ(serial.evaluations, threaded.evaluations);
  return serial;
}

// Threads share the evaluations of each half-ensemble; the draws are made before, so the samples
// must be the same bit for bit whatever the thread count.
TEST(Ensemble, ThreadsDoNotChangeTheSamples) {
  EnsembleOptions options;
  options.steps = 200;
  const LogDensity density = gaussian_log_density(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  const auto start = start_ball(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), options);
  expect_samples_independent_of_threads(density, start, options);
  options.threads = 0;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, options); }, {"threads = 0"});
}

TEST(Ensemble, RecordsWhatItKeeps) {
  EnsembleOptions options;
  options.steps = 100;
  options.burn_in = 30;
  const auto start = start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), options);
  const EnsembleRun run = sample(gaussian_log_density(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity()), start,
                                 options);
  ASSERT_EQ(run.chains.size(), 16u);
  EXPECT_EQ(run.chains.front().rows(), 70);
  EXPECT_EQ(run.chains.front().cols(), 2);
  EXPECT_EQ(run.evaluations, 16 + 16 * 100);
  EXPECT_NEAR(run.log_density[3](10), -0.5 * run.chains[3].row(10).squaredNorm(), 1e-12);
  EXPECT_GT(run.acceptance, 0.2);
  EXPECT_LT(run.acceptance, 0.9);
}

// A bounded support: proposals outside are refused and the density is never asked about them twice.
TEST(Ensemble, StaysInsideTheSupport) {
  const LogDensity box = [](const Eigen::VectorXd& x) {
    return (x.array().abs() <= 1.0).all() ? 0.0 : -std::numeric_limits<double>::infinity();
  };
  EnsembleOptions options;
  options.steps = 2000;
  const EnsembleRun run = sample(box, start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(0.2), options),
                                 options);
  const Eigen::MatrixXd samples = pooled_samples(run.chains);
  EXPECT_LE(samples.cwiseAbs().maxCoeff(), 1.0);
  const double ess = diagnose(run).ess.minCoeff();
  // Uniform on [-1, 1]: variance 1/3; the sample variance of uniform draws has sd sqrt(4/45 / ESS).
  const Eigen::MatrixXd covariance = covariance_matrix(samples);
  EXPECT_NEAR(covariance(0, 0), 1.0 / 3.0, kStandardErrors * std::sqrt(4.0 / 45.0 / ess));
}

// Walkers near the largest doubles: some proposals overflow to infinity; they are refused without
// asking the density, which is never called with a non-finite coordinate.
TEST(Ensemble, NeverAsksAboutNonFinitePoints) {
  int non_finite_calls = 0;
  const LogDensity flat = [&](const Eigen::VectorXd& x) {
    if (!x.allFinite()) ++non_finite_calls;
    return 0.0;
  };
  EnsembleOptions options;
  options.steps = 200;
  const EnsembleRun run = sample(flat, start_ball(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 5e307), options),
                                 options);
  EXPECT_EQ(non_finite_calls, 0);
  EXPECT_LT(run.evaluations, 16 + 16 * 200);  // the overflowing proposals were not evaluated
  EXPECT_TRUE(pooled_samples(run.chains).allFinite());
}

// A run length that adapts to the target: checked every 250 steps, it stops at the first check where
// the kept half (the burn-in is the first half) passes the convergence criteria, well before its cap,
// and the draws then have the target's moments.
TEST(Ensemble, RunsUntilConverged) {
  const Eigen::Vector3d mean(1.0, -2.0, 0.5);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(1.0, 4.0, 0.25).asDiagonal();
  EnsembleOptions options;
  options.steps = 50000;
  options.check_every = 250;
  int checks = 0;
  options.stop = [&checks](const EnsembleRun& so_far) {
    ++checks;
    EXPECT_EQ(so_far.chains.front().rows(), so_far.steps - so_far.steps / 2);
    return assess_convergence(diagnose(so_far)).converged;
  };
  const EnsembleRun run =
      sample(gaussian_log_density(mean, covariance), start_ball(mean, Eigen::Vector3d::Constant(0.01), options), options);
  const Diagnostics diagnostics = diagnose(run);
  std::cout << "  converged after " << run.steps << " steps (" << checks << " checks); largest tau "
            << diagnostics.autocorrelation_time.maxCoeff() << ", acceptance " << run.acceptance << '\n';
  EXPECT_TRUE(assess_convergence(diagnostics).converged);
  EXPECT_LT(run.steps, options.steps);
  EXPECT_EQ(run.steps % 250, 0);
  EXPECT_EQ(checks, run.steps / 250);
  const Eigen::Vector3d sampled = pooled_samples(run.chains).colwise().mean().transpose();
  for (Eigen::Index i = 0; i < 3; ++i) {
    EXPECT_NEAR(sampled(i), mean(i), kStandardErrors * std::sqrt(covariance(i, i) / diagnostics.ess(i)));
  }
  // The stop depends on the samples only: on 2 threads the run stops at the same step, bit for bit.
  options.threads = 2;
  const EnsembleRun threaded =
      sample(gaussian_log_density(mean, covariance), start_ball(mean, Eigen::Vector3d::Constant(0.01), options), options);
  EXPECT_EQ(threaded.steps, run.steps);
  for (std::size_t k = 0; k < run.chains.size(); ++k) EXPECT_EQ(threaded.chains[k], run.chains[k]);
}

// The differential-evolution moves (ter Braak 2006) and the snooker (ter Braak & Vrugt 2008, whose
// proposal is not symmetric: its Jacobian factor must be right), each alone and in the inversion's
// mixture, keep a correlated Gaussian's mean and covariance.
TEST(Ensemble, DifferentialMovesSampleACorrelatedGaussian) {
  Eigen::Vector3d mean(1.0, -20.0, 0.5);
  Eigen::Matrix3d mixing;
  mixing << 1.0, 0.0, 0.0,  //
      99.0, 14.1, 0.0,      //
      -0.5, 0.3, 0.2;
  const Eigen::Matrix3d covariance = mixing * mixing.transpose();
  for (const MoveMix& moves : {MoveMix{0.0, 1.0, 0.0}, MoveMix{0.0, 0.0, 1.0}, differential_moves()}) {
    EnsembleOptions options;
    options.moves = moves;
    options.steps = 6000;
    options.seed = 11;
    SCOPED_TRACE("moves: de " + std::to_string(moves.differential_evolution) + ", snooker " +
                 std::to_string(moves.snooker));
    expect_gaussian_moments(mean, covariance, options);
  }
}

// A curved ridge with closed-form moments, Haario, Saksman & Tamminen's twisted Gaussian (1999,
// Comput. Stat. 14, 375): x1 ~ N(0, 100), x2 + b (x1^2 - 100) ~ N(0, 1) with b = 0.03, so E x = 0,
// var x1 = 100, var x2 = 1 + b^2 var(x1^2) = 1 + 2 b^2 100^2 = 19.
TEST(Ensemble, DifferentialMovesFollowACurvedRidge) {
  const double b = 0.03;
  const LogDensity banana = [b](const Eigen::VectorXd& x) {
    const double y = x(1) + b * (x(0) * x(0) - 100.0);
    return -0.5 * (x(0) * x(0) / 100.0 + y * y);
  };
  EnsembleOptions options;
  options.moves = differential_moves();
  options.walkers = 32;
  options.steps = 20000;
  options.seed = 5;
  const EnsembleRun run = sample(banana, start_ball(Eigen::Vector2d(0.0, 3.0), Eigen::Vector2d(1.0, 0.3), options),
                                 options);
  const Diagnostics diagnostics = diagnose(run);
  std::cout << "  twisted Gaussian: tau " << diagnostics.autocorrelation_time.transpose() << ", ESS "
            << diagnostics.ess.transpose() << ", acceptance " << run.acceptance << '\n';
  EXPECT_TRUE(assess_convergence(diagnostics).converged) << assess_convergence(diagnostics).advice;
  const Eigen::MatrixXd samples = pooled_samples(run.chains);
  const Eigen::Vector2d sampled_mean = samples.colwise().mean().transpose();
  const Eigen::MatrixXd sampled_covariance = covariance_matrix(samples);
  EXPECT_NEAR(sampled_mean(0), 0.0, kStandardErrors * std::sqrt(100.0 / diagnostics.ess(0)));
  EXPECT_NEAR(sampled_mean(1), 0.0, kStandardErrors * std::sqrt(19.0 / diagnostics.ess(1)));
  // The sample variance's error: var sqrt(2 / ESS) for x1 (normal); for x2, which is not normal, the
  // distribution-free sqrt((m4 - var^2) / ESS) with the sampled fourth central moment m4.
  EXPECT_NEAR(sampled_covariance(0, 0), 100.0, kStandardErrors * 100.0 * std::sqrt(2.0 / diagnostics.ess(0)));
  const double m4 = (samples.col(1).array() - sampled_mean(1)).pow(4).mean();
  EXPECT_NEAR(sampled_covariance(1, 1), 19.0, kStandardErrors * std::sqrt((m4 - 19.0 * 19.0) / diagnostics.ess(1)));
}

// The shape that made the stretch move slow on the inversion's unseen parameters: a long, thin
// ridge along (1, 1, 1) (sd 0.05 across it), cut off by a box [-10, 10]^3 (the priors' bounds). The
// ridge is linear, so no affine map makes it harder or easier; what hurts the stretch move is the
// box's corners, where most of its proposals leave the support. Over 6 seeds the largest tau of each
// run, with the differential mixture against the stretch move alone: the mixture's median is below
// half the stretch move's, and the mixture is faster on most seeds.
TEST(Ensemble, DifferentialMovesMixABoundedRidgeFasterThanTheStretchMove) {
  const LogDensity ridge = [](const Eigen::VectorXd& x) {
    if ((x.array().abs() > 10.0).any()) return -std::numeric_limits<double>::infinity();
    const double along = x.sum() / 3.0;
    return -0.5 * (x.array() - along).matrix().squaredNorm() / (0.05 * 0.05);
  };
  std::vector<double> stretch_taus, mixture_taus;
  int mixture_faster = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    EnsembleOptions options;
    options.steps = 6000;
    options.seed = seed;
    const auto start = start_ball(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.02), options);
    const double stretch_tau = diagnose(sample(ridge, start, options)).autocorrelation_time.maxCoeff();
    options.moves = differential_moves();
    const double mixture_tau = diagnose(sample(ridge, start, options)).autocorrelation_time.maxCoeff();
    std::cout << "  seed " << seed << ": tau stretch " << stretch_tau << ", differential mixture " << mixture_tau
              << '\n';
    stretch_taus.push_back(stretch_tau);
    mixture_taus.push_back(mixture_tau);
    mixture_faster += mixture_tau < stretch_tau ? 1 : 0;
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  EXPECT_LT(median(mixture_taus), 0.5 * median(stretch_taus));
  EXPECT_GE(mixture_faster, 5);
}

// Differential moves draw all their random numbers before evaluating: any thread count gives the
// same samples.
TEST(Ensemble, DifferentialMovesDoNotDependOnThreads) {
  EnsembleOptions options;
  options.steps = 300;
  options.moves = differential_moves();
  const LogDensity density = gaussian_log_density(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  const auto start = start_ball(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), options);
  const EnsembleRun serial = expect_samples_independent_of_threads(density, start, options);
  options.moves = {};
  EXPECT_NE(sample(density, start, options).chains.front(), serial.chains.front());
}

TEST(Ensemble, RefusesBadOptionsSayingWhatToChange) {
  const LogDensity density = gaussian_log_density(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  EnsembleOptions options;
  const auto start = start_ball(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), options);

  EnsembleOptions odd = options;
  odd.walkers = 17;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, odd); }, {"walkers = 17", "even"});
  EnsembleOptions too_few = options;
  too_few.walkers = 4;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, too_few); }, {"walkers = 4", ">= 6"});
  EnsembleOptions no_kept = options;
  no_kept.steps = 100;
  no_kept.burn_in = 100;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, no_kept); }, {"steps = 100", "exceed"});
  EnsembleOptions no_stop = options;
  no_stop.check_every = 100;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, no_stop); }, {"check_every", "stop"});
  EnsembleOptions fixed_burn_in = no_stop;
  fixed_burn_in.stop = [](const EnsembleRun&) { return true; };
  fixed_burn_in.burn_in = 50;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, fixed_burn_in); },
                                        {"burn_in = 50", "first half"});
  EnsembleOptions no_stretch = options;
  no_stretch.stretch = 1.0;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, no_stretch); }, {"stretch", "> 1"});

  expect_refusal<std::invalid_argument>(
      [&] { (void)sample(density, std::vector<Eigen::VectorXd>(start.begin(), start.begin() + 10), options); },
      {"10 start walkers", "16"});
  const LogDensity positive_half = [](const Eigen::VectorXd& x) {
    return x(0) > 0.0 ? 0.0 : -std::numeric_limits<double>::infinity();
  };
  expect_refusal<std::invalid_argument>([&] { (void)sample(positive_half, start, options); },
                                        {"outside the support"});
  // Walkers on one line of the plane: the stretch move could never leave it.
  std::vector<Eigen::VectorXd> on_a_line;
  for (int k = 0; k < 16; ++k) on_a_line.emplace_back(Eigen::Vector3d(k, 2.0 * k, 1.0 - k));
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, on_a_line, options); },
                                        {"lower-dimensional plane", "scatter"});
  std::vector<Eigen::VectorXd> flat = start;
  for (Eigen::VectorXd& walker : flat) walker(1) = 0.5;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, flat, options); }, {"parameter 1"});
  EnsembleOptions negative_weight = options;
  negative_weight.moves.snooker = -1.0;
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, negative_weight); },
                                        {"move weights", ">= 0"});
  EnsembleOptions no_weight = options;
  no_weight.moves = {0.0, 0.0, 0.0};
  expect_refusal<std::invalid_argument>([&] { (void)sample(density, start, no_weight); }, {"all 0"});
  EnsembleOptions snooker_few = options;
  snooker_few.moves = differential_moves();
  snooker_few.walkers = 4;
  const auto start_2d = start_ball(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), snooker_few);
  expect_refusal<std::invalid_argument>(
      [&] { (void)sample(gaussian_log_density(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity()), start_2d,
                         snooker_few); },
      {"walkers = 4", "at least 6"});
  const LogDensity broken = [](const Eigen::VectorXd&) { return std::numeric_limits<double>::quiet_NaN(); };
  expect_refusal<std::domain_error>([&] { (void)sample(broken, start, options); }, {"nan", "finite"});
}

}  // namespace
}  // namespace sedwave::sampling
