#include "sedwave/forward/theory/lattice.hpp"

#include <complex>

namespace sedwave::forward {

ComplexWavenumber lattice_wavenumber(double omega_hat, double gamma_hat) {
  // The dispersion relation of eq. 2.7 is sin(k~/2) = k~_continuum / 2, so k~ = 2 asin(z) with
  // z = k~_continuum / 2. Damping gives Im z > 0 and the principal asin then has Im > 0 (decay) and
  // no branch cut on the path. Without damping z is real with imaginary part +0, which glibc's
  // casin maps to the upper side of the cut: k~ = pi + 2i acosh(z) above the cutoff z = 1.
  const ComplexWavenumber continuum = continuum_wavenumber(omega_hat, gamma_hat);
  const std::complex<double> z = 0.5 * continuum.k;
  // d(2 asin z) = 2 dz / sqrt(1 - z^2) = dk_continuum / sqrt((1 - z)(1 + z)); the factored form
  // keeps the sign of zero imaginary parts consistent with the asin branch above the cutoff.
  const std::complex<double> one(1.0, 0.0);
  const std::complex<double> root = std::sqrt((one - z) * (one + z));
  return {2.0 * std::asin(z), continuum.dk_domega_hat / root, continuum.dk_dgamma_hat / root};
}

DispersionPoint LatticeModel::evaluate(double omega_hat, double gamma_hat) const {
  return dispersion_from_wavenumber(omega_hat, lattice_wavenumber(omega_hat, gamma_hat));
}

}  // namespace sedwave::forward
