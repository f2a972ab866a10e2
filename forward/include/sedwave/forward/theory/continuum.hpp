#pragma once
// Long-wavelength (continuum) limit of the 1D spring-dashpot chain, thesis eq. 2.8:
//   m y_tt = kappa d^2 y_xx + gamma d^2 y_txx.
// A plane wave exp(i(k~ x - omega t)) gives the complex wavenumber
//   k~ = omega_hat / sqrt(1 - i omega_hat gamma_hat),   k~ = k_hat + i alpha_hat,
// equivalent to eqs. 2.16/2.17. Evaluated without cancellation for any omega_hat*gamma_hat.
#include <complex>

#include "sedwave/forward/dispersion.hpp"

namespace sedwave::forward {

/// Complex dimensionless wavenumber k~ = k_hat + i alpha_hat of the continuum chain and its partials.
struct ComplexWavenumber {
  std::complex<double> k;
  std::complex<double> dk_domega_hat;
  std::complex<double> dk_dgamma_hat;
};

/// k~ of the continuum chain with exact derivatives. Requires omega_hat > 0, gamma_hat >= 0.
[[nodiscard]] ComplexWavenumber continuum_wavenumber(double omega_hat, double gamma_hat);

/// alpha_hat, c_hat and their gradients from a complex wavenumber (c_hat = omega_hat / k_hat).
[[nodiscard]] DispersionPoint dispersion_from_wavenumber(double omega_hat, const ComplexWavenumber& w);

class ContinuumModel final : public DispersionModel {
 public:
  [[nodiscard]] std::string name() const override { return "continuum"; }
  [[nodiscard]] DispersionPoint evaluate(double omega_hat, double gamma_hat) const override;
};

}  // namespace sedwave::forward
