#pragma once
// Shared test helper: compare a model's analytic gradients with central finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "sedwave/forward/dispersion.hpp"

namespace sedwave::forward::testing {

/// Central difference of f at x with relative step h, Richardson-extrapolated (error O(h^4)).
template <typename F>
double richardson_derivative(F f, double x, double h_rel = 1e-3) {
  const double h = h_rel * x;
  const double d1 = (f(x + h) - f(x - h)) / (2.0 * h);
  const double d2 = (f(x + 0.5 * h) - f(x - 0.5 * h)) / h;
  return (4.0 * d2 - d1) / 3.0;
}

inline void expect_gradients_match_finite_differences(const DispersionModel& model, double w, double g,
                                                      double tolerance) {
  const DispersionPoint p = model.evaluate(w, g);
  auto alpha_w = [&](double x) { return model.evaluate(x, g).alpha_hat; };
  auto alpha_g = [&](double x) { return model.evaluate(w, x).alpha_hat; };
  auto c_w = [&](double x) { return model.evaluate(x, g).c_hat; };
  auto c_g = [&](double x) { return model.evaluate(w, x).c_hat; };
  // Compare derivatives scaled to d(value)/d(ln input), relative to the value: the quantity that
  // matters for a fit in log space, and well defined where a derivative itself is tiny.
  auto check = [&](double analytic, double numeric, double input, double value, const char* what) {
    EXPECT_NEAR(analytic * input / value, numeric * input / value, tolerance)
        << model.name() << " " << what << " at w=" << w << " g=" << g;
  };
  check(p.d_alpha_hat.d_omega_hat, richardson_derivative(alpha_w, w), w, p.alpha_hat, "d alpha/d omega");
  check(p.d_alpha_hat.d_gamma_hat, richardson_derivative(alpha_g, g), g, p.alpha_hat, "d alpha/d gamma");
  check(p.d_c_hat.d_omega_hat, richardson_derivative(c_w, w), w, p.c_hat, "d c/d omega");
  check(p.d_c_hat.d_gamma_hat, richardson_derivative(c_g, g), g, p.c_hat, "d c/d gamma");
}

}  // namespace sedwave::forward::testing
