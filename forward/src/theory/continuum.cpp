#include "sedwave/forward/theory/continuum.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sedwave::forward {
namespace {

void require_valid(double omega_hat, double gamma_hat) {
  if (!(omega_hat > 0.0) || !std::isfinite(omega_hat)) {
    throw std::domain_error("omega_hat must be positive and finite, got " + std::to_string(omega_hat));
  }
  if (!(gamma_hat >= 0.0) || !std::isfinite(gamma_hat)) {
    throw std::domain_error("gamma_hat must be non-negative and finite, got " + std::to_string(gamma_hat));
  }
}

}  // namespace

ComplexWavenumber continuum_wavenumber(double omega_hat, double gamma_hat) {
  require_valid(omega_hat, gamma_hat);
  using cd = std::complex<double>;
  // With x = omega_hat*gamma_hat and h = |1 - i x| = sqrt(1 + x^2), the principal root
  // s = sqrt(1 - i x) has Re s = sqrt((h + 1) / 2) and Im s = -x / (2 Re s); then
  // 1/s = conj(s) / h. Every step adds positive numbers, so both limits x -> 0 and x -> inf keep
  // full relative precision (no 1 - sqrt(1 + x^2) style cancellation). Real arithmetic throughout:
  // hypot() and complex division cost three times the rest (docs/performance.md).
  const double x = omega_hat * gamma_hat;
  const double h = x < 1e150 ? std::sqrt(1.0 + x * x) : x;
  const double re_s = std::sqrt(0.5 * (h + 1.0));
  const double k_re = omega_hat * re_s / h;
  const double k_im = omega_hat * (x / (2.0 * re_s)) / h;
  // d/d omega_hat: k/omega_hat * (1 - i x/2) / (1 - i x) = k/omega_hat * (A + i B);
  // d/d gamma_hat: k * (i omega_hat / 2) / (1 - i x) = k * (C + i D), using
  // 1 / (1 - i x) = (1 + i x) q with q = 1 / (1 + x^2) (0 where x^2 overflows: the terms vanish).
  const double q = 1.0 / (1.0 + x * x);
  const double a = 0.5 + 0.5 * q, b = 0.5 * x * q;
  const double c = -0.5 * omega_hat * x * q, d = 0.5 * omega_hat * q;
  const double kw_re = k_re / omega_hat, kw_im = k_im / omega_hat;
  return {cd(k_re, k_im), cd(kw_re * a - kw_im * b, kw_re * b + kw_im * a), cd(k_re * c - k_im * d, k_re * d + k_im * c)};
}

DispersionPoint dispersion_from_wavenumber(double omega_hat, const ComplexWavenumber& w) {
  const double k_hat = w.k.real();
  DispersionPoint p;
  p.alpha_hat = w.k.imag();
  p.c_hat = omega_hat / k_hat;
  p.d_alpha_hat = {w.dk_domega_hat.imag(), w.dk_dgamma_hat.imag()};
  // c_hat = omega_hat / k_hat  =>  dc = dw / k_hat - omega_hat dk_hat / k_hat^2.
  p.d_c_hat = {(1.0 - p.c_hat * w.dk_domega_hat.real()) / k_hat, -p.c_hat * w.dk_dgamma_hat.real() / k_hat};
  return p;
}

DispersionPoint ContinuumModel::evaluate(double omega_hat, double gamma_hat) const {
  return dispersion_from_wavenumber(omega_hat, continuum_wavenumber(omega_hat, gamma_hat));
}

}  // namespace sedwave::forward
