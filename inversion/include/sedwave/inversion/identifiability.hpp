#pragma once
// What the data determine. A fit in theta = ln(parameters) is linearised at the solution through
// the whitened Jacobian J (n residuals x p free parameters). Its singular value decomposition
// J = U S V^T says which directions of theta the data constrain: a direction v_i with s_i ~ 0 is
// invisible to the data (the continuum chain, for instance, only sees c0 ~ sqrt(kappa/d) and
// tau = gamma/kappa, so scaling kappa, d and gamma together is one such direction), and one with
// 1/s_i larger than the acceptable log-uncertainty is only poorly constrained.
//
// A smooth function q(theta) is determined when its gradient has no component along the null
// directions and its linearised 1-sigma spread sqrt(g^T Cov g), in ln units, is below a threshold.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace sedwave::inversion {

struct JacobianAnalysis {
  Eigen::VectorXd singular_values;   ///< descending
  Eigen::MatrixXd right_vectors;     ///< columns v_i, matching singular_values
  int rank = 0;                      ///< number of s_i above the rank tolerance
  Eigen::MatrixXd null_space;        ///< columns spanning the numerical null space (p x (p - rank))
};

/// SVD of the whitened Jacobian; s_i <= rank_tolerance * s_max count as zero.
[[nodiscard]] JacobianAnalysis analyze_jacobian(const Eigen::MatrixXd& jacobian, double rank_tolerance = 1e-9);

/// Linearised uncertainty of q with gradient g (w.r.t. the free ln-parameters).
struct Determination {
  double log_sigma = 0.0;        ///< sqrt(g^T Cov g), ln units (meaningful only if not in null space)
  double null_component = 0.0;   ///< |N^T g| / |g|: 0 if q ignores the unseen directions
  bool determined = false;
};

/// `covariance` is the (pseudo-)inverse of J^T J in the same free ln-parameter coordinates.
[[nodiscard]] Determination determine(const Eigen::VectorXd& gradient, const JacobianAnalysis& analysis,
                                      const Eigen::MatrixXd& covariance, double max_log_sigma);

/// "kappa^1 d^1 gamma^1" style description of a direction in ln-parameter space (components
/// normalised so the largest is 1; tiny ones dropped).
[[nodiscard]] std::string describe_direction(const Eigen::VectorXd& direction, const std::vector<std::string>& names);

}  // namespace sedwave::inversion
