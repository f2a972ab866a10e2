#pragma once
// The least-squares problem behind every fit (private to the inversion library): observations with
// resolved sigmas, chi^2, the Ceres problem over theta = ln(parameters), and one local fit. The
// solvers (fit.cpp) and the likelihood profiles (profile.cpp) both build on it.
#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/residuals.hpp"

namespace sedwave::inversion::detail {

/// ln of every parameter value, in the model's order.
using Theta = std::vector<double>;

/// A function of theta with its gradient d/d theta (one entry per parameter).
struct Differentiated {
  double a = 0.0;
  Eigen::VectorXd v;
};

/// Everything a fit needs besides the solver: observations with resolved sigmas and the model.
struct Setup {
  std::vector<Observation> observations;
  std::vector<double> sigmas;
  std::vector<bool> defaulted;
  std::vector<double> frequencies;        ///< distinct frequencies [Hz]: the model runs once per frequency
  std::vector<std::size_t> frequency_of;  ///< row -> index into frequencies
  /// Rows of one quantity at one frequency with one sigma, as the fit compares them (residuals.hpp:
  /// compared_value, compared_sigma). Their whitening does not depend on the observed values, so
  /// their squared residuals sum exactly to n (model - mean)^2 / sigma^2 + scatter^2 / sigma^2: one
  /// residual for the mean and one for the scatter stand for all n rows, with the same chi^2,
  /// gradient and J^T J, and a fit costs what its distinct rows cost, not its rows. A group of one
  /// row has no scatter residual, and its residual is that row's to the last bit.
  struct RowGroup {
    Quantity quantity = Quantity::Attenuation;
    std::size_t frequency = 0;  ///< index into frequencies
    double grazing_angle = 0.0;  ///< [rad] of a reflection quantity (part of the group's key), else 0
    double observed = 0.0;      ///< mean of the rows' compared values
    double data_sigma = 0.0;    ///< their common compared sigma
    double count = 0.0;
    double scatter = 0.0;       ///< sqrt of the sum of squared deviations from the mean (0 for one row)
  };
  std::vector<RowGroup> groups;  ///< in the order of their first rows
  std::size_t residual_count = 0;  ///< the whitened residuals of the groups: one each, plus one per scatter
  const sediment::SedimentModel* model = nullptr;
  FitParameters parameters;
  std::vector<int> free;
  /// The groups of reflection quantities (indices into groups) and the water above the seabed they need.
  std::vector<std::size_t> reflection_groups;
  bool shear_rows = false;  ///< whether any row is of the shear wave (the model then runs it too)
  double water_speed = 0.0;       ///< [m/s]
  double water_density = 1025.0;  ///< [kg/m^3]
};

/// Step in theta = ln(value) of the central differences that give d bottom loss / d theta: the
/// reflection code is not differentiated, and a model's density has no derivatives.
inline constexpr double kBottomLossStep = 1e-5;

/// Throws std::invalid_argument, naming file and line, for a sigma that is not a usable positive
/// number; if `parameters` are not those of `model`; and where bottom-loss rows are given without a
/// water sound speed or to a model that fixes no bulk density. The water density is the data's
/// "water_density_kg_per_m3" metadata, else 1025 kg/m^3.
[[nodiscard]] Setup make_setup(const ObservationSet& data, const sediment::SedimentModel& model,
                               const FitParameters& parameters, const FitOptions& options);

/// The rows 0, stride, 2 stride, ... of s (frequencies re-indexed).
[[nodiscard]] Setup every_kth_row(const Setup& s, std::size_t stride);

/// The model's evaluations at a parameter point (residuals_at calls, a Jacobian's included) made so
/// far on the calling thread: what a comparison counts for a fit.
[[nodiscard]] long& evaluations_on_this_thread();

/// The groups' whitened residuals at theta (residual_count of them, Setup::RowGroup), and (if
/// `jacobian`) d residual / d theta for every parameter (residuals x parameters). False where the
/// model cannot be evaluated (std::domain_error) or a residual is not defined; `why` (if given) then
/// receives the model's reason.
[[nodiscard]] bool residuals_at(const Setup& s, const Theta& theta, double* residuals, Eigen::MatrixXd* jacobian,
                                std::string* why = nullptr);

/// Every row's own whitened residual at theta (observations.size() of them), for the report.
[[nodiscard]] bool row_residuals_at(const Setup& s, const Theta& theta, double* residuals, std::string* why = nullptr);

/// The model's wave at every row's frequency (SI).
[[nodiscard]] std::vector<double> predictions_at(const Setup& s, const Theta& theta);

/// chi^2 at theta; +inf where the model cannot be evaluated.
[[nodiscard]] double chi2_at(const Setup& s, const Theta& theta);

/// A function of the parameters that the data may determine even when they do not (c0, tau ...):
/// one of the model's derived quantities (sediment::DerivedQuantity).
struct DerivedFunction {
  std::string name;
  std::string unit;
  std::string meaning;
  /// ln q(theta) and its gradient.
  std::function<Differentiated(const Setup&, const Theta&)> log_value;
};

/// The parameter values exp(theta) (SI).
[[nodiscard]] std::vector<double> values_of(const Theta& theta);

/// The model's own derived quantities as functions of theta (derived.cpp).
[[nodiscard]] std::vector<DerivedFunction> derived_functions_for(const Setup& s);
/// Every derived quantity's value at theta, in the same order, without gradients (a posterior
/// draw's); throws as DerivedFunction::log_value does where one is not a positive number.
[[nodiscard]] std::vector<double> derived_at(const Setup& s, const Theta& theta);

/// An extra residual that ties a derived quantity to a target value (a likelihood profile of a
/// derived quantity holds it fixed this way).
struct Constraint {
  const DerivedFunction* derived = nullptr;
  double target = 0.0;      ///< in ln units
  double tolerance = 1e-5;  ///< the residual is (ln q - target) / tolerance
};

struct LocalFit {
  Theta theta;
  bool converged = false;
  std::string message;
  double chi2 = 0.0;  ///< of the observations alone (a constraint's residual is not counted)
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

/// Whitened Jacobian d residual / d theta_free, one row per residual of residuals_at. Throws std::runtime_error if the model cannot be
/// evaluated there or its derivatives are not finite.
[[nodiscard]] Eigen::MatrixXd whitened_jacobian(const Setup& s, const Theta& theta);

/// Covariance of the free ln-parameters at theta (ceres::Covariance, pseudo-inverse when singular).
[[nodiscard]] Eigen::MatrixXd covariance(const Setup& s, Theta theta);

[[nodiscard]] inline double log_lower(const Setup& s, int i) { return std::log(s.parameters.spec[i].lower); }
[[nodiscard]] inline double log_upper(const Setup& s, int i) { return std::log(s.parameters.spec[i].upper); }

/// The free entries of a gradient over all parameters.
[[nodiscard]] inline Eigen::VectorXd free_part(const Eigen::VectorXd& gradient, const std::vector<int>& free) {
  Eigen::VectorXd g(static_cast<Eigen::Index>(free.size()));
  for (std::size_t k = 0; k < free.size(); ++k) g(static_cast<Eigen::Index>(k)) = gradient(free[k]);
  return g;
}

}  // namespace sedwave::inversion::detail
