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

/// An observation's value where residuals compare it: ln for an attenuation (of either wave), the
/// value itself for a speed, a bottom loss [dB] or |R|.
[[nodiscard]] inline double compared_value(const Observation& o) {
  return is_attenuation(o.quantity) ? std::log(o.value) : o.value;
}

/// The data's 1-sigma where residuals compare it: relative for an attenuation (sigma / value), in the
/// value's own unit otherwise.
[[nodiscard]] inline double compared_sigma(const Observation& o, double sigma) {
  return is_attenuation(o.quantity) ? sigma / o.value : sigma;
}

/// The whitened residual of a quantity observed as `observed` with 1-sigma `data_sigma` (both where
/// residuals compare them: compared_value, compared_sigma) against the wave `w` the model predicts at
/// its frequency for parameter `values` (its shear wave for a shear quantity; a reflection quantity is
/// no one wave's, and the fit computes it from the reflection coefficient); with `d_theta` non-null (and `w` holding derivatives) also
/// d residual / d ln value_i into d_theta[0 .. values.size()). `sigma_total` (if given) receives the
/// residual's whole 1-sigma, the model's own added. False where the residual is not defined (a
/// non-positive attenuation).
[[nodiscard]] inline bool whitened_residual(Quantity quantity, double observed, double data_sigma,
                                            const sediment::Wave& w, std::span<const double> values,
                                            double& residual, double* d_theta, double* sigma_total = nullptr) {
  const bool attenuation = is_attenuation(quantity);
  if (attenuation && !(w.attenuation > 0.0)) return false;
  const double model_sigma = attenuation ? w.sigma_attenuation / w.attenuation : w.sigma_speed;
  const double total = std::sqrt(data_sigma * data_sigma + model_sigma * model_sigma);
  residual = ((attenuation ? std::log(w.attenuation) : w.speed) - observed) / total;
  if (d_theta) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      d_theta[i] = attenuation ? w.d_attenuation[i] * values[i] / (w.attenuation * total) : w.d_speed[i] * values[i] / total;
    }
  }
  if (sigma_total) *sigma_total = total;
  return std::isfinite(residual);
}

/// The same for observation `o` with 1-sigma `sigma` in SI.
[[nodiscard]] inline bool whitened_residual(const Observation& o, double sigma, const sediment::Wave& w,
                                            std::span<const double> values, double& residual, double* d_theta) {
  return whitened_residual(o.quantity, compared_value(o), compared_sigma(o, sigma), w, values, residual, d_theta);
}

}  // namespace sedwave::inversion
