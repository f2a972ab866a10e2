#pragma once
// Whitened residuals of field observations against any sediment model (sediment_model.hpp).
//
// The fit works in theta = ln(parameter values). A model answers attenuation alpha [Np/m] and phase
// speed c [m/s] at a frequency with exact derivatives d/d value_i; here they become residuals and
// d residual / d theta_i = (d residual / d value_i) value_i. Attenuation spans decades, so it is
// compared in log space with a relative sigma; sound speed is compared linearly. A model's own
// uncertainty (a table's sigma) adds in quadrature and is not differentiated.
#include <cmath>
#include <span>

#include "sedwave/inversion/observations.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

/// The model's value of an observation's quantity [SI]. A bottom loss is no property of one wave:
/// the fit computes it from the reflection coefficient (NaN here).
[[nodiscard]] inline double predicted_value(const Observation& o, const sediment::Wave& w) {
  if (is_reflection(o.quantity)) return std::nan("");
  return is_attenuation(o.quantity) ? w.attenuation : w.speed;
}

/// The whitened residual of observation `o` (1-sigma `sigma` in SI) against the wave `w` the model
/// predicts at its frequency (the shear wave for a shear row) for parameter `values`; with `d_theta` non-null (and `w` holding
/// derivatives) also d residual / d ln value_i into d_theta[0 .. values.size()). False where the
/// residual is not defined (a non-positive attenuation).
[[nodiscard]] inline bool whitened_residual(const Observation& o, double sigma, const sediment::Wave& w,
                                            std::span<const double> values, double& residual, double* d_theta) {
  if (is_attenuation(o.quantity)) {
    if (!(w.attenuation > 0.0)) return false;
    const double relative_model = w.sigma_attenuation / w.attenuation;
    const double relative_data = sigma / o.value;
    const double sigma_log = std::sqrt(relative_data * relative_data + relative_model * relative_model);
    residual = (std::log(w.attenuation) - std::log(o.value)) / sigma_log;
    if (d_theta) {
      for (std::size_t i = 0; i < values.size(); ++i) {
        d_theta[i] = w.d_attenuation[i] * values[i] / (w.attenuation * sigma_log);
      }
    }
  } else {
    const double total = std::sqrt(sigma * sigma + w.sigma_speed * w.sigma_speed);
    residual = (w.speed - o.value) / total;
    if (d_theta) {
      for (std::size_t i = 0; i < values.size(); ++i) d_theta[i] = w.d_speed[i] * values[i] / total;
    }
  }
  return std::isfinite(residual);
}

}  // namespace sedwave::inversion
