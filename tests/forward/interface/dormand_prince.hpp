#pragma once
// The interface tests' independent integrator: Dormand & Prince (1980) 5(4) with the usual step
// control (Hairer, Norsett & Wanner, Solving ODEs I, sec. II.4-5): error per component against
// atol_i + rtol |y_i|, factor 0.9 err^(-1/5) in [0.2, 5]. For autonomous systems y' = rhs(y).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace sedwave::forward::interface::test {

template <class Rhs>
std::vector<double> dormand_prince(std::vector<double> y, double t_end, const Rhs& rhs, const std::vector<double>& atol,
                                   double rtol) {
  static constexpr double a[7][6] = {{},
                                     {1.0 / 5},
                                     {3.0 / 40, 9.0 / 40},
                                     {44.0 / 45, -56.0 / 15, 32.0 / 9},
                                     {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
                                     {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
                                     {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  static constexpr double b5[7] = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
  static constexpr double b4[7] = {5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100,
                                   1.0 / 40};
  double t = 0.0, h = t_end * 1e-6;
  const std::size_t n = y.size();
  while (t < t_end) {
    h = std::min(h, t_end - t);
    std::array<std::vector<double>, 7> stage;
    for (int s = 0; s < 7; ++s) {
      std::vector<double> ys = y;
      for (int r = 0; r < s; ++r)
        for (std::size_t i = 0; i < n; ++i) ys[i] += h * a[s][r] * stage[static_cast<std::size_t>(r)][i];
      stage[static_cast<std::size_t>(s)] = rhs(ys);
    }
    std::vector<double> y5 = y;
    double err = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double e = 0.0;
      for (std::size_t s = 0; s < 7; ++s) {
        y5[i] += h * b5[s] * stage[s][i];
        e += h * (b5[s] - b4[s]) * stage[s][i];
      }
      err = std::max(err, std::abs(e) / (atol[i] + rtol * std::abs(y5[i])));
    }
    if (err <= 1.0) {
      t += h;
      y = y5;
    }
    h *= std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0);
  }
  return y;
}

}  // namespace sedwave::forward::interface::test
