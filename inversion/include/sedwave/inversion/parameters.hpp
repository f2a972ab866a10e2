#pragma once
// The physical parameters an inversion can fit, their units, bounds and which ones are free.
//
// Three parameters describe a grain contact: stiffness kappa [N/m], grain diameter d [m] and the
// normal damping, either as the dashpot gamma [kg/s] or as the restitution coefficient e_n [-] of a
// binary collision of two equal grains. The grain density rho_s [kg/m^3] is always fixed. The fit
// works in natural logarithms of the three, so steps are relative and decades apart are equal.
#include <array>
#include <string>
#include <vector>

namespace sedwave::inversion {

enum class DampingForm { Gamma, Restitution };

/// Index of each fitted quantity in the parameter vector theta = (ln kappa, ln d, ln damping).
enum ParameterIndex : int { kKappa = 0, kDiameter = 1, kDamping = 2, kParameterCount = 3 };

struct ParameterSpec {
  double value;  ///< start value if free, the value used if fixed [SI]
  double lower;  ///< bound [SI]
  double upper;  ///< bound [SI]
  bool free;
};

/// All parameters of one inversion, in SI.
struct FitParameters {
  DampingForm damping = DampingForm::Gamma;
  double density = 2650.0;  ///< grain density rho_s [kg/m^3], fixed
  std::array<ParameterSpec, kParameterCount> spec{{
      {6.0e3, 1.0e-3, 1.0e13, true},   // kappa [N/m]
      {2.0e-4, 1.0e-8, 1.0, true},     // d [m]: 10 nm (clay) to 1 m (boulders)
      {1.0e-2, 1.0e-12, 1.0e8, true},  // gamma [kg/s]; see set_damping_form for e_n
  }};

  /// Switch between gamma and e_n, resetting the damping entry to that form's defaults.
  void set_damping_form(DampingForm form);
  /// Mark free exactly the parameters named in a list like "kappa,d,gamma" (others fixed).
  /// Accepted names: kappa, d, gamma, en (e_n also accepted). Throws std::invalid_argument.
  void set_free_from_list(const std::string& list);
  [[nodiscard]] std::vector<int> free_indices() const;
  /// theta = natural logarithms of the three values.
  [[nodiscard]] std::array<double, kParameterCount> log_values() const;
  /// Throws std::invalid_argument if a value lies outside its bounds or bounds are not positive.
  void validate() const;
};

/// Name, symbol and SI unit of each parameter (the damping one depends on the form).
[[nodiscard]] std::string parameter_name(int index, DampingForm form);
[[nodiscard]] std::string parameter_unit(int index, DampingForm form);

}  // namespace sedwave::inversion
