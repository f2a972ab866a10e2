#include "fit_problem.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sedwave::inversion::detail {
namespace {

/// A sigma must be a positive number the residual can divide by without overflow: finite, and at
/// least 1e-12 of the value (no measurement is better).
void check_sigma(const Observation& o, double sigma, bool defaulted) {
  if (std::isfinite(sigma) && sigma > 0.0 && sigma >= 1e-12 * std::abs(o.value)) return;
  std::ostringstream msg;
  msg << o.file << ":" << o.line << ": ";
  if (defaulted) {
    msg << "field 'sigma' is empty and the default relative sigma gives " << sigma
        << ", which is not usable (give --default-sigma a number in [1e-12, 10])";
  } else {
    msg << "field 'sigma' = " << sigma << " is not usable: a 1-sigma uncertainty must be positive, finite and at "
        << "least 1e-12 of the value (" << o.value << ")";
  }
  throw std::invalid_argument(msg.str());
}

/// All observations' residuals as one Ceres cost function: one block of n rows instead of n blocks
/// of one row, which spares Ceres its per-block bookkeeping (5x faster on 10^4 observations). Exact
/// Jacobians from Jets; a model outside its domain makes the step fail instead of throwing.
class ObservationResiduals final : public ceres::CostFunction {
 public:
  explicit ObservationResiduals(const Setup& s) : setup_(&s) {
    set_num_residuals(static_cast<int>(s.residuals.size()));
    for (int i = 0; i < kParameterCount; ++i) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    try {
      if (!jacobians) {
        for (size_t r = 0; r < setup_->residuals.size(); ++r) {
          if (!setup_->residuals[r](parameters[0], parameters[1], parameters[2], &residuals[r])) return false;
        }
        return true;
      }
      const std::array<double, kParameterCount> theta{parameters[0][0], parameters[1][0], parameters[2][0]};
      const ThetaJets t = seeded_jets(theta.data());
      for (size_t r = 0; r < setup_->residuals.size(); ++r) {
        Jet3 value;
        if (!setup_->residuals[r](&t[0], &t[1], &t[2], &value)) return false;
        residuals[r] = value.a;
        for (int i = 0; i < kParameterCount; ++i) {
          if (jacobians[i]) jacobians[i][r] = value.v[i];
        }
      }
      return true;
    } catch (const std::domain_error&) {
      return false;
    }
  }

 private:
  const Setup* setup_;
};

/// The residual (ln q(theta) - target) / tolerance of a Constraint, with its exact gradient.
class ConstraintResidual final : public ceres::SizedCostFunction<1, 1, 1, 1> {
 public:
  ConstraintResidual(const Setup& s, const Constraint& c) : setup_(&s), constraint_(c) {}
  bool Evaluate(double const* const* parameters, double* residual, double** jacobians) const override {
    const std::array<double, kParameterCount> theta{parameters[0][0], parameters[1][0], parameters[2][0]};
    const ThetaJets t = seeded_jets(theta.data());
    const Jet3 q = constraint_.log_value(t, *setup_);
    residual[0] = (q.a - constraint_.target) / constraint_.tolerance;
    if (jacobians) {
      for (int i = 0; i < kParameterCount; ++i) {
        if (jacobians[i]) jacobians[i][0] = q.v[i] / constraint_.tolerance;
      }
    }
    return std::isfinite(residual[0]);
  }

 private:
  const Setup* setup_;
  Constraint constraint_;
};

}  // namespace

Setup make_setup(const ObservationSet& data, const forward::DispersionModel& model, const FitParameters& parameters,
                 const FitOptions& options) {
  if (data.observations.empty()) throw std::invalid_argument("no observations to fit");
  parameters.validate();
  Setup s{data.observations, {}, {}, {}, Predictor(model, parameters.damping, parameters.density), parameters,
          parameters.free_indices()};
  for (const Observation& o : data.observations) {
    const bool missing = !o.sigma.has_value();
    const double sigma = missing ? options.default_relative_sigma * o.value : *o.sigma;
    check_sigma(o, sigma, missing);
    s.residuals.emplace_back(s.predictor, o, sigma);
    s.sigmas.push_back(sigma);
    s.defaulted.push_back(missing);
  }
  return s;
}

double chi2_at(const Setup& s, const Theta& theta) {
  double chi2 = 0.0;
  for (const ObservationResidual& r : s.residuals) {
    double value = 0.0;
    try {
      if (!r(&theta[0], &theta[1], &theta[2], &value)) return std::numeric_limits<double>::infinity();
    } catch (const std::domain_error&) {
      return std::numeric_limits<double>::infinity();
    }
    chi2 += value * value;
  }
  return std::isfinite(chi2) ? chi2 : std::numeric_limits<double>::infinity();
}

void build_problem(const Setup& s, Theta& theta, ceres::Problem& problem, int held, const Constraint* constraint) {
  problem.AddResidualBlock(new ObservationResiduals(s), nullptr, &theta[0], &theta[1], &theta[2]);
  if (constraint) {
    problem.AddResidualBlock(new ConstraintResidual(s, *constraint), nullptr, &theta[0], &theta[1], &theta[2]);
  }
  for (int i = 0; i < kParameterCount; ++i) {
    const ParameterSpec& spec = s.parameters.spec[i];
    if (!spec.free || i == held) {
      problem.SetParameterBlockConstant(&theta[i]);
      continue;
    }
    problem.SetParameterLowerBound(&theta[i], 0, log_lower(s, i));
    problem.SetParameterUpperBound(&theta[i], 0, log_upper(s, i));
  }
}

LocalFit solve_local(const Setup& s, Theta theta, int max_iterations, int held, const Constraint* constraint) {
  ceres::Problem problem;
  build_problem(s, theta, problem, held, constraint);
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  // chi^2 from our own evaluation: when the model cannot be evaluated at the start (outside a
  // table, say) Ceres fails with final_cost 0, which must not read as a perfect fit.
  const double chi2 = chi2_at(s, theta);
  return {theta, summary.termination_type == ceres::CONVERGENCE && std::isfinite(chi2), summary.message, chi2};
}

Eigen::MatrixXd whitened_jacobian(const Setup& s, const Theta& theta) {
  const ThetaJets t = seeded_jets(theta.data());
  Eigen::MatrixXd J(static_cast<Eigen::Index>(s.residuals.size()), static_cast<Eigen::Index>(s.free.size()));
  for (size_t r = 0; r < s.residuals.size(); ++r) {
    Jet3 value;
    if (!s.residuals[r](&t[0], &t[1], &t[2], &value)) throw std::runtime_error("residual failed at the solution");
    for (size_t k = 0; k < s.free.size(); ++k) {
      J(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = value.v[s.free[k]];
    }
  }
  if (!J.allFinite()) {
    throw std::runtime_error("the derivatives of model " + s.predictor.model().name() +
                             " are not finite at the fitted point; it cannot be analysed there");
  }
  return J;
}

/// Covariance of the free ln-parameters from ceres::Covariance; a pseudo-inverse when J^T J is
/// singular (eigenvalues below kRankTolerance^2 of the largest dropped).
Eigen::MatrixXd covariance(const Setup& s, Theta theta) {
  ceres::Problem problem;
  build_problem(s, theta, problem);
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.null_space_rank = -1;
  options.min_reciprocal_condition_number = kRankTolerance * kRankTolerance;
  options.num_threads = 1;
  ceres::Covariance solver(options);
  std::vector<const double*> blocks;
  for (int i : s.free) blocks.push_back(&theta[i]);
  const auto n = static_cast<Eigen::Index>(blocks.size());
  Eigen::MatrixXd result = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (!solver.Compute(blocks, &problem)) return result;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dense(n, n);
  solver.GetCovarianceMatrix(blocks, dense.data());
  return dense;
}

}  // namespace sedwave::inversion::detail
