// The discrete chain: its defining relation, the undamped band edge, the continuum limit, branch
// continuity, and derivatives of both 1D models against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "../derivative_check.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward {
namespace {

TEST(Lattice, SatisfiesDiscreteEquationOfMotion) {
  // A plane wave exp(i(k~ n - omega t)) solves m y''_n = (kappa + gamma d/dt)(y_{n+1} - 2 y_n + y_{n-1})
  // iff omega_hat^2 = 4 sin^2(k~/2) (1 - i omega_hat gamma_hat).
  for (double w : {1e-3, 0.5, 1.9, 2.0, 2.1, 5.0, 1e3}) {
    for (double g : {1e-3, 0.1, 1.0, 30.0}) {
      const std::complex<double> k = lattice_wavenumber(w, g).k;
      const std::complex<double> s = std::sin(0.5 * k);
      const std::complex<double> lhs = 4.0 * s * s * std::complex<double>(1.0, -w * g);
      EXPECT_LT(std::abs(lhs - w * w) / (w * w), 1e-13) << "w=" << w << " g=" << g;
      EXPECT_GE(k.imag(), 0.0);
      EXPECT_GT(k.real(), 0.0);
    }
  }
}

TEST(Lattice, UndampedPassBandAndEvanescentBand) {
  for (double w : {0.1, 1.0, 1.99}) {
    const DispersionPoint p = LatticeModel().evaluate(w, 0.0);
    EXPECT_EQ(p.alpha_hat, 0.0);
    EXPECT_NEAR(p.c_hat, w / (2.0 * std::asin(0.5 * w)), 1e-15);
  }
  for (double w : {2.01, 3.0, 100.0}) {
    const ComplexWavenumber k = lattice_wavenumber(w, 0.0);
    EXPECT_NEAR(k.k.real(), std::numbers::pi, 1e-15);  // neighbours move in antiphase
    EXPECT_NEAR(k.k.imag(), 2.0 * std::acosh(0.5 * w), 1e-13);
  }
}

TEST(Lattice, ContinuousThroughCutoffWithDamping) {
  for (double g : {1e-6, 1e-3, 0.1}) {
    const ComplexWavenumber below = lattice_wavenumber(2.0 - 1e-9, g);
    const ComplexWavenumber above = lattice_wavenumber(2.0 + 1e-9, g);
    EXPECT_LT(std::abs(below.k - above.k), 1e-3) << "g=" << g;
  }
  // Fine sweep: no jumps anywhere in omega_hat.
  std::complex<double> previous = lattice_wavenumber(1.0, 1e-4).k;
  for (double w = 1.0; w < 3.0; w += 1e-4) {
    const std::complex<double> k = lattice_wavenumber(w, 1e-4).k;
    EXPECT_LT(std::abs(k - previous), 0.05) << "w=" << w;
    previous = k;
  }
}

TEST(Lattice, ReducesToContinuumAtLowFrequency) {
  // k~ = 2 asin(k~_c / 2) = k~_c (1 + k~_c^2 / 24 + ...).
  for (double w : {1e-2, 1e-3, 1e-4}) {
    const std::complex<double> kl = lattice_wavenumber(w, 2.0).k;
    const std::complex<double> kc = continuum_wavenumber(w, 2.0).k;
    EXPECT_LT(std::abs(kl / kc - 1.0), 0.05 * std::norm(kc)) << "w=" << w;
    EXPECT_LT(std::abs(kl / kc - 1.0 - kc * kc / 24.0), std::pow(std::abs(kc), 4)) << "w=" << w;
  }
}

TEST(Lattice, ExtremeArgumentsStayFiniteAndPositive) {
  const ContinuumModel continuum;
  const LatticeModel lattice;
  for (const DispersionModel* model : {static_cast<const DispersionModel*>(&continuum),
                                       static_cast<const DispersionModel*>(&lattice)}) {
    for (double w = 1e-8; w <= 1e8; w *= 10.0) {
      for (double g : {0.0, 1e-8, 1.0, 1e8}) {
        const DispersionPoint p = model->evaluate(w, g);
        EXPECT_TRUE(std::isfinite(p.alpha_hat) && std::isfinite(p.c_hat)) << "w=" << w << " g=" << g;
        EXPECT_GE(p.alpha_hat, 0.0);
        EXPECT_GT(p.c_hat, 0.0);
        if (g > 0.0) {
          EXPECT_GT(p.alpha_hat, 0.0) << model->name() << " w=" << w << " g=" << g;
        }
      }
    }
  }
}

TEST(Lattice, LowFrequencyAttenuationIsTinyButRelativelyExact) {
  // At omega_hat = 1e-6 alpha_hat ~ 5e-13 gamma_hat: must keep full relative precision.
  const DispersionPoint p = LatticeModel().evaluate(1e-6, 1.0);
  EXPECT_NEAR(p.alpha_hat / 5e-13, 1.0, 1e-9);
}

TEST(Derivatives, BothModelsMatchFiniteDifferences) {
  const ContinuumModel continuum;
  const LatticeModel lattice;
  for (double w : {1e-4, 0.05, 0.7, 1.5, 2.5, 40.0}) {
    for (double g : {1e-3, 0.2, 3.0, 300.0}) {
      testing::expect_gradients_match_finite_differences(continuum, w, g, 1e-7);
      testing::expect_gradients_match_finite_differences(lattice, w, g, 1e-6);
    }
  }
}

}  // namespace
}  // namespace sedwave::forward
