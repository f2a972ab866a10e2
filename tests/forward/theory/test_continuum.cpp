// The continuum chain against its closed forms (thesis eqs. 2.16/2.17), its asymptotes, an
// extended-precision evaluation, and finite-difference derivatives.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "sedwave/forward/theory/continuum.hpp"

namespace sedwave::forward {
namespace {

// Independent reference: k~ = omega / sqrt(1 - i x) in 80-bit long double (64-bit mantissa).
std::complex<long double> reference_wavenumber(double omega_hat, double gamma_hat) {
  const long double w = omega_hat;
  const long double x = w * static_cast<long double>(gamma_hat);
  return w / std::sqrt(std::complex<long double>(1.0L, -x));
}

double relative_error(double value, long double reference) {
  return static_cast<double>(std::fabs((static_cast<long double>(value) - reference) / reference));
}

TEST(Continuum, MatchesThesisClosedForm) {
  // Eqs. 2.16 and 2.17, written out as printed.
  for (double w : {0.01, 0.3, 1.0, 4.0}) {
    for (double g : {0.05, 1.0, 20.0}) {
      const double x2 = (w * g) * (w * g);
      const double bracket = (1.0 + x2) * (1.0 + std::sqrt(1.0 + x2));
      const double alpha = w * w * g / std::sqrt(2.0) / std::sqrt(bracket);
      const double k = w / std::sqrt(2.0) * std::sqrt(bracket) / (1.0 + x2);
      const DispersionPoint p = ContinuumModel().evaluate(w, g);
      EXPECT_NEAR(p.alpha_hat / alpha, 1.0, 1e-14) << "w=" << w << " g=" << g;
      EXPECT_NEAR(p.c_hat / (w / k), 1.0, 1e-14) << "w=" << w << " g=" << g;
    }
  }
}

TEST(Continuum, AccurateForProductFrom1em10To1e10) {
  double worst = 0.0;
  for (double log_x = -10.0; log_x <= 10.0; log_x += 0.25) {
    for (double w : {1e-6, 1e-2, 1.0, 50.0}) {
      const double g = std::pow(10.0, log_x) / w;
      const ComplexWavenumber k = continuum_wavenumber(w, g);
      const std::complex<long double> ref = reference_wavenumber(w, g);
      worst = std::max({worst, relative_error(k.k.real(), ref.real()), relative_error(k.k.imag(), ref.imag())});
    }
  }
  EXPECT_LT(worst, 4e-15);
}

TEST(Continuum, LowFrequencyAsymptotes) {
  // omega_hat gamma_hat << 1: alpha_hat = omega_hat^2 gamma_hat / 2 (1 + O(x^2)), c_hat -> 1.
  const double g = 0.5;
  for (double w : {1e-8, 1e-6, 1e-4}) {
    const DispersionPoint p = ContinuumModel().evaluate(w, g);
    EXPECT_NEAR(p.alpha_hat / (0.5 * w * w * g), 1.0, 1e-7);
    EXPECT_NEAR(p.c_hat, 1.0, 1e-7);
  }
}

TEST(Continuum, HighFrequencyAsymptotes) {
  // omega_hat gamma_hat >> 1: k~ -> omega_hat e^{i pi/4} / sqrt(x), so alpha_hat = sqrt(omega_hat /
  // (2 gamma_hat)) (the f^(1/2) law) and c_hat = sqrt(2 omega_hat gamma_hat).
  const double g = 100.0;
  for (double w : {1e4, 1e6, 1e8}) {
    const DispersionPoint p = ContinuumModel().evaluate(w, g);
    EXPECT_NEAR(p.alpha_hat / std::sqrt(w / (2.0 * g)), 1.0, 1e-5);
    EXPECT_NEAR(p.c_hat / std::sqrt(2.0 * w * g), 1.0, 1e-5);
  }
}

TEST(Continuum, UndampedIsDispersionless) {
  const DispersionPoint p = ContinuumModel().evaluate(3.0, 0.0);
  EXPECT_EQ(p.alpha_hat, 0.0);
  EXPECT_DOUBLE_EQ(p.c_hat, 1.0);
}

TEST(Continuum, RejectsInvalidArguments) {
  const ContinuumModel model;
  EXPECT_THROW((void)model.evaluate(0.0, 1.0), std::domain_error);
  EXPECT_THROW((void)model.evaluate(-1.0, 1.0), std::domain_error);
  EXPECT_THROW((void)model.evaluate(1.0, -1.0), std::domain_error);
  EXPECT_THROW((void)model.evaluate(std::nan(""), 1.0), std::domain_error);
  EXPECT_THROW((void)model.evaluate(1.0, INFINITY), std::domain_error);
}

}  // namespace
}  // namespace sedwave::forward
