#pragma once
// The physical parameters an inversion can fit: one entry per parameter of the sediment model
// (sediment/sediment_model.hpp), with its SI unit, start or fixed value, search bounds and whether
// it is free. The fit works in natural logarithms of the values, so steps are relative and decades
// apart are equal; every parameter is therefore positive.
//
// The default set is the grain-contact family's: contact stiffness kappa [N/m], grain diameter
// d [m], the normal damping as the dashpot gamma [kg/s] or the restitution coefficient e_n [-] of
// a collision of two equal grains, and the grain density rho_s [kg/m^3] (fixed). Parameters are
// found by name (index_of), never by position.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/sediment/grain_contact.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

using sediment::DampingForm;

struct ParameterSpec {
  std::string name;
  std::string unit;
  double value = 0.0;  ///< start value if free, the value used if fixed [unit]
  double lower = 0.0;  ///< search bound [unit]
  double upper = 0.0;  ///< search bound [unit]
  bool free = false;
};

/// All parameters of one inversion, in SI, in the model's order.
struct FitParameters {
  std::vector<ParameterSpec> spec;

  /// The grain-contact family with the dashpot gamma: kappa, d, gamma free; rho_s fixed at 2650.
  FitParameters();
  /// A model's parameters at their defaults, search bounds = physical ranges, all fixed.
  explicit FitParameters(const std::vector<sediment::Parameter>& parameters);

  [[nodiscard]] int size() const { return static_cast<int>(spec.size()); }
  /// Index by name; throws std::invalid_argument listing the accepted names.
  [[nodiscard]] int index_of(const std::string& name) const;
  /// Index of the contact damping (the parameter named gamma or e_n), or -1 for a model without one.
  [[nodiscard]] int damping_index() const;
  /// The form of the contact damping: Restitution when a parameter is e_n, Gamma else.
  [[nodiscard]] DampingForm damping_form() const;
  /// Switch between gamma and e_n (models with a contact damping only), resetting that entry to the
  /// form's defaults and keeping whether it is free.
  void set_damping_form(DampingForm form);
  /// Mark free exactly the parameters named in a list like "kappa,d,gamma" (others fixed). For a
  /// model with a contact damping, naming gamma or en (e_n) selects that damping form. Throws
  /// std::invalid_argument naming an unknown, repeated or conflicting name.
  /// `origin` names the list in messages (default "--fit 'LIST'").
  void set_free_from_list(const std::string& list, const std::string& origin = "");
  [[nodiscard]] std::vector<int> free_indices() const;
  [[nodiscard]] std::vector<double> values() const;
  /// theta = natural logarithms of the values.
  [[nodiscard]] std::vector<double> log_values() const;
  /// Throws std::invalid_argument if a value lies outside its bounds or bounds are not positive.
  void validate() const;
  /// Throws std::invalid_argument unless these are the parameters of `model` (same names, order).
  void require_parameters_of(const sediment::SedimentModel& model) const;
};

/// The entry named `name` of a list of named results (FitResult::parameters, ::derived quantities,
/// PosteriorResult::parameters ...); throws std::invalid_argument if there is none.
template <typename Named>
[[nodiscard]] const Named& by_name(const std::vector<Named>& list, const std::string& name) {
  const auto it = std::find_if(list.begin(), list.end(), [&](const Named& q) { return q.name == name; });
  if (it == list.end()) throw std::invalid_argument("no result named '" + name + "'");
  return *it;
}

}  // namespace sedwave::inversion
