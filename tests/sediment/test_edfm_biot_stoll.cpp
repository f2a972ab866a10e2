// EDFM (Williams 2001) and Biot-Stoll (Stoll 1989): limits and asymptotes against closed forms.
//
// Published values: Williams et al., IEEE J. Ocean. Eng. 27, 413 (2002) compare both models with
// the SAX99 measurements, but neither that paper's parameter table nor its predictions could be
// consulted, so no printed value is tested. The tests check the closed forms the models must
// reduce to instead.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "sedwave/sediment/biot_stoll.hpp"
#include "sedwave/sediment/edfm.hpp"

namespace sedwave::sediment {
namespace {

using E = EffectiveDensityFluidModel;
using B = BiotStollModel;
using cd = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

double wood_of(const std::vector<double>& v) {
  return wood_speed(v[E::kPorosity], v[E::kGrainDensity], v[E::kGrainBulk], v[E::kWaterDensity], v[E::kWaterBulk]);
}

// Williams (2001): a fluid of Wood's bulk modulus and density
// rho_eff = (rho m - rho_f^2) / (m + rho - 2 rho_f), m = alpha rho_f / beta + i eta F* / (k omega),
// evaluated here in std::complex, apart from the Biot quadratic the model solves.
cd edfm_wavenumber(const std::vector<double>& v, double f) {
  const double omega = kTwoPi * f, beta = v[E::kPorosity], rf = v[E::kWaterDensity];
  const double rho = beta * rf + (1 - beta) * v[E::kGrainDensity];
  const double kappa = v[E::kPoreSize] * std::sqrt(omega * rf / v[E::kViscosity]);
  const Complex<double> F = biot_viscous_correction(kappa);
  const cd m = v[E::kTortuosity] * rf / beta + cd(0, 1) * v[E::kViscosity] * cd(F.re, -F.im) / (v[E::kPermeability] * omega);
  const cd rho_eff = (rho * m - rf * rf) / (m + rho - 2 * rf);
  const double k_wood = 1.0 / (beta / v[E::kWaterBulk] + (1 - beta) / v[E::kGrainBulk]);
  return omega * std::sqrt(rho_eff / k_wood);
}

TEST(Edfm, EqualsWilliamsEffectiveDensityFluidAtEveryFrequency) {
  const E model;
  const std::vector<double> v = model.default_values();
  for (double f = 1.0; f <= 1e7; f *= 10.0) {
    const cd k = edfm_wavenumber(v, f);
    const Wave w = model.evaluate(v, f, false);
    EXPECT_NEAR(w.speed / (kTwoPi * f / k.real()), 1.0, 1e-12) << f;
    EXPECT_NEAR(w.attenuation / k.imag(), 1.0, 1e-9) << f;
  }
}

TEST(Edfm, LowFrequencyIsWoodWithAttenuationGrowingAsFSquared) {
  const E model;
  const std::vector<double> v = model.default_values();
  const Wave a = model.evaluate(v, 1.0, false), b = model.evaluate(v, 2.0, false);
  EXPECT_NEAR(a.speed / wood_of(v), 1.0, 1e-6);
  EXPECT_NEAR(b.attenuation / a.attenuation, 4.0, 4e-4);
}

TEST(Edfm, HighFrequencyIsTheTortuosityCoupledFluidWithAttenuationAsRootF) {
  const E model;
  const std::vector<double> v = model.default_values();
  const double beta = v[E::kPorosity], rf = v[E::kWaterDensity];
  const double rho = beta * rf + (1 - beta) * v[E::kGrainDensity], m = v[E::kTortuosity] * rf / beta;
  const double rho_inf = (rho * m - rf * rf) / (m + rho - 2 * rf);
  const double k_wood = 1.0 / (beta / v[E::kWaterBulk] + (1 - beta) / v[E::kGrainBulk]);
  // The viscous terms fall as f^(-1/2): at 1e12 Hz (a mathematical limit, not a sediment
  // frequency) they are ~1e-5 of the inertia.
  const Wave a = model.evaluate(v, 1e12, false), b = model.evaluate(v, 4e12, false);
  EXPECT_NEAR(a.speed / std::sqrt(k_wood / rho_inf), 1.0, 1e-5);
  EXPECT_NEAR(b.attenuation / a.attenuation, 2.0, 1e-3);
  EXPECT_GT(a.speed, wood_of(v));
}

template <typename Model>
void expect_gradient_matches_central_differences(const Model& model, double f) {
  const std::vector<double> v = model.default_values();
  const Wave w = model.evaluate(v, f, true);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double h = 1e-6 * std::abs(v[i]);
    std::vector<double> up = v, down = v;
    up[i] += h;
    down[i] -= h;
    const Wave a = model.evaluate(up, f, false), b = model.evaluate(down, f, false);
    EXPECT_NEAR(w.d_speed[i], (a.speed - b.speed) / (2 * h), 1e-5 * w.speed / std::abs(v[i]))
        << model.parameters()[i].name << " f " << f;
    EXPECT_NEAR(w.d_attenuation[i], (a.attenuation - b.attenuation) / (2 * h), 1e-5 * w.attenuation / std::abs(v[i]))
        << model.parameters()[i].name << " f " << f;
  }
}

TEST(Edfm, GradientMatchesCentralDifferences) {
  for (const double f : {1e2, 1e4, 1e6}) expect_gradient_matches_central_differences(E{}, f);
}

// Gassmann's saturated P-wave modulus with Stoll's complex frame (exp(-i omega t): K (1 - i delta/pi)).
cd gassmann_p_wave(const std::vector<double>& v) {
  const cd kb = v[B::kFrameBulk] * cd(1.0, -v[B::kBulkDecrement] / std::numbers::pi);
  const cd mu = v[B::kFrameShear] * cd(1.0, -v[B::kShearDecrement] / std::numbers::pi);
  const double ks = v[B::kGrainBulk], kw = v[B::kWaterBulk], beta = v[B::kPorosity];
  const cd k_sat = kb + (1.0 - kb / ks) * (1.0 - kb / ks) / (beta / kw + (1 - beta) / ks - kb / (ks * ks));
  return k_sat + 4.0 / 3.0 * mu;
}

TEST(BiotStoll, LockedFluidIsGassmannWithConstantQFrameLoss) {
  const B model;
  std::vector<double> v = model.default_values();
  v[B::kViscosity] = 1e9;  // eta -> infinity: no relative flow, only the frame's loss remains
  const double rho = v[B::kPorosity] * v[B::kWaterDensity] + (1 - v[B::kPorosity]) * v[B::kGrainDensity];
  for (const double f : {1e2, 1e4}) {
    const cd k = kTwoPi * f * std::sqrt(rho / gassmann_p_wave(v));
    const Wave w = model.evaluate(v, f, false);
    EXPECT_NEAR(w.speed / (kTwoPi * f / k.real()), 1.0, 1e-7) << f;
    EXPECT_NEAR(w.attenuation / k.imag(), 1.0, 1e-5) << f;
  }
  // Constant decrement: attenuation proportional to f.
  EXPECT_NEAR(model.evaluate(v, 2e3, false).attenuation / model.evaluate(v, 1e3, false).attenuation, 2.0, 1e-5);
}

TEST(BiotStoll, LosslessFrameAndVanishingViscosityGiveTheInviscidBiotWave) {
  const B model;
  std::vector<double> v = model.default_values();
  v[B::kBulkDecrement] = v[B::kShearDecrement] = 0.0;
  v[B::kViscosity] = 1e-20;  // viscous terms vanish as sqrt(eta)
  const double beta = v[B::kPorosity], rf = v[B::kWaterDensity], ks = v[B::kGrainBulk], kw = v[B::kWaterBulk];
  const double kb = v[B::kFrameBulk], mu = v[B::kFrameShear];
  const double d = ks * (1 + beta * (ks / kw - 1));
  const double h = (ks - kb) * (ks - kb) / (d - kb) + kb + 4.0 / 3.0 * mu, c = ks * (ks - kb) / (d - kb),
               mm = ks * ks / (d - kb);
  const double rho = beta * rf + (1 - beta) * v[B::kGrainDensity], mass = v[B::kTortuosity] * rf / beta;
  const double qa = h * mm - c * c, qb = h * mass + rho * mm - 2 * c * rf, qc = rho * mass - rf * rf;
  const double fast = 1.0 / std::sqrt((qb - std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa));
  const double slow = 1.0 / std::sqrt((qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa));
  const Wave w = model.evaluate(v, 1e4, false);
  EXPECT_NEAR(w.speed / fast, 1.0, 1e-8);
  EXPECT_GT(std::abs(w.speed - slow), 0.3 * fast);  // not the slow wave
}

TEST(BiotStoll, ARigidityFreeFrameIsTheEdfm) {
  const B biot_stoll;
  const E edfm;
  std::vector<double> v = biot_stoll.default_values();
  v[B::kFrameBulk] = v[B::kFrameShear] = 0.0;
  const std::vector<double> e(v.begin(), v.begin() + E::kParameters);  // the shared leading parameters
  for (const double f : {1e2, 1e4, 1e6}) {
    const Wave a = biot_stoll.evaluate(v, f, false), b = edfm.evaluate(e, f, false);
    EXPECT_NEAR(a.speed, b.speed, 1e-12 * b.speed);
    EXPECT_NEAR(a.attenuation, b.attenuation, 1e-9 * b.attenuation);
  }
}

TEST(BiotStoll, GradientMatchesCentralDifferences) {
  for (const double f : {1e2, 1e4, 1e6}) expect_gradient_matches_central_differences(B{}, f);
}

TEST(PoroelasticModels, DefaultsLieInTheirRangesAndNamesAreStable) {
  const E e;
  const B b;
  EXPECT_EQ(e.name(), "edfm");
  EXPECT_EQ(b.name(), "biot-stoll");
  EXPECT_NO_THROW(e.check_values(e.default_values()));
  EXPECT_NO_THROW(b.check_values(b.default_values()));
  for (std::size_t i = 0; i < E::kParameters; ++i) EXPECT_EQ(e.parameters()[i].name, b.parameters()[i].name);
}

}  // namespace
}  // namespace sedwave::sediment
