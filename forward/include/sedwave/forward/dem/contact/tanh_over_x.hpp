#pragma once
// tanh(x)/x for x >= 0, as accurate as std::tanh (3.8e-16 relative at worst against long double,
// std::tanh 3.9e-16: tests/forward/dem/test_contact_laws.cpp) at about half its cost. Coulomb-tanh friction
// needs tanh(k_s |v|)/|v| for every sliding contact each step, and glibc's tanh goes through expm1,
// which was 15-25 % of a frictional interface run.
//   x < 0.625: the odd rational tanh(x) = x + x^3 P(x^2)/Q(x^2) of Cephes' tanh.c (S. L. Moshier,
//              Cephes Math Library, 1989; peak relative error 2.5e-16 on [-0.625, 0.625]), divided by x;
//   x >= 0.625: (e^{2x} - 1)/((e^{2x} + 1) x), no cancellation (e^{2x} > 3.4) and one division; the
//              exponent stops at 40, past which tanh is 1 in double precision (beyond x = 19.1).
// Exactly 1 at x = 0, so the friction law needs no branch at zero slip; NaN stays NaN.
#include <algorithm>
#include <cmath>

namespace sedwave::forward::dem {

[[nodiscard]] inline double tanh_over_x(double x) {
  if (x < 0.625) {
    const double s = x * x;
    const double p = (-9.64399179425052238628e-1 * s - 9.92877231001918586564e1) * s - 1.61468768441708447952e3;
    const double q = ((s + 1.12811678491632931402e2) * s + 2.23548839060100448583e3) * s + 4.84406305325125486048e3;
    return 1.0 + s * p / q;
  }
  const double e = std::exp(2.0 * std::min(x, 20.0));  // min(NaN, 20) is NaN (std::min returns its first)
  return (e - 1.0) / ((e + 1.0) * x);
}

}  // namespace sedwave::forward::dem
