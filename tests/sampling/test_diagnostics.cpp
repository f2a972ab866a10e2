// Convergence diagnostics on series with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sampling_test_support.hpp"
#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::sampling {
namespace {

Eigen::VectorXd normal_series(Eigen::Index n, double mean, double sd, RandomStream& random) {
  Eigen::VectorXd series(n);
  for (double& x : series) x = mean + sd * random.normal();
  return series;
}

// AR(1): x_t = rho x_{t-1} + sqrt(1 - rho^2) e_t, stationary unit variance; its integrated
// autocorrelation time is (1 + rho) / (1 - rho) (e.g. Sokal 1997, eq. 2.21 with rho(t) = rho^|t|).
Eigen::VectorXd ar1_series(Eigen::Index n, double rho, RandomStream& random) {
  Eigen::VectorXd series(n);
  double x = random.normal();
  const double innovation = std::sqrt(1.0 - rho * rho);
  for (double& value : series) {
    x = rho * x + innovation * random.normal();
    value = x;
  }
  return series;
}

TEST(Diagnostics, RhatOfWellMixedChainsIsOne) {
  RandomStream random(11);
  std::vector<Eigen::VectorXd> chains;
  for (int k = 0; k < 4; ++k) chains.push_back(normal_series(5000, 2.0, 3.0, random));
  EXPECT_NEAR(split_rhat(chains), 1.0, 0.01);
  EXPECT_LT(rank_normalized_rhat(chains), 1.01);
}

// Two walkers stuck in separate modes, N(-5, 1) and N(+5, 1): R-hat far above 1, no convergence,
// and the advice names R-hat and multimodality.
TEST(Diagnostics, UnmixedChainsAreFlagged) {
  RandomStream random(12);
  const std::vector<Eigen::VectorXd> chains{normal_series(2000, -5.0, 1.0, random),
                                            normal_series(2000, 5.0, 1.0, random)};
  EXPECT_GT(split_rhat(chains), 3.0);
  EXPECT_GT(rank_normalized_rhat(chains), 1.5);

  std::vector<Eigen::MatrixXd> walkers;
  for (const Eigen::VectorXd& chain : chains) walkers.emplace_back(chain);
  const Convergence verdict = assess_convergence(diagnose(walkers, 0.4));
  EXPECT_FALSE(verdict.converged);
  EXPECT_NE(verdict.advice.find("R-hat"), std::string::npos) << verdict.advice;
  EXPECT_NE(verdict.advice.find("multimodal"), std::string::npos) << verdict.advice;
}

// A drift inside each chain (first half lower than the second): only splitting the chains sees it.
TEST(Diagnostics, SplitRhatSeesATrendWithinChains) {
  RandomStream random(13);
  std::vector<Eigen::VectorXd> chains;
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd chain = normal_series(2000, 0.0, 1.0, random);
    chain.tail(1000).array() += 2.0;
    chains.push_back(chain);
  }
  EXPECT_GT(split_rhat(chains), 1.3);
}

// Same location, different scale: the classic R-hat compares means only; the rank-normalised one's
// folded ("tail") part catches it (V21 section 4.2).
TEST(Diagnostics, RankNormalizedRhatSeesDifferentScales) {
  RandomStream random(14);
  std::vector<Eigen::VectorXd> chains;
  for (int k = 0; k < 4; ++k) chains.push_back(normal_series(4000, 0.0, k < 2 ? 1.0 : 3.0, random));
  EXPECT_LT(split_rhat(chains), 1.01);
  EXPECT_GT(rank_normalized_rhat(chains), 1.1);
}

// ESS of one AR(1) series = N (1 - rho) / (1 + rho) within 10 % (the estimator's own relative
// spread, sqrt(2 (2M + 1) / N) with window M ~ 5 tau (Sokal 1997 eq. 3.19), is 3 % at rho = 0.9).
TEST(Diagnostics, EffectiveSampleSizeOfAnAR1Series) {
  RandomStream random(15);
  const Eigen::Index n = 400000;
  for (const double rho : {0.0, 0.5, 0.9}) {
    const std::vector<Eigen::VectorXd> chain{ar1_series(n, rho, random)};
    const double expected_ess = static_cast<double>(n) * (1.0 - rho) / (1.0 + rho);
    const double ess = static_cast<double>(n) / autocorrelation_time(chain);
    EXPECT_NEAR(ess / expected_ess, 1.0, 0.1) << "rho = " << rho;
  }
}

// Averaging the autocorrelation over walkers: 8 independent AR(1) walkers give the same tau as one.
TEST(Diagnostics, AutocorrelationTimeAveragesOverWalkers) {
  RandomStream random(16);
  std::vector<Eigen::VectorXd> chains;
  for (int k = 0; k < 8; ++k) chains.push_back(ar1_series(50000, 0.8, random));
  EXPECT_NEAR(autocorrelation_time(chains), 9.0, 0.9);
}

TEST(Diagnostics, WellMixedChainsConverge) {
  RandomStream random(17);
  std::vector<Eigen::MatrixXd> walkers;
  for (int k = 0; k < 16; ++k) {
    Eigen::MatrixXd chain(1000, 2);
    chain.col(0) = ar1_series(1000, 0.5, random);
    chain.col(1) = normal_series(1000, 1.0, 2.0, random);
    walkers.push_back(chain);
  }
  const Diagnostics diagnostics = diagnose(walkers, 0.35);
  EXPECT_NEAR(diagnostics.autocorrelation_time(0), 3.0, 0.5);
  EXPECT_NEAR(diagnostics.ess(1), 16000.0, 2000.0);
  const Convergence verdict = assess_convergence(diagnostics);
  EXPECT_TRUE(verdict.converged) << verdict.advice;
  EXPECT_NE(verdict.advice.find("converged"), std::string::npos);
}

// Columns that are named (a caller's parameters and derived quantities) are named in the advice.
TEST(Diagnostics, AdviceNamesTheColumnsItWasGiven) {
  RandomStream random(19);
  std::vector<Eigen::MatrixXd> walkers;
  for (int k = 0; k < 16; ++k) {
    Eigen::MatrixXd chain(100, 2);
    chain.col(0) = normal_series(100, 0.0, 1.0, random);
    chain.col(1) = ar1_series(100, 0.95, random);
    walkers.push_back(chain);
  }
  Diagnostics diagnostics = diagnose(walkers, 0.4);
  diagnostics.names = {"kappa", "f_star"};
  const Convergence verdict = assess_convergence(diagnostics);
  EXPECT_FALSE(verdict.converged);
  EXPECT_NE(verdict.advice.find("f_star: effective sample size"), std::string::npos) << verdict.advice;
  EXPECT_EQ(verdict.advice.find("parameter 1"), std::string::npos) << verdict.advice;
}

// Too short a run: the advice asks for more steps, says how far it got and how many it needs; a very
// low acceptance is remarked on.
TEST(Diagnostics, ShortRunAdviceSaysHowManySteps) {
  RandomStream random(18);
  std::vector<Eigen::MatrixXd> walkers;
  for (int k = 0; k < 16; ++k) walkers.emplace_back(ar1_series(100, 0.95, random));
  const Convergence verdict = assess_convergence(diagnose(walkers, 0.05));
  EXPECT_FALSE(verdict.converged);
  for (const char* part : {"effective sample size", "more steps", "Got 100 kept steps", "kept steps with 16 walkers",
                           "stuck"}) {
    EXPECT_NE(verdict.advice.find(part), std::string::npos) << part << " not in: " << verdict.advice;
  }
}

// Walkers that all sit at one value (a parameter the sampler never moved): R-hat has no variance to
// compare (0/0), and the advice says so instead of printing "R-hat nan".
TEST(Diagnostics, StuckWalkersGetWordsNotNan) {
  std::vector<Eigen::MatrixXd> walkers;
  for (int k = 0; k < 8; ++k) walkers.emplace_back(Eigen::MatrixXd::Constant(200, 1, 1.0));
  const Diagnostics diagnostics = diagnose(walkers, 0.0);
  const Convergence verdict = assess_convergence(diagnostics);
  EXPECT_FALSE(verdict.converged);
  EXPECT_EQ(verdict.advice.find("R-hat nan"), std::string::npos) << verdict.advice;
  EXPECT_EQ(verdict.advice.find("R-hat -nan"), std::string::npos) << verdict.advice;
  EXPECT_FALSE(std::isfinite(diagnostics.rhat(0)));  // the case this test is about
  EXPECT_NE(verdict.advice.find("R-hat cannot be computed"), std::string::npos) << verdict.advice;
}

}  // namespace
}  // namespace sedwave::sampling
