#include "sedwave/forward/linear/equivalent_linearisation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sedwave::forward::linear {

EquivalentContact equivalent_contact(const std::function<double(double)>& force, double overlap, double amplitude,
                                     double tangent) {
  if (!(amplitude > 1e-6 * std::abs(overlap))) return {overlap > 0.0 ? tangent : 0.0, overlap > 0.0 ? 1.0 : 0.0};
  if (amplitude <= -overlap) return {0.0, 0.0};  // a gap the motion never closes
  const double theta_c = std::acos(std::clamp(-overlap / amplitude, -1.0, 1.0));  // closed for |theta| < theta_c
  // Gauss-Legendre on [0, theta_c]: the integrand is smooth there (F vanishes at theta_c).
  static constexpr double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                  0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static constexpr double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                  0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  constexpr int panels = 8;
  // F(delta0) is subtracted inside and its part, F0 sin(theta_c), added back exactly: for a << delta0
  // the integral is a small difference of large terms otherwise.
  const double f0 = overlap > 0.0 ? force(overlap) : 0.0;
  double integral = f0 * std::sin(theta_c);
  const double h = theta_c / panels;
  for (int p = 0; p < panels; ++p) {
    for (int q = 0; q < 8; ++q) {
      const double theta = h * (p + 0.5 * (x[q] + 1.0));
      const double delta = overlap + amplitude * std::cos(theta);
      integral += 0.5 * h * w[q] * ((delta > 0.0 ? force(delta) : 0.0) - f0) * std::cos(theta);
    }
  }
  return {2.0 * integral / (std::numbers::pi * amplitude),
          (theta_c - std::sin(theta_c) * std::cos(theta_c)) / std::numbers::pi};
}

}  // namespace sedwave::forward::linear
