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
  // With x = omega_hat*gamma_hat and h = |1 - i x| = hypot(1, x), the principal root
  // s = sqrt(1 - i x) has Re s = sqrt((h + 1) / 2) and Im s = -x / (2 Re s); then
  // 1/s = conj(s) / h. Every step adds positive numbers, so both limits x -> 0 and x -> inf keep
  // full relative precision (no 1 - sqrt(1 + x^2) style cancellation).
  const double x = omega_hat * gamma_hat;
  const double h = std::hypot(1.0, x);
  const double re_s = std::sqrt(0.5 * (h + 1.0));
  const cd k(omega_hat * re_s / h, omega_hat * (x / (2.0 * re_s)) / h);
  // d/d omega_hat: k/omega_hat * (1 - i x/2) / (1 - i x);  d/d gamma_hat: k * (i omega_hat / 2) / (1 - i x).
  const cd one_minus_ix(1.0, -x);
  const cd dk_dw = (k / omega_hat) * (cd(1.0, -0.5 * x) / one_minus_ix);
  const cd dk_dg = k * (cd(0.0, 0.5 * omega_hat) / one_minus_ix);
  return {k, dk_dw, dk_dg};
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
