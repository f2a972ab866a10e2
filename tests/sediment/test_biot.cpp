// Biot's theory (biot.hpp): Kelvin functions and F(kappa) against reference values, Wood and
// Gassmann against their textbook forms, and the fast wave's limits against closed forms.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "sedwave/sediment/biot.hpp"
#include "sediment_test_support.hpp"

namespace sedwave::sediment {
namespace {

using testing::kTwoPi;

// Reference values of ber, bei and their derivatives computed with mpmath 1.3 (mp.ber, mp.bei and
// mp.diff at 30 digits), an independent arbitrary-precision implementation.
struct KelvinReference {
  double x, ber, bei, dber, dbei;
};
constexpr KelvinReference kKelvin[] = {
    {1.0, 0.98438178121308688, 0.24956604003665972, -0.06244575217903096, 0.49739651146809733},
    {5.0, -6.2300824786663577, 0.11603438155020038, -3.8453394732621545, -4.3541405148431109},
    {10.0, 138.84046594163265, 56.370458553906638, 51.195258393599611, 135.30930171596461},
    {17.9, 28365.181167541647, -8992.3853606210635, 25618.37380566284, 13960.765974133879},
    {18.1, 33619.164440033998, -5615.9815280558034, 26807.352815942547, 19967.706229649026},
    {25.0, 9797.7169497354903, -3808789.9114440357, 2700522.3179499553, -2609578.7488822996},
};

TEST(Kelvin, SeriesAndAsymptoticFormsMatchReferenceValues) {
  for (const KelvinReference& r : kKelvin) {
    const Complex<double> b = kelvin_ber_bei(r.x);
    const Complex<double> db = kelvin_ber_bei_derivative(r.x);
    // Relative to the modulus: ber and bei oscillate, so one of them can be near a zero.
    const double scale = std::hypot(r.ber, r.bei), dscale = std::hypot(r.dber, r.dbei);
    const double tol = r.x < kKelvinSeriesLimit ? 1e-13 : 1e-10;
    EXPECT_NEAR(b.re, r.ber, tol * scale) << "x = " << r.x;
    EXPECT_NEAR(b.im, r.bei, tol * scale) << "x = " << r.x;
    EXPECT_NEAR(db.re, r.dber, tol * dscale) << "x = " << r.x;
    EXPECT_NEAR(db.im, r.dbei, tol * dscale) << "x = " << r.x;
  }
}

// I_2 on the ray (the order F's series needs beside I_1) against mpmath 1.3 (mp.besseli(2, z) at
// z = x e^{i pi/4}, 30 digits); orders the series has no factors for are refused.
TEST(Kelvin, SecondOrderOnTheRayMatchesReferenceValues) {
  struct Reference {
    double x, re, im;
  };
  for (const Reference& r : {Reference{3.0, -0.80836846563726819091, 0.89102236377977331571},
                             Reference{10.0, 111.77860559843972449, 66.609510232626560509},
                             Reference{17.5, 18302.964323417072049, -10137.98074966985212}}) {
    const Complex<double> v = bessel_i_on_kelvin_ray(2, r.x);
    EXPECT_NEAR(v.re, r.re, 1e-13 * std::hypot(r.re, r.im)) << "x = " << r.x;
    EXPECT_NEAR(v.im, r.im, 1e-13 * std::hypot(r.re, r.im)) << "x = " << r.x;
  }
  EXPECT_THROW((void)bessel_i_on_kelvin_ray(kKelvinSeriesOrders, 1.0), std::invalid_argument);
}

// Biot's own expression F = (kappa/4) T / (1 - 2T/(i kappa)), T = (ber' + i bei')/(ber + i bei),
// evaluated with the Kelvin functions, where it has no cancellation (kappa >= 3).
Complex<double> biot_published_form(double kappa) {
  const Complex<double> t = kelvin_ber_bei_derivative(kappa) / kelvin_ber_bei(kappa);
  const Complex<double> i(0.0, 1.0);
  return Complex<double>(kappa / 4.0) * t / (Complex<double>(1.0) - Complex<double>(2.0) * t / (i * kappa));
}

TEST(ViscousCorrection, EqualsBiotsKelvinFunctionForm) {
  for (const double kappa : {3.0, 8.0, 15.0, 17.99, 18.01, 25.0, 40.0}) {
    const Complex<double> f = biot_viscous_correction(kappa), g = biot_published_form(kappa);
    EXPECT_NEAR(f.re, g.re, 1e-9 * abs(g)) << kappa;
    EXPECT_NEAR(f.im, g.im, 1e-9 * abs(g)) << kappa;
  }
}

// mpmath (z/4) I_1(z)/I_2(z) at z = kappa e^{i pi/4}, checked there against Biot's ber/bei form.
TEST(ViscousCorrection, MatchesReferenceValuesAndLimits) {
  struct {
    double kappa, re, im;
  } const reference[] = {{0.5, 1.0000542493517709, 0.010416214592939745},
                         {3.0, 1.0641003121371718, 0.3559953716762031},
                         {8.0, 1.8304660922044293, 1.3650376826293096},
                         {30.0, 5.6893429832489013, 5.2917245163242107},
                         {100.0, 18.055983909900027, 17.674307905049149}};
  for (const auto& r : reference) {
    const Complex<double> f = biot_viscous_correction(r.kappa);
    EXPECT_NEAR(f.re, r.re, 1e-12 * std::hypot(r.re, r.im)) << r.kappa;
    EXPECT_NEAR(f.im, r.im, 1e-12 * std::hypot(r.re, r.im)) << r.kappa;
  }
  // Poiseuille limit F -> 1 + i kappa^2 / 24 (the small-kappa expansion of R_1 / (2 R_2)).
  const Complex<double> small = biot_viscous_correction(1e-3);
  EXPECT_NEAR(small.re, 1.0, 1e-12);
  EXPECT_NEAR(small.im, 1e-6 / 24.0, 1e-15);
  // Boundary-layer limit F -> kappa (1 + i) / (4 sqrt 2) (Biot 1956b).
  const double kappa = 1e6;
  const Complex<double> large = biot_viscous_correction(kappa);
  EXPECT_NEAR(large.re / (kappa / (4.0 * std::numbers::sqrt2)), 1.0, 1e-5);
  EXPECT_NEAR(large.im / (kappa / (4.0 * std::numbers::sqrt2)), 1.0, 1e-5);
}

TEST(ViscousCorrection, IsContinuousWhereTheFormsSwitch) {
  const Complex<double> below = biot_viscous_correction(kKelvinSeriesLimit * (1.0 - 1e-12));
  const Complex<double> above = biot_viscous_correction(kKelvinSeriesLimit * (1.0 + 1e-12));
  EXPECT_NEAR(below.re, above.re, 1e-10 * abs(below));
  EXPECT_NEAR(below.im, above.im, 1e-10 * abs(below));
}

// Medium sand in sea water (defaults of docs/models/poroelastic.md).
BiotMedium<double> sand(Complex<double> frame_bulk, Complex<double> frame_shear, double viscosity) {
  return {frame_bulk, frame_shear, 0.40, 2650.0, 3.6e10, 1025.0, 2.31e9, viscosity, 4.0e-11, 1.75, 4.4e-5};
}

TEST(Mixtures, WoodIsTheReussAverage) {
  const double k = wood_bulk_modulus(0.4, 3.6e10, 2.31e9);
  EXPECT_NEAR(1.0 / k, 0.4 / 2.31e9 + 0.6 / 3.6e10, 1e-15 / k);
  EXPECT_NEAR(wood_speed(0.4, 2650.0, 3.6e10, 1025.0, 2.31e9), std::sqrt(k / (0.4 * 1025.0 + 0.6 * 2650.0)), 1e-9);
}

TEST(Mixtures, BiotHIsGassmannsPWaveModulusAndAFreeFrameGivesWood) {
  const Complex<double> kb(4.4e7, -2.1e6), mu(2.9e7, -1.4e6);
  const BiotModuli<double> m = biot_moduli(kb, mu, 0.4, 3.6e10, 2.31e9);
  const Complex<double> gassmann = gassmann_bulk_modulus(kb, 0.4, 3.6e10, 2.31e9) + mu * (4.0 / 3.0);
  EXPECT_NEAR(m.H.re, gassmann.re, 1e-9 * m.H.re);
  EXPECT_NEAR(m.H.im, gassmann.im, 1e-9 * m.H.re);
  const BiotModuli<double> free = biot_moduli(Complex<double>(0.0), Complex<double>(0.0), 0.4, 3.6e10, 2.31e9);
  const double wood = wood_bulk_modulus(0.4, 3.6e10, 2.31e9);
  for (const Complex<double>& c : {free.H, free.C, free.M}) EXPECT_NEAR(c.re / wood, 1.0, 1e-12);
}

TEST(Mixtures, PoissonSplitKeepsThePWaveModulusAndTheRatio) {
  const FrameModuli<double> f = split_p_wave_modulus(Complex<double>(1.0e8, -1.0e7), 0.2);
  const Complex<double> p = f.bulk + f.shear * (4.0 / 3.0);
  EXPECT_NEAR(p.re, 1.0e8, 1e-3);
  EXPECT_NEAR(p.im, -1.0e7, 1e-3);
  // nu = (3K - 2mu) / (2 (3K + mu)).
  EXPECT_NEAR((3 * f.bulk.re - 2 * f.shear.re) / (2 * (3 * f.bulk.re + f.shear.re)), 0.2, 1e-12);
}

// Roots of (HM - C^2) s^2 - (H m + rho M - 2 C rho_f) s + (rho m - rho_f^2) = 0 for a real m
// (Biot 1956a, the non-dissipative velocities), by the textbook formula in std::complex.
struct InviscidSpeeds {
  double fast, slow;
};
InviscidSpeeds inviscid_biot_speeds(const BiotMedium<double>& md) {
  const BiotModuli<double> bm = biot_moduli(md.frame_bulk, md.frame_shear, md.porosity, md.grain_bulk, md.fluid_bulk);
  const double h = bm.H.re, c = bm.C.re, m = bm.M.re;
  const double rho = md.porosity * md.fluid_density + (1 - md.porosity) * md.grain_density;
  const double rf = md.fluid_density, mass = md.tortuosity * rf / md.porosity;
  const double qa = h * m - c * c, qb = h * mass + rho * m - 2 * c * rf, qc = rho * mass - rf * rf;
  const double disc = std::sqrt(qb * qb - 4 * qa * qc);
  return {1.0 / std::sqrt((qb - disc) / (2 * qa)), 1.0 / std::sqrt((qb + disc) / (2 * qa))};
}

TEST(BiotFastWave, VanishingViscosityGivesTheInviscidHighFrequencyLimit) {
  // The viscous terms vanish as sqrt(eta): eta = 1e-20 Pa s leaves ~1e-9 of the fluid mass.
  const BiotMedium<double> md = sand(Complex<double>(4.4e7), Complex<double>(2.9e7), 1e-20);
  const double omega = kTwoPi * 1e4;
  const InviscidSpeeds expected = inviscid_biot_speeds(md);
  const AttenuationSpeed<double> fast = attenuation_and_speed(biot_fast_wavenumber(md, omega), omega);
  const AttenuationSpeed<double> slow = attenuation_and_speed(biot_slow_wavenumber(md, omega), omega);
  EXPECT_NEAR(fast.speed / expected.fast, 1.0, 1e-8);
  EXPECT_NEAR(slow.speed / expected.slow, 1.0, 1e-8);
  EXPECT_LT(slow.speed, 0.8 * fast.speed);  // the two are distinct: the fast one is returned
  EXPECT_LT(fast.attenuation, 1e-8 * omega / fast.speed);
}

TEST(BiotFastWave, InfiniteViscosityAndZeroFrequencyGiveGassmann) {
  const Complex<double> kb(4.4e7), mu(2.9e7);
  const double rho = 0.4 * 1025.0 + 0.6 * 2650.0;
  const double gassmann =
      std::sqrt((gassmann_bulk_modulus(kb, 0.40, 3.6e10, 2.31e9).re + 4.0 / 3.0 * mu.re) / rho);
  // Locked fluid: eta -> infinity at 10 kHz, and omega -> 0 at the water's own viscosity.
  for (const auto& [eta, f] : {std::pair{1e8, 1e4}, std::pair{1e-3, 1e-5}}) {
    const double omega = kTwoPi * f;
    const AttenuationSpeed<double> w = attenuation_and_speed(biot_fast_wavenumber(sand(kb, mu, eta), omega), omega);
    EXPECT_NEAR(w.speed / gassmann, 1.0, 1e-6) << "eta " << eta << " f " << f;
    EXPECT_LT(w.attenuation, 1e-6 * omega / w.speed);
    EXPECT_GT(w.attenuation, 0.0);
  }
}

TEST(BiotFastWave, ARigidityFreeFrameAtLowFrequencyIsWood) {
  const double omega = kTwoPi * 1e-3;
  const AttenuationSpeed<double> w = attenuation_and_speed(
      biot_fast_wavenumber(sand(Complex<double>(0.0), Complex<double>(0.0), 1e-3), omega), omega);
  EXPECT_NEAR(w.speed / wood_speed(0.40, 2650.0, 3.6e10, 1025.0, 2.31e9), 1.0, 1e-7);
}

TEST(BiotFastWave, NeverReturnsTheSlowWaveAcrossFrequencyAndFrameStiffness) {
  for (const double kb : {1e5, 1e7, 4.4e7, 1e9, 1e10}) {
    for (double f = 1.0; f <= 1e7; f *= 10.0) {
      const double omega = kTwoPi * f;
      const BiotMedium<double> md = sand(Complex<double>(kb, -0.05 * kb), Complex<double>(0.6 * kb, -0.03 * kb), 1e-3);
      const Complex<double> kf = biot_fast_wavenumber(md, omega), ks = biot_slow_wavenumber(md, omega);
      EXPECT_GT(kf.im, 0.0);
      EXPECT_GT(kf.re, 0.0);
      EXPECT_LT(kf.re, ks.re) << "K_b " << kb << " f " << f;  // slower wave = larger Re k
      EXPECT_LT(kf.im, ks.im) << "K_b " << kb << " f " << f;  // the slow wave is the lossier one
    }
  }
}

TEST(BiotFastWave, JetGradientMatchesFiniteDifferencesThroughTheSwitch) {
  // d speed / d pore size on both sides of the Kelvin series/asymptotic switch.
  using Jet = ceres::Jet<double, 1>;
  for (const double a : {1.0e-5, 4.4e-5}) {  // kappa = 8 and 35 at 100 kHz
    const double omega = kTwoPi * 1e5;
    auto medium = [&](auto pore) {
      using T = decltype(pore);
      return BiotMedium<T>{Complex<T>(T(4.4e7)), Complex<T>(T(2.9e7)), T(0.4), T(2650.0), T(3.6e10), T(1025.0),
                           T(2.31e9), T(1e-3), T(4e-11), T(1.75), pore};
    };
    const Jet speed = attenuation_and_speed(biot_fast_wavenumber(medium(Jet(a, 0)), omega), omega).speed;
    const double h = 1e-6 * a;
    const double up = attenuation_and_speed(biot_fast_wavenumber(medium(a + h), omega), omega).speed;
    const double down = attenuation_and_speed(biot_fast_wavenumber(medium(a - h), omega), omega).speed;
    EXPECT_NEAR(speed.v[0], (up - down) / (2 * h), 1e-5 * std::abs(speed.v[0]) + 1e-9 * speed.a / a);
  }
}

}  // namespace
}  // namespace sedwave::sediment
