#pragma once
// The long-wavelength limit of a prepared packing, from one quasi-static solve.
//
// When a wavelength spans hundreds of grains, no grain's inertia matters within it: the packing
// responds as a continuum with a complex modulus M, the homogenised K + i omega C of its contact
// network. Every dashpot is gamma times a fixed matrix, so M depends on omega and gamma only through
// x = omega_hat * gamma_hat, and with the packing's density rho
//   c_complex = sqrt(M / rho),  k = omega / c_complex,
//   alpha_hat / omega_hat = -Im(1 / c_hat_complex),  c_hat = 1 / Re(1 / c_hat_complex)
// are functions of x alone. That is the regime of field frequencies: omega_hat ~ 1e-5 .. 1e-3 for
// sand at 50 Hz .. 10 kHz (docs/tables.md), far below what a driven channel can resolve.
//
// How M is measured: the lower wall of the channel is displaced by a unit amplitude along the axis
// (z: compression, the P-wave modulus; x: shear, the shear modulus) at a frequency so low that the
// column's inertia changes nothing (k L ~ 1e-3), with the dashpots at x; the far wall is fixed. The
// stress is the force on the driven wall per cross-section (uniform along a column without
// inertia); the strain is the slope of the grains' displacement over the interior 60 % of the
// column, away from the walls' boundary layers. No wave travels, so neither the channel's length
// nor the elastic scattering of a narrow disordered channel enters.
//
// Units: dimensionless (channel/packing_units.hpp): modulus in kappa / d, density in m / d^3.
#include <complex>
#include <vector>

#include "sedwave/forward/linear/linear_channel.hpp"

namespace sedwave::forward::linear {

struct LongWavelengthLimit {
  double x = 0.0;                  ///< omega_hat * gamma_hat
  std::complex<double> modulus;    ///< stress / strain [kappa / d]
  double density = 0.0;            ///< mass of the grains with contacts per column volume [m / d^3]
  double alpha_over_omega = 0.0;   ///< alpha_hat / omega_hat
  double c_hat = 0.0;              ///< phase speed [d sqrt(kappa / m)]
  /// rms distance of the interior displacements from their fitted line, over the line's change
  /// across the fit: how affine the quasi-static response is (0 for an ordered chain).
  double non_affinity = 0.0;
  double solve_seconds = 0.0;
};

/// The limit of `channel` at x = omega_hat gamma_hat for waves along `axis` (longitudinal: P waves,
/// transverse: S waves). Throws std::invalid_argument for x < 0 or a column too short to fit.
[[nodiscard]] LongWavelengthLimit long_wavelength_limit(const LinearChannel& channel, double x,
                                                        channel::DriveAxis axis);

}  // namespace sedwave::forward::linear
