#pragma once
// The wavenumber analysis of a granular-solid interface run (docs/interface.md, "Wavenumber
// spreading"): the spatial Fourier transform of the plate's velocity along the recorded line
// parallel to the interface, its kinetic-energy spectrum E(k, t), the variance sigma_k^2(t) of k
// under E, and a least-squares line sigma_k^2 = rate t + intercept. SI units: k [rad/m],
// E [J/m per unit of k-bin] (kinetic energy per unit depth of a strip of the plate's thickness),
// sigma_k^2 [rad^2/m^2], rate [rad^2/(m^2 s)].
#include <vector>

#include "sedwave/forward/experiment/interface_run.hpp"

namespace sedwave::forward::experiment {

/// Mean and variance of k under the weights E(k) (both zero when E sums to zero).
struct SpectrumMoments {
  double mean = 0.0;
  double variance = 0.0;
};
[[nodiscard]] SpectrumMoments spectrum_moments(const std::vector<double>& k, const std::vector<double>& energy);

/// Least-squares line y = slope x + intercept and its coefficient of determination.
struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double r_squared = 0.0;
};
[[nodiscard]] LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

struct WavenumberSpread {
  std::vector<double> k;                    ///< one-sided wavenumbers [rad/m]
  std::vector<std::vector<double>> energy;  ///< E(k, t) per sample [J/m]
  std::vector<double> line_energy;          ///< sum over k per sample [J/m]
  std::vector<double> variance;             ///< sigma_k^2(t) per sample [rad^2/m^2]
  std::size_t first = 0, last = 0;          ///< the samples fitted: line energy >= 1 % of its peak, from the peak on
  LineFit growth;                           ///< sigma_k^2 against t over [first, last)
};

/// `density` and `thickness` of the plate, `spacing` of the line's nodes.
[[nodiscard]] WavenumberSpread wavenumber_spread(const InterfaceRun& run, double density, double thickness,
                                                 double spacing);

}  // namespace sedwave::forward::experiment
