#pragma once
// Shared helpers of the sampling tests: Gaussian targets and Monte Carlo error bounds.
#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "sedwave/sampling/ensemble.hpp"

namespace sedwave::sampling::testing {

/// ln N(x; mean, covariance) up to a constant.
inline LogDensity gaussian_log_density(const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance) {
  const Eigen::LLT<Eigen::MatrixXd> factor(covariance);
  return [factor, mean](const Eigen::VectorXd& x) {
    const Eigen::VectorXd whitened = factor.matrixL().solve(x - mean);
    return -0.5 * whitened.squaredNorm();
  };
}

/// Expects f() to throw E whose message contains every one of `parts`.
template <typename E, typename F>
void expect_refusal(F f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected a refusal naming " << *parts.begin();
  } catch (const E& e) {
    for (const char* part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "'" << part << "' not in: " << e.what();
    }
  }
}

}  // namespace sedwave::sampling::testing
