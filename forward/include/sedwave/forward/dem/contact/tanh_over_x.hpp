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
//
// tanh_over_x_in_lanes is the same function without a branch or a call, for loops the compiler runs
// several contacts at a time in SIMD lanes: both forms are computed and one selected, and e^{2x} is
// exp_in_lanes's polynomial (a scalar sticking contact pays for that exponential; the lanes do not).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

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

/// e^y for 0 <= y <= 40 without a branch or a call: y = k ln 2 + r with |r| <= ln 2 / 2, e^r by its
/// Taylor series to r^13 (truncation below 2e-16 relative), 2^k added to the exponent's bits. k is
/// rounded by adding the shifter 1.5 2^52, whose low bits then hold it, so no conversion to an integer
/// type is needed (SSE2 has none from doubles to 64-bit integers). ln 2 in two parts (Cody-Waite).
[[nodiscard]] inline double exp_in_lanes(double y) {
  constexpr double log2e = 1.4426950408889634, ln2_hi = 6.93147180369123816490e-01,
                   ln2_lo = 1.90821492927058770002e-10, shifter = 6755399441055744.0;
  const double shifted = y * log2e + shifter;
  const double k = shifted - shifter;
  const double r = (y - k * ln2_hi) - k * ln2_lo;
  // Horner's rule from 1/13!; written out, as a loop would be control flow in the lanes' loop.
  double p = 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  const std::uint64_t k_bits = std::bit_cast<std::uint64_t>(shifted) - std::bit_cast<std::uint64_t>(shifter);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(p) + (k_bits << 52));
}

/// tanh(x)/x for x >= 0 as tanh_over_x, without a branch (see the header's comment).
[[nodiscard]] inline double tanh_over_x_in_lanes(double x) {
  const double s = x * x;
  const double p = (-9.64399179425052238628e-1 * s - 9.92877231001918586564e1) * s - 1.61468768441708447952e3;
  const double q = ((s + 1.12811678491632931402e2) * s + 2.23548839060100448583e3) * s + 4.84406305325125486048e3;
  const double small = 1.0 + s * p / q;
  const double clamped = std::min(std::max(x, 0.625), 20.0);
  const double e = exp_in_lanes(2.0 * clamped);
  const double large = (e - 1.0) / ((e + 1.0) * std::max(x, 0.625));
  return x < 0.625 ? small : x == x ? large : x;  // NaN stays NaN
}

}  // namespace sedwave::forward::dem
