#pragma once
// A sediment model: named physical parameters in SI, and the compressional wave it predicts at a
// frequency (attenuation [Np/m], phase speed [m/s]) with exact derivatives; where the model has one,
// also its shear wave and its bulk density (what plane-wave reflection at the seabed needs).
//
// This is the level the inversion works at. The dimensionless grain-contact engines of forward/
// (chain theories, 3D tables) enter through one family (grain_contact.hpp); poroelastic and
// grain-shearing models are closed forms in SI. Every model is written once, templated on the
// scalar type T, and JetEvaluated<> turns it into values plus a gradient by forward-mode automatic
// differentiation (ceres::Jet), so Ceres, NLopt, the identifiability analysis and samplers need
// nothing model-specific. A model also describes itself: the quantities it derives from its
// parameters (with units, meanings and plausible ranges, differentiated by the same Jets), the
// parameters a fit frees by default, and the dimensionless engine behind it if it has one; the
// inversion's report, profiles and plausibility flags read them from here
// (docs/models/adding-a-model.md).
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sedwave::forward {
class DispersionModel;
}

namespace sedwave::sediment {

/// One physical parameter of a model.
struct Parameter {
  std::string name;     ///< command-line name, e.g. "porosity" (an option --porosity sets it)
  std::string unit;     ///< SI unit; "1" for a dimensionless number
  double default_value = 0.0;  ///< documented default (quartz sand in sea water unless said)
  double lower = 0.0;   ///< physical range, lower > 0: values outside [lower, upper] are refused
  double upper = 0.0;
  /// Spans decades (a log-uniform prior suits it) rather than a narrow linear range. Every
  /// parameter is positive, and the inversion steps all of them in ln.
  bool log_scale = true;
  std::string meaning;  ///< one line, with its source where it has one
  /// The default stands for a typical sediment, so a forward run may use it; false where a default
  /// is only a place to start a search from (a grain contact's stiffness), and a run must be given it.
  bool typical = true;
};

/// The compressional wave at one frequency.
struct Wave {
  double attenuation = 0.0;        ///< alpha [Np/m]; amplitude ~ exp(-alpha x)
  double speed = 0.0;              ///< phase speed [m/s]
  double sigma_attenuation = 0.0;  ///< the model's own 1-sigma uncertainty [Np/m] (tables; 0 else)
  double sigma_speed = 0.0;        ///< [m/s]
  /// d attenuation / d value_i and d speed / d value_i (SI), one entry per parameter; empty unless
  /// derivatives were asked for.
  std::vector<double> d_attenuation;
  std::vector<double> d_speed;
};

/// A quantity a model derives from its parameters that the data may determine when the parameters
/// are not (a grain contact's relaxation time, a mixture's Wood speed). The inversion reports it with
/// its interval and flags a value outside its plausible range.
struct DerivedQuantity {
  std::string name;     ///< e.g. "tau"
  std::string unit;     ///< SI unit; "1" for a dimensionless number
  std::string meaning;  ///< one line, with its source where it has one
  /// Values a seabed sediment can have; a fitted value outside is flagged. lower = upper = 0: none.
  double plausible_lower = 0.0;
  double plausible_upper = 0.0;
  std::string plausible_basis;  ///< where the range comes from
  std::string below_cause;      ///< likely cause of a value below it
  std::string above_cause;      ///< likely cause of a value above it
};

/// One derived quantity's value and, if asked for, d value / d value_i (SI, one entry per parameter).
struct DerivedValue {
  double value = 0.0;
  std::vector<double> gradient;
};

/// The dimensionless coordinates and wave of a grain-contact model at one frequency.
struct DimensionlessWave {
  double omega_hat = 0.0;
  double gamma_hat = 0.0;
  double alpha_hat = 0.0;
  double c_hat = 0.0;
};

/// Interface of every sediment model. Implementations are immutable after construction and
/// thread-safe for concurrent evaluate().
class SedimentModel {
 public:
  virtual ~SedimentModel() = default;
  /// Identifier on the command line and in reports, e.g. "biot-stoll".
  [[nodiscard]] virtual std::string name() const = 0;
  /// One line: what the model is, with its source.
  [[nodiscard]] virtual std::string summary() const = 0;
  [[nodiscard]] virtual const std::vector<Parameter>& parameters() const = 0;
  /// The wave at `frequency_hz` for parameter `values` (SI, in parameters() order). With
  /// `derivatives`, Wave::d_* hold the gradient. Throws std::domain_error where the model has no
  /// answer (a table's range); never returns NaN silently.
  [[nodiscard]] virtual Wave evaluate(std::span<const double> values, double frequency_hz,
                                      bool derivatives) const = 0;

  /// Whether the model predicts a shear wave (evaluate_shear answers): the grain-shearing models and
  /// those with a frame shear modulus do; a fluid-like model (EDFM) and the dry chain do not.
  [[nodiscard]] virtual bool has_shear() const { return false; }
  /// The shear wave at `frequency_hz` (attenuation [Np/m], phase speed [m/s], as evaluate() for the
  /// compressional wave, with the same exact derivatives). Throws std::logic_error naming the model
  /// where has_shear() is false.
  [[nodiscard]] virtual Wave evaluate_shear(std::span<const double> values, double frequency_hz,
                                            bool derivatives) const;
  /// One line: where the shear wave comes from and what it assumes (e.g. a frame Poisson ratio);
  /// empty where the model has none.
  [[nodiscard]] virtual std::string shear_summary() const { return {}; }
  /// The sediment's bulk density [kg/m^3] at parameter `values`, which reflection at the seabed
  /// needs; nothing for a model that does not fix it (the dry frame alone).
  [[nodiscard]] virtual std::optional<double> bulk_density(std::span<const double> /*values*/) const {
    return std::nullopt;
  }

  /// What the model's own sigmas are known to leave out, in words (an inversion flags it); empty
  /// when nothing is known to be missing.
  [[nodiscard]] virtual std::string uncertainty_caveat() const { return {}; }

  /// The quantities the model derives from its parameters, in the order derived_values() returns them.
  [[nodiscard]] virtual const std::vector<DerivedQuantity>& derived_quantities() const;
  /// Their values (and, with `derivatives`, gradients) at parameter `values` (SI, parameters() order).
  [[nodiscard]] virtual std::vector<DerivedValue> derived_values(std::span<const double> values,
                                                                 bool derivatives) const;
  /// The parameters a fit frees when the user does not say (`--fit`), comma-separated: those that
  /// sandy-site data over 50 Hz - 100 kHz can inform and that the model is meant to explain. All
  /// parameters unless a model says otherwise.
  [[nodiscard]] virtual std::string typical_free_parameters() const;
  /// The dimensionless forward model (forward/) behind a grain-contact model; nullptr for others.
  [[nodiscard]] virtual const forward::DispersionModel* dimensionless_engine() const { return nullptr; }
  /// The dimensionless coordinates of the wave at `values` and `frequency_hz`, for a model that is
  /// one dimensionless engine scaled to SI (the dry frame); nothing for others.
  [[nodiscard]] virtual std::optional<DimensionlessWave> dimensionless_wave(std::span<const double> values,
                                                                            double frequency_hz) const;

  /// Index of a parameter by name; throws std::invalid_argument listing the accepted names.
  [[nodiscard]] int index_of(const std::string& name) const;
  /// Whether the model has a parameter of that name.
  [[nodiscard]] bool has_parameter(const std::string& name) const;
  /// The defaults, in parameters() order.
  [[nodiscard]] std::vector<double> default_values() const;
  /// Throws std::invalid_argument naming the parameter, its value and its range if a value lies
  /// outside its physical range or is not finite.
  void check_values(std::span<const double> values) const;
};

}  // namespace sedwave::sediment
