#include "sedwave/inversion/identifiability.hpp"

#include <cmath>
#include <cstdio>

namespace sedwave::inversion {

JacobianAnalysis analyze_jacobian(const Eigen::MatrixXd& jacobian, double rank_tolerance) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeFullV);
  JacobianAnalysis a;
  const Eigen::Index p = jacobian.cols();
  a.singular_values = Eigen::VectorXd::Zero(p);
  a.singular_values.head(svd.singularValues().size()) = svd.singularValues();  // n < p pads zeros
  a.right_vectors = svd.matrixV();
  const double s_max = p > 0 ? a.singular_values(0) : 0.0;
  while (a.rank < p && a.singular_values(a.rank) > rank_tolerance * s_max) ++a.rank;
  a.null_space = a.right_vectors.rightCols(p - a.rank);
  return a;
}

Determination determine(const Eigen::VectorXd& gradient, const JacobianAnalysis& analysis,
                        const Eigen::MatrixXd& covariance, double max_log_sigma) {
  Determination d;
  const double norm = gradient.norm();
  if (norm == 0.0) {  // depends on fixed parameters only: known exactly
    d.determined = true;
    return d;
  }
  d.null_component = analysis.null_space.cols() > 0 ? (analysis.null_space.transpose() * gradient).norm() / norm : 0.0;
  d.log_sigma = std::sqrt(std::max(0.0, gradient.dot(covariance * gradient)));
  // 1e-6: a structural null direction is exact up to round-off in the Jacobian (~1e-8 here).
  d.determined = d.null_component < 1e-6 && d.log_sigma < max_log_sigma;
  return d;
}

std::string describe_direction(const Eigen::VectorXd& direction, const std::vector<std::string>& names) {
  Eigen::Index largest = 0;
  direction.cwiseAbs().maxCoeff(&largest);
  const Eigen::VectorXd v = direction / direction(largest);
  std::string text;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (std::abs(v(i)) < 1e-3) continue;
    char term[64];
    std::snprintf(term, sizeof term, "%s%s^%.3g", text.empty() ? "" : " * ", names[static_cast<size_t>(i)].c_str(), v(i));
    text += term;
  }
  return text;
}

}  // namespace sedwave::inversion
