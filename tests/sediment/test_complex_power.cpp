// Powers, exponential and logarithm of the Jet-capable Complex<T>, against std::complex<double>
// (an independent implementation) and, for derivatives, against d z^p / d p = ln(z) z^p.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include <complex>
#include <vector>

#include "sedwave/sediment/complex.hpp"

namespace sedwave::sediment {
namespace {

using Std = std::complex<double>;

void expect_near(const Complex<double>& z, const Std& expected, double relative) {
  const double tolerance = relative * std::abs(expected);
  EXPECT_NEAR(z.re, expected.real(), tolerance);
  EXPECT_NEAR(z.im, expected.imag(), tolerance);
}

// All four quadrants and both sides of the branch cut on the negative real axis.
const std::vector<Std> kPoints{{1.5, 0.3}, {-0.7, 2.0}, {-3.0, -0.4}, {0.2, -5.0}, {-2.0, 1e-12}, {-2.0, -1e-12}};

TEST(ComplexPower, MatchesStdComplexOnThePrincipalBranch) {
  for (const Std& z : kPoints) {
    for (const double p : {-0.5, 0.0851, -0.9383, 2.5}) {
      expect_near(pow(Complex<double>(z.real(), z.imag()), p), std::pow(z, p), 1e-13);
    }
  }
}

TEST(ComplexPower, ExpAndLogMatchStdComplex) {
  for (const Std& z : kPoints) {
    const Complex<double> c(z.real(), z.imag());
    expect_near(log(c), std::log(z), 1e-14);
    expect_near(exp(c), std::exp(z), 1e-14);
    EXPECT_NEAR(arg(c), std::arg(z), 1e-15);
  }
}

// (i x)^p = x^p e^{i p pi/2}.
TEST(ComplexPower, PowerOfAnImaginaryNumber) {
  for (const double x : {1e-6, 0.3, 6.3e5}) {
    for (const double p : {0.0617, 0.5, 0.99}) {
      expect_near(pow_imaginary(x, p), std::pow(Std(0.0, x), p), 1e-13);
    }
  }
}

// The Jet derivative with respect to the exponent is ln(z) z^p, and with respect to z (holomorphic)
// p z^(p-1): d/d re = p z^(p-1), d/d im = i p z^(p-1).
TEST(ComplexPower, JetDerivativesAreTheAnalyticOnes) {
  using Jet = ceres::Jet<double, 3>;
  const Std z(0.8, -1.3);
  const double p = -0.4;
  const Complex<Jet> zj(Jet(z.real(), 0), Jet(z.imag(), 1));
  const Complex<Jet> w = pow(zj, Jet(p, 2));
  const Std d_re = p * std::pow(z, p - 1.0);
  const Std d_im = Std(0.0, 1.0) * d_re;
  const Std d_p = std::log(z) * std::pow(z, p);
  EXPECT_NEAR(w.re.v[0], d_re.real(), 1e-13);
  EXPECT_NEAR(w.im.v[0], d_re.imag(), 1e-13);
  EXPECT_NEAR(w.re.v[1], d_im.real(), 1e-13);
  EXPECT_NEAR(w.im.v[1], d_im.imag(), 1e-13);
  EXPECT_NEAR(w.re.v[2], d_p.real(), 1e-13);
  EXPECT_NEAR(w.im.v[2], d_p.imag(), 1e-13);
}

}  // namespace
}  // namespace sedwave::sediment
