#pragma once
// Posterior summaries from pooled draws: per-parameter mean, standard deviation, median and central
// intervals; covariance and correlation matrices; marginal density histograms (CSV-ready).
// Manual: docs/sampling.md.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sedwave::sampling {

/// All walkers' draws stacked: (walkers * kept steps) x dim, walker after walker.
[[nodiscard]] Eigen::MatrixXd pooled_samples(const std::vector<Eigen::MatrixXd>& chains);

/// The p-quantile of `values`, linear between order statistics (Hyndman & Fan 1996, Am. Stat. 50,
/// 361, definition 7, the default of R and NumPy). p in [0, 1].
[[nodiscard]] double quantile(const Eigen::VectorXd& values, double p);

struct Interval {
  double lower = 0.0;
  double upper = 0.0;
};

/// Central intervals hold the middle 68.27 % (the normal's +-1 sigma mass) and 95 % of the draws.
struct ParameterSummary {
  double mean = 0.0;
  double standard_deviation = 0.0;
  double median = 0.0;
  Interval central68;
  Interval central95;
};

/// One summary per column of `samples` (draws x dim).
[[nodiscard]] std::vector<ParameterSummary> summarize(const Eigen::MatrixXd& samples);

/// Sample covariance (divisor draws - 1) and correlation of the columns of `samples`.
[[nodiscard]] Eigen::MatrixXd covariance_matrix(const Eigen::MatrixXd& samples);
[[nodiscard]] Eigen::MatrixXd correlation_matrix(const Eigen::MatrixXd& samples);

/// A marginal density estimate: bins of equal width between edges(0) and edges(bins); density
/// integrates to the fraction of draws inside [edges(0), edges(bins)] (1 with the default range).
struct Histogram {
  Eigen::VectorXd edges;    ///< bins + 1 bin edges
  Eigen::VectorXd density;  ///< per bin: count / (all draws * width)
  /// "lower,upper,density" header and one line per bin.
  [[nodiscard]] std::string csv() const;
};

/// Histogram of `values` over [min, max] of the values.
[[nodiscard]] Histogram marginal_histogram(const Eigen::VectorXd& values, int bins);
/// Histogram of `values` over [lower, upper]; draws outside are counted in no bin.
[[nodiscard]] Histogram marginal_histogram(const Eigen::VectorXd& values, int bins, double lower, double upper);

}  // namespace sedwave::sampling
