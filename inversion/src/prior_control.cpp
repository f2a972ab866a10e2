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
