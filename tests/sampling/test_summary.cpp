// Posterior summaries on draws with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sedwave/sampling/random_stream.hpp"
#include "sedwave/sampling/summary.hpp"

namespace sedwave::sampling {
namespace {

TEST(Summary, QuantilesInterpolateBetweenOrderStatistics) {
  Eigen::VectorXd values(5);
  values << 5.0, 1.0, 4.0, 2.0, 3.0;
  EXPECT_DOUBLE_EQ(quantile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(values, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile(values, 0.125), 1.5);  // NumPy's default gives 1.5 too
  EXPECT_DOUBLE_EQ(quantile(values, 1.0), 5.0);
  EXPECT_THROW((void)quantile(values, 1.5), std::invalid_argument);
}

TEST(Summary, PoolsWalkersAndSummarizesEachParameter) {
  std::vector<Eigen::MatrixXd> chains(2, Eigen::MatrixXd(3, 2));
  chains[0] << 1, 10, 2, 20, 3, 30;
  chains[1] << 4, 40, 5, 50, 6, 60;
  const Eigen::MatrixXd pooled = pooled_samples(chains);
  ASSERT_EQ(pooled.rows(), 6);
  EXPECT_EQ(pooled(3, 1), 40.0);
  const std::vector<ParameterSummary> summaries = summarize(pooled);
  EXPECT_DOUBLE_EQ(summaries[0].mean, 3.5);
  EXPECT_DOUBLE_EQ(summaries[1].median, 35.0);
  EXPECT_NEAR(summaries[0].standard_deviation, std::sqrt(3.5), 1e-12);
  EXPECT_NEAR(correlation_matrix(pooled)(0, 1), 1.0, 1e-12);
}

// Independent normal draws: the summary's intervals and the correlation of a known mixing.
TEST(Summary, NormalDrawsGiveNormalIntervalsAndCorrelation) {
  RandomStream random(21);
  const Eigen::Index n = 200000;
  Eigen::MatrixXd draws(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = random.normal();
    const double b = random.normal();
    draws(i, 0) = a;
    draws(i, 1) = 0.6 * a + 0.8 * b;  // correlation 0.6
  }
  const ParameterSummary s = summarize(draws).front();
  // Quantile standard error sqrt(p (1 - p) / n) / phi(z): 0.003 at z = 1, 0.0055 at z = 1.96.
  EXPECT_NEAR(s.central68.lower, -1.0, 0.012);
  EXPECT_NEAR(s.central68.upper, 1.0, 0.012);
  EXPECT_NEAR(s.central95.lower, -1.959964, 0.022);
  EXPECT_NEAR(s.central95.upper, 1.959964, 0.022);
  EXPECT_NEAR(correlation_matrix(draws)(0, 1), 0.6, 4.0 * (1.0 - 0.36) / std::sqrt(static_cast<double>(n)));
}

TEST(Summary, HistogramIsADensityAndWritesCsv) {
  RandomStream random(22);
  Eigen::VectorXd values(10000);
  for (double& v : values) v = random.uniform();
  const Histogram histogram = marginal_histogram(values, 10);
  ASSERT_EQ(histogram.edges.size(), 11);
  const double width = histogram.edges(1) - histogram.edges(0);
  EXPECT_NEAR(histogram.density.sum() * width, 1.0, 1e-12);
  // Uniform on [0, 1): each bin's density 1 within 4 binomial standard errors, sqrt(p (1 - p) / n) / p
  // with p = 0.1 the bin's probability.
  EXPECT_LT((histogram.density.array() - 1.0).abs().maxCoeff(), 4.0 * std::sqrt(0.1 * 0.9 / 10000.0) / 0.1);
  const std::string csv = marginal_histogram(values, 2, 0.0, 2.0).csv();
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "lower,upper,density");
  EXPECT_NE(csv.find("\n0,1,1\n1,2,0\n"), std::string::npos) << csv;
  EXPECT_THROW((void)marginal_histogram(values, 0), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::sampling
