#include "sedwave/sampling/summary.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sedwave::sampling {

namespace {

// Normal probability mass within one standard deviation: erf(1/sqrt 2).
constexpr double kOneSigmaMass = 0.6826894921370859;

// Hyndman & Fan definition 7 on already sorted values.
double sorted_quantile(const Eigen::VectorXd& sorted, double p) {
  const double position = p * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<Eigen::Index>(std::floor(position));
  const Eigen::Index above = std::min(below + 1, sorted.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return sorted(below) + fraction * (sorted(above) - sorted(below));
}

Interval central_interval(const Eigen::VectorXd& sorted, double mass) {
  return {sorted_quantile(sorted, 0.5 * (1.0 - mass)), sorted_quantile(sorted, 0.5 * (1.0 + mass))};
}

ParameterSummary summarize_column(Eigen::VectorXd values) {
  ParameterSummary summary;
  summary.mean = values.mean();
  summary.standard_deviation =
      std::sqrt((values.array() - summary.mean).square().sum() / static_cast<double>(values.size() - 1));
  std::sort(values.begin(), values.end());
  summary.median = sorted_quantile(values, 0.5);
  summary.central68 = central_interval(values, kOneSigmaMass);
  summary.central95 = central_interval(values, 0.95);
  return summary;
}

}  // namespace

Eigen::MatrixXd pooled_samples(const std::vector<Eigen::MatrixXd>& chains) {
  if (chains.empty()) throw std::invalid_argument("no chains to pool");
  const Eigen::Index steps = chains.front().rows();
  Eigen::MatrixXd pooled(steps * static_cast<Eigen::Index>(chains.size()), chains.front().cols());
  for (std::size_t k = 0; k < chains.size(); ++k) {
    pooled.middleRows(static_cast<Eigen::Index>(k) * steps, steps) = chains[k];
  }
  return pooled;
}

double quantile(const Eigen::VectorXd& values, double p) {
  if (values.size() == 0 || !(p >= 0.0 && p <= 1.0)) throw std::invalid_argument("quantile: need values and p in [0, 1]");
  Eigen::VectorXd sorted = values;
  std::sort(sorted.begin(), sorted.end());
  return sorted_quantile(sorted, p);
}

std::vector<ParameterSummary> summarize(const Eigen::MatrixXd& samples) {
  if (samples.rows() < 2) throw std::invalid_argument("summarize: need at least two draws");
  std::vector<ParameterSummary> summaries;
  for (Eigen::Index i = 0; i < samples.cols(); ++i) summaries.push_back(summarize_column(samples.col(i)));
  return summaries;
}

Eigen::MatrixXd covariance_matrix(const Eigen::MatrixXd& samples) {
  if (samples.rows() < 2) throw std::invalid_argument("covariance_matrix: need at least two draws");
  const Eigen::MatrixXd centred = samples.rowwise() - samples.colwise().mean();
  return centred.transpose() * centred / static_cast<double>(samples.rows() - 1);
}

Eigen::MatrixXd correlation_matrix(const Eigen::MatrixXd& samples) {
  const Eigen::MatrixXd covariance = covariance_matrix(samples);
  const Eigen::VectorXd inverse_sd = covariance.diagonal().cwiseSqrt().cwiseInverse();
  return inverse_sd.asDiagonal() * covariance * inverse_sd.asDiagonal();
}

std::string Histogram::csv() const {
  std::ostringstream text;
  text.precision(10);
  text << "lower,upper,density\n";
  for (Eigen::Index b = 0; b < density.size(); ++b) text << edges(b) << ',' << edges(b + 1) << ',' << density(b) << '\n';
  return text.str();
}

Histogram marginal_histogram(const Eigen::VectorXd& values, int bins) {
  if (values.size() == 0) throw std::invalid_argument("marginal_histogram: no values");
  return marginal_histogram(values, bins, values.minCoeff(), values.maxCoeff());
}

Histogram marginal_histogram(const Eigen::VectorXd& values, int bins, double lower, double upper) {
  if (bins < 1 || !(upper > lower) || values.size() == 0) {
    throw std::invalid_argument("marginal_histogram: need values, bins >= 1 and upper > lower");
  }
  Histogram histogram;
  histogram.edges = Eigen::VectorXd::LinSpaced(bins + 1, lower, upper);
  histogram.density = Eigen::VectorXd::Zero(bins);
  const double width = (upper - lower) / bins;
  for (const double value : values) {
    if (!(value >= lower && value <= upper)) continue;
    const auto bin = std::min(static_cast<Eigen::Index>((value - lower) / width), Eigen::Index{bins - 1});
    histogram.density(bin) += 1.0;
  }
  histogram.density /= static_cast<double>(values.size()) * width;
  return histogram;
}

}  // namespace sedwave::sampling
