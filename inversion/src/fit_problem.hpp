#pragma once
// The least-squares problem behind every fit (private to the inversion library): observations with
// resolved sigmas, chi^2, the Ceres problem over theta = ln(parameters), and one local fit. The
// solvers (fit.cpp) and the likelihood profiles (profile.cpp) both build on it.
#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/residuals.hpp"

namespace sedwave::inversion::detail {

using Theta = std::array<double, kParameterCount>;
using Jet3 = ceres::Jet<double, kParameterCount>;
using ThetaJets = std::array<Jet3, kParameterCount>;

/// theta as Jets seeded with the unit derivative of each ln-parameter: one evaluation then gives a
/// function of theta with its gradient.
[[nodiscard]] inline ThetaJets seeded_jets(const double* theta) {
  ThetaJets t;
  for (int i = 0; i < kParameterCount; ++i) t[i] = Jet3(theta[i], i);
  return t;
}

/// Everything a fit needs besides the solver: observations with resolved sigmas and the predictor.
struct Setup {
  std::vector<Observation> observations;
  std::vector<ObservationResidual> residuals;
  std::vector<double> sigmas;
  std::vector<bool> defaulted;
  Predictor predictor;
  FitParameters parameters;
  std::vector<int> free;
};

/// Throws std::invalid_argument, naming file and line, for a sigma that is not a usable positive
/// number (see fit.cpp).
[[nodiscard]] Setup make_setup(const ObservationSet& data, const forward::DispersionModel& model,
                               const FitParameters& parameters, const FitOptions& options);

/// chi^2 at theta; +inf where the model cannot be evaluated.
[[nodiscard]] double chi2_at(const Setup& s, const Theta& theta);

/// An extra residual that ties a function of theta to a target value (a likelihood profile of a
/// combination holds it fixed this way).
struct Constraint {
  /// ln q(theta) with its gradient; evaluated on Jets.
  Jet3 (*log_value)(const std::array<Jet3, kParameterCount>& theta, const Setup& s) = nullptr;
  double target = 0.0;  ///< in ln units
  double tolerance = 1e-5;  ///< the residual is (ln q - target) / tolerance
};

struct LocalFit {
  Theta theta;
  bool converged;
  std::string message;
  double chi2;  ///< of the observations alone (a constraint's residual is not counted)
};

/// Levenberg-Marquardt from theta within the bounds. `held` (>= 0) is a free parameter held at its
/// value in theta; `constraint` (if given) adds its residual.
[[nodiscard]] LocalFit solve_local(const Setup& s, Theta theta, int max_iterations, int held = -1,
                                   const Constraint* constraint = nullptr);

/// Relative size below which a singular value of the whitened Jacobian counts as zero. The
/// covariance drops the matching eigenvalues of J^T J (their squares), so both views agree on
/// which directions are unseen.
inline constexpr double kRankTolerance = 1e-8;

/// The Ceres problem over theta: fixed parameters (and `held`) are constant blocks, bounds in ln space.
void build_problem(const Setup& s, Theta& theta, ceres::Problem& problem, int held = -1,
                   const Constraint* constraint = nullptr);

/// Whitened Jacobian d residual / d theta_free, by forward-mode automatic differentiation. Throws
/// std::runtime_error if the model cannot be evaluated there or its derivatives are not finite.
[[nodiscard]] Eigen::MatrixXd whitened_jacobian(const Setup& s, const Theta& theta);

/// Covariance of the free ln-parameters at theta (ceres::Covariance, pseudo-inverse when singular).
[[nodiscard]] Eigen::MatrixXd covariance(const Setup& s, Theta theta);

[[nodiscard]] inline double log_lower(const Setup& s, int i) { return std::log(s.parameters.spec[i].lower); }
[[nodiscard]] inline double log_upper(const Setup& s, int i) { return std::log(s.parameters.spec[i].upper); }

}  // namespace sedwave::inversion::detail
