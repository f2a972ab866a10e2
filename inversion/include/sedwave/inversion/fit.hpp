#pragma once
// Fitting contact parameters to field observations: the solver side.
//   ceres   Levenberg-Marquardt from the start values, exact Jacobians (local).
//   nlopt   a derivative-free global search over the bounds (DIRECT-L, CRS2 or MLSL).
//   global  the NLopt search, then a Ceres polish; also a local fit from the start values, and a
//           report of whether the two agree.
// Every method ends with the same analysis at the solution: covariance (ceres::Covariance, a
// pseudo-inverse when the data leave directions undetermined), identifiability, and goodness of fit.
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/parameters.hpp"
#include "sedwave/inversion/plausibility.hpp"
#include "sedwave/sediment/grain_contact.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

enum class FitMethod { Ceres, NLopt, Global };

struct FitOptions {
  FitMethod method = FitMethod::Global;
  std::string global_algorithm = "direct-l";  ///< direct-l | crs2 | mlsl
  int max_global_evaluations = 5000;
  int max_iterations = 200;                   ///< Levenberg-Marquardt iterations
  double default_relative_sigma = 0.1;        ///< for observations whose file gave no sigma
  /// A parameter or derived quantity is "determined" when its 1-sigma spread in ln units is below this
  /// (0.5: known to within a factor e^0.5 = 1.65) and it has no component along unseen directions.
  double determined_log_sigma = 0.5;
  unsigned random_seed = 20090501;            ///< for the stochastic NLopt algorithms
  /// Also compute profile-likelihood intervals (Delta chi^2 = 1) of each free parameter and
  /// derived quantity, and call a quantity determined only if its profile closes on both sides. Costs
  /// ~40-80 local fits each.
  bool profile_likelihood = true;
  /// Called with the name of each stage as it starts (global search, each profile): a long fit
  /// (10^5 observations and more) can say where it is. Empty: silent.
  std::function<void(const std::string&)> progress = nullptr;
};

struct ParameterResult {
  std::string name;
  std::string unit;
  double value = 0.0;       ///< [unit]
  bool free = false;
  bool at_bound = false;     ///< within 1 % of a search bound: the bound, not the data, holds it
  bool determined = false;  ///< fixed parameters count as determined
  double log_sigma = 0.0;   ///< 1-sigma of ln(value); meaningful only if determined
  double sigma = 0.0;       ///< value * log_sigma (first order) [unit]
  /// Profile-likelihood 68% interval [unit]; a missing side is open (the bound lies within it, or
  /// only another parameter's bound closes it: profile.hpp).
  std::optional<double> profile_lower;
  std::optional<double> profile_upper;
};

/// A function of the parameters that the data may determine even when they do not.
struct DerivedResult {
  std::string name;
  std::string unit;
  std::string meaning;
  double value = 0.0;
  bool determined = false;
  double log_sigma = 0.0;
  double sigma = 0.0;
  /// Profile-likelihood 68% interval [unit]; a missing side is open (reaches the parameter bounds, or
  /// only another parameter's bound closes it).
  std::optional<double> profile_lower;
  std::optional<double> profile_upper;
};

/// A direction of ln-parameter space the data cannot see or barely see.
struct WeakDirection {
  std::string direction;     ///< e.g. "kappa^1 * d^1 * gamma^1"
  double singular_value;     ///< whitened; 0 for a structural null direction
  bool unseen;               ///< in the numerical null space
};

struct PointResidual {
  Observation observation;
  double sigma = 0.0;            ///< SI, as used (defaulted if the file had none)
  bool default_sigma = false;
  double model = 0.0;            ///< SI
  double normalized = 0.0;       ///< whitened residual
};

struct GlobalSearchReport {
  std::string algorithm;
  int evaluations = 0;
  double chi2_search = 0.0;           ///< best chi^2 the global search found
  double chi2_polished = 0.0;         ///< after the Ceres polish
  double chi2_local_from_start = 0.0; ///< Ceres alone from the start values (method global)
  bool local_and_global_agree = false;  ///< the two local fits' chi^2 within max(0.01, 1e-6 chi^2)
};

/// A local minimum of chi^2 other than the fit's, with a barrier between the two (chi^2 along the
/// straight line between them, in the ln-parameters, rises above both): a second mode.
struct LocalMinimum {
  std::vector<double> values;  ///< every parameter, in the order of FitParameters::spec [unit]
  double chi2 = 0.0;
};

/// FitResult::other_minima keeps minima whose chi^2 lies at most this far above the fit's (their
/// likelihood e^-20 of its: beyond that no width of a mode makes its mass matter).
inline constexpr double kOtherMinimaChi2 = 40.0;

struct FitResult {
  std::string model;
  std::string method;
  FitParameters fitted;  ///< the solution (values updated)
  std::vector<ParameterResult> parameters;
  /// The model's derived quantities (sediment::DerivedQuantity) at the fit; fit.json keeps its
  /// key "combinations" for them, as files written before do.
  std::vector<DerivedResult> derived;
  std::vector<std::string> free_names;
  Eigen::MatrixXd correlation;       ///< of the free ln-parameters (NaN rows for undetermined ones)
  Eigen::MatrixXd covariance;        ///< of the free ln-parameters (pseudo-inverse)
  Eigen::VectorXd singular_values;   ///< of the whitened Jacobian
  int rank = 0;
  std::vector<WeakDirection> weak_directions;
  std::vector<PointResidual> residuals;
  double chi2 = 0.0;
  int n_observations = 0;
  int dof = 0;        ///< n - rank
  double aic = 0.0;   ///< chi2 + 2 rank
  double bic = 0.0;   ///< chi2 + rank ln n
  bool converged = false;
  std::string solver_message;
  std::optional<GlobalSearchReport> global;
  /// Method global: the other local minima that polishing the global search's best points in
  /// separate regions led to (and the local fit from the start values), within kOtherMinimaChi2 of
  /// the fit's chi^2, lowest first. The fit itself is not among them.
  std::vector<LocalMinimum> other_minima;
  /// Times a likelihood profile found a lower chi^2 than the solver's minimum, so the fit moved there.
  int profile_restarts = 0;
  /// Results outside physical ranges, parameters at search bounds: each with its likely cause.
  std::vector<PlausibilityFlag> flags;
  double wall_seconds = 0.0;
};

/// Fits `parameters` (free ones from their start values; the model's own parameters, in its order)
/// to `data` with `model`. Throws std::invalid_argument for unusable input (no observations, ratio
/// without water speed, parameters of another model ...).
[[nodiscard]] FitResult fit(const ObservationSet& data, const sediment::SedimentModel& model,
                            const FitParameters& parameters, const FitOptions& options);
/// The same with a dimensionless model as a dry grain-contact frame (grain_contact_model()).
[[nodiscard]] FitResult fit(const ObservationSet& data, const forward::DispersionModel& model,
                            const FitParameters& parameters, const FitOptions& options);

/// A dimensionless model as the grain-contact sediment model, borrowing `model` (which must
/// outlive the result).
[[nodiscard]] std::shared_ptr<const sediment::GrainContactModel> grain_contact_model(
    const forward::DispersionModel& model, DampingForm form);

/// Physical predictions of a fitted model on a frequency grid, with 1-sigma bands from the
/// covariance (attenuation in Np/m, speed in m/s). The dimensionless coordinates are those of a dry
/// grain-contact frame, kNotApplicable (NaN) for other models.
inline constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();
struct CurvePoint {
  double frequency_hz;
  double omega_hat, gamma_hat, alpha_hat, c_hat;
  double alpha, alpha_sigma;
  double speed, speed_sigma;
};
/// The fitted model at each frequency; frequencies outside the model's domain (a table's range) are
/// left out, so the curve stops where the model does.
[[nodiscard]] std::vector<CurvePoint> model_curves(const FitResult& result, const sediment::SedimentModel& model,
                                                   const std::vector<double>& frequencies_hz);
[[nodiscard]] std::vector<CurvePoint> model_curves(const FitResult& result, const forward::DispersionModel& model,
                                                   const std::vector<double>& frequencies_hz);

[[nodiscard]] FitMethod parse_fit_method(const std::string& name);

}  // namespace sedwave::inversion
