// Derived quantities: functions of theta that the data may determine when the parameters are not. They
// are the model's own derived quantities (sediment::SedimentModel::derived_quantities), evaluated
// with exact gradients by the model; here each becomes ln q(theta) with d ln q / d theta, so the
// same code gives the value, the linearised sigma, the likelihood profile and a posterior sample's value.
#include <cmath>
#include <stdexcept>

#include "fit_problem.hpp"

namespace sedwave::inversion::detail {
namespace {

/// Throws unless q, the model's k-th derived quantity, is a positive number (its logarithm is used).
void require_positive(const Setup& s, std::size_t k, double q) {
  if (!(q > 0.0) || !std::isfinite(q)) {
    throw std::domain_error(s.model->name() + ": derived quantity " + s.model->derived_quantities()[k].name +
                            " is not a positive number");
  }
}

/// ln q_k at theta, d ln q / d theta_i = (d q / d value_i) value_i / q (values = exp(theta)).
Differentiated log_derived(const Setup& s, const Theta& theta, std::size_t k) {
  const std::vector<double> values = values_of(theta);
  const std::vector<sediment::DerivedValue> all = s.model->derived_values(values, true);
  if (k >= all.size() || all[k].gradient.size() != values.size()) {
    throw std::logic_error(s.model->name() + ": derived_values does not match derived_quantities");
  }
  const sediment::DerivedValue& q = all[k];
  require_positive(s, k, q.value);
  Differentiated out{std::log(q.value), Eigen::VectorXd(static_cast<Eigen::Index>(values.size()))};
  for (std::size_t i = 0; i < values.size(); ++i) {
    out.v(static_cast<Eigen::Index>(i)) = q.gradient[i] * values[i] / q.value;
  }
  return out;
}

}  // namespace

std::vector<double> derived_at(const Setup& s, const Theta& theta) {
  const std::vector<sediment::DerivedValue> all = s.model->derived_values(values_of(theta), false);
  if (all.size() != s.model->derived_quantities().size()) {
    throw std::logic_error(s.model->name() + ": derived_values does not match derived_quantities");
  }
  std::vector<double> out(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    require_positive(s, k, all[k].value);
    out[k] = all[k].value;
  }
  return out;
}

std::vector<DerivedFunction> derived_functions_for(const Setup& s) {
  std::vector<DerivedFunction> list;
  const std::vector<sediment::DerivedQuantity>& quantities = s.model->derived_quantities();
  for (std::size_t k = 0; k < quantities.size(); ++k) {
    list.push_back({quantities[k].name, quantities[k].unit, quantities[k].meaning,
                    [k](const Setup& setup, const Theta& theta) { return log_derived(setup, theta, k); }});
  }
  return list;
}

}  // namespace sedwave::inversion::detail
