#include "prior_control.hpp"

#include <algorithm>
#include <cmath>

namespace sedwave::inversion::detail {

Eigen::Index central_draw(const Eigen::MatrixXd& ln_samples) {
  const Eigen::MatrixXd centred = ln_samples.rowwise() - ln_samples.colwise().mean();
  const Eigen::MatrixXd covariance =
      centred.transpose() * centred / static_cast<double>(std::max<Eigen::Index>(ln_samples.rows() - 1, 1));
  const Eigen::MatrixXd precision = covariance.completeOrthogonalDecomposition().pseudoInverse();
  Eigen::Index best = 0;
  (centred * precision).cwiseProduct(centred).rowwise().sum().minCoeff(&best);
  return best;
}

namespace {

/// The width of the central 95 % interval of `values` (sorted in place).
double central_95_width(Eigen::VectorXd values) {
  std::sort(values.begin(), values.end());
  const auto at = [&](double p) {
    const double position = p * static_cast<double>(values.size() - 1);
    const auto below = static_cast<Eigen::Index>(std::floor(position));
    const Eigen::Index above = std::min<Eigen::Index>(below + 1, values.size() - 1);
    return values(below) + (position - static_cast<double>(below)) * (values(above) - values(below));
  };
  return at(0.975) - at(0.025);
}

}  // namespace

double prior_width_share(const Eigen::VectorXd& posterior, const Eigen::VectorXd& prior) {
  if (posterior.size() < 2 || prior.size() < 2) return 0.0;
  const double prior_width = central_95_width(prior);
  if (!(prior_width > 0.0) || !std::isfinite(prior_width)) return 0.0;
  const double ratio = central_95_width(posterior) / prior_width;
  return std::clamp(ratio * ratio, 0.0, 1.0);
}

double prior_share_against_profile(double credible_lower, double credible_upper, std::optional<double> profile_lower,
                                   std::optional<double> profile_upper) {
  if (!profile_lower || !profile_upper) return 1.0;
  if (!(*profile_upper > *profile_lower && *profile_lower > 0.0)) return 0.0;
  if (!(credible_upper > credible_lower && credible_lower > 0.0)) return 0.0;
  const double ratio = std::log(credible_upper / credible_lower) / std::log(*profile_upper / *profile_lower);
  return std::clamp(1.0 - ratio * ratio, 0.0, 1.0);
}

PriorControl::PriorControl(const Eigen::MatrixXd& ln_samples, const Eigen::MatrixXd& data_information) {
  const Eigen::MatrixXd centred = ln_samples.rowwise() - ln_samples.colwise().mean();
  const auto draws = static_cast<double>(std::max<Eigen::Index>(ln_samples.rows() - 1, 1));
  const Eigen::MatrixXd covariance = centred.transpose() * centred / draws;
  // Sigma^(1/2) and its pseudo-inverse; a direction without spread (all draws equal) is left out.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> posterior(covariance);
  const Eigen::VectorXd variances = posterior.eigenvalues().cwiseMax(0.0);
  const double tiny = 1e-14 * std::max(variances.maxCoeff(), 1e-300);
  Eigen::VectorXd root(variances.size()), inverse_root(variances.size());
  for (Eigen::Index k = 0; k < variances.size(); ++k) {
    root(k) = std::sqrt(variances(k));
    inverse_root(k) = variances(k) > tiny ? 1.0 / root(k) : 0.0;
  }
  const Eigen::MatrixXd& axes = posterior.eigenvectors();
  const Eigen::MatrixXd sqrt_sigma = axes * root.asDiagonal() * axes.transpose();
  const Eigen::MatrixXd inverse_sqrt_sigma = axes * inverse_root.asDiagonal() * axes.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> shares(sqrt_sigma * data_information * sqrt_sigma);
  data_shares_ = shares.eigenvalues();
  coordinates_ = centred * inverse_sqrt_sigma * shares.eigenvectors();
}

double PriorControl::prior_share(const Eigen::VectorXd& ln_values) const {
  const Eigen::VectorXd centred = ln_values.array() - ln_values.mean();
  const double variance = centred.squaredNorm();
  if (!(variance > 0.0)) return 0.0;
  double from_prior = 0.0;
  for (Eigen::Index k = 0; k < data_shares_.size(); ++k) {
    const auto y = coordinates_.col(k);
    const double norm = y.squaredNorm();
    if (!(norm > 0.0)) continue;
    const double covariance = centred.dot(y);
    from_prior += std::clamp(1.0 - data_shares_(k), 0.0, 1.0) * covariance * covariance / norm;
  }
  return std::clamp(from_prior / variance, 0.0, 1.0);
}

}  // namespace sedwave::inversion::detail
