#pragma once
// The one question every sedwave forward model answers:
//   given the dimensionless angular frequency omega_hat = omega * sqrt(m / kappa) and the
//   dimensionless dashpot gamma_hat = gamma / sqrt(kappa * m), what are the dimensionless
//   attenuation alpha_hat = alpha * d (Np per grain diameter) and sound speed
//   c_hat = c / (d * sqrt(kappa / m)), with what uncertainty?
//
// Closed-form theories, tables and simulations all implement DispersionModel, so the inversion
// never depends on which one it is fitting with.
#include <cstdint>
#include <string>
#include <vector>

namespace sedwave::forward {

/// Partial derivatives of one output with respect to the two dimensionless inputs.
struct Gradient {
  double d_omega_hat = 0.0;
  double d_gamma_hat = 0.0;
};

/// The answer of a forward model at one (omega_hat, gamma_hat). All quantities are dimensionless.
struct DispersionPoint {
  double alpha_hat = 0.0;        ///< attenuation times grain diameter, Np (amplitude ~ exp(-alpha x))
  double c_hat = 0.0;            ///< phase speed over d*sqrt(kappa/m)
  Gradient d_alpha_hat;          ///< exact partial derivatives of alpha_hat
  Gradient d_c_hat;              ///< exact partial derivatives of c_hat
  double sigma_alpha_hat = 0.0;  ///< 1-sigma model uncertainty (0 for closed forms)
  double sigma_c_hat = 0.0;      ///< 1-sigma model uncertainty (0 for closed forms)
};

/// A count a model keeps while it answers (how often a table fell back to a theory, say), which a
/// fit made with the model must report, or a theory's answers would pass for the model's own.
struct ModelDiagnostic {
  std::string key;          ///< its name in a fit report, e.g. "table_fallback_evaluations"
  std::uint64_t count = 0;
  std::string note;         ///< one sentence for the reader when there is something to say, else empty
};

/// Interface of all forward models. Implementations must be thread-safe for concurrent evaluate().
class DispersionModel {
 public:
  virtual ~DispersionModel() = default;
  /// Short identifier used on the command line and in reports, e.g. "continuum".
  [[nodiscard]] virtual std::string name() const = 0;
  /// Values and derivatives at one point. Throws std::domain_error outside the model's domain.
  [[nodiscard]] virtual DispersionPoint evaluate(double omega_hat, double gamma_hat) const = 0;
  /// c_hat as omega_hat -> 0 (the static, fully relaxed packing; the same for every gamma_hat, since
  /// dashpots carry no force at zero frequency). 1 for the chains, whose speed scale d sqrt(kappa/m)
  /// is their low-frequency speed; a 3D packing is softer or stiffer.
  [[nodiscard]] virtual double long_wavelength_c_hat() const { return 1.0; }
  /// What the model's own sigmas are known to leave out, in words (an inversion flags it); empty
  /// when nothing is known to be missing (closed forms are exact).
  [[nodiscard]] virtual std::string uncertainty_caveat() const { return {}; }
  /// How the model's answers so far came about, where that is more than the model itself (none for
  /// closed forms).
  [[nodiscard]] virtual std::vector<ModelDiagnostic> diagnostics() const { return {}; }
};

}  // namespace sedwave::forward
