// Plane-wave reflection at the seabed against closed forms and identities: Rayleigh's coefficient of
// a fluid half-space, its critical and intromission angles and grazing limit; the fluid-solid
// coefficient of Brekhovskikh & Lysanov and its fluid limit; energy conservation; layers that must
// leave R unchanged, the quarter-wave matching layer, total reflection through a lossless stack,
// and thick lossy stacks at 100 kHz.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/reflection.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::sediment {
namespace {

using Std = std::complex<double>;
constexpr double kDegree = std::numbers::pi / 180.0;

const AcousticMedium kWater{1500.0, 0.0, 0.0, 0.0, 1000.0};

LayeredHalfspace over(const AcousticMedium& halfspace, std::vector<MediumLayer> layers = {}) {
  return {kWater, std::move(layers), halfspace};
}

/// Rayleigh (e.g. Brekhovskikh & Lysanov, Fundamentals of Ocean Acoustics, ch. 2), grazing angle:
/// R = (m sin theta - sqrt(n^2 - cos^2 theta)) / (m sin theta + sqrt(n^2 - cos^2 theta)),
/// n = c_w / c_b, m = rho_b / rho_w; the root's branch decays into the bottom for e^{-i omega t}.
Std rayleigh(double c_b, double rho_b, double theta) {
  const double n = kWater.compressional_speed / c_b, m = rho_b / kWater.density;
  const double radicand = n * n - std::cos(theta) * std::cos(theta);
  const Std root = radicand >= 0.0 ? Std(std::sqrt(radicand), 0.0) : Std(0.0, std::sqrt(-radicand));
  return (m * std::sin(theta) - root) / (m * std::sin(theta) + root);
}

TEST(FluidHalfspace, IsRayleighsCoefficient) {
  const AcousticMedium sand{1700.0, 0.0, 0.0, 0.0, 1900.0};
  for (double deg = 0.5; deg <= 90.0; deg += 0.5) {
    const Std r = reflection_coefficient(over(sand), deg * kDegree, 1e3);
    EXPECT_LT(std::abs(r - rayleigh(1700.0, 1900.0, deg * kDegree)), 1e-13) << deg;
  }
}

TEST(FluidHalfspace, ReflectsTotallyBelowTheCriticalAngleOnlyWithoutLoss) {
  const AcousticMedium sand{1700.0, 0.0, 0.0, 0.0, 1900.0};
  const double critical = std::acos(1500.0 / 1700.0);
  for (const double theta : {0.1 * critical, 0.5 * critical, critical - 1e-9}) {
    EXPECT_NEAR(std::abs(reflection_coefficient(over(sand), theta, 1e3)), 1.0, 1e-14) << theta;
  }
  EXPECT_LT(std::abs(reflection_coefficient(over(sand), critical + 1e-6, 1e3)), 1.0 - 1e-4);
  AcousticMedium lossy = sand;
  lossy.compressional_attenuation = 0.5;  // Np/m at 1 kHz: about 0.5 dB per wavelength
  EXPECT_LT(std::abs(reflection_coefficient(over(lossy), 0.5 * critical, 1e3)), 1.0 - 1e-3);
}

TEST(FluidHalfspace, VanishesAtTheIntromissionAngle) {
  // c_b < c_w and rho_b c_b > rho_w c_w: sin^2 theta = (n^2 - 1) / (m^2 - 1) lies in (0, 1).
  const double c_b = 1450.0, rho_b = 1600.0;
  const double n = 1500.0 / c_b, m = rho_b / 1000.0;
  const double theta = std::asin(std::sqrt((n * n - 1.0) / (m * m - 1.0)));
  const AcousticMedium mud{c_b, 0.0, 0.0, 0.0, rho_b};
  EXPECT_LT(std::abs(reflection_coefficient(over(mud), theta, 1e3)), 1e-14);
  EXPECT_GT(std::abs(reflection_coefficient(over(mud), theta + 1.0 * kDegree, 1e3)), 1e-3);
  // A slower bottom of lower impedance than water (rho_b c_b < rho_w c_w) has none: the ratio exceeds 1.
  const AcousticMedium light{1450.0, 0.0, 0.0, 0.0, 1020.0};
  ASSERT_GT((n * n - 1.0) / ((1.02 * 1.02) - 1.0), 1.0);
  // Its smallest |R| is at normal incidence, |Z_b - Z_w| / (Z_b + Z_w) = 0.0071, not zero.
  const double normal = (1500.0 * 1000.0 - 1450.0 * 1020.0) / (1500.0 * 1000.0 + 1450.0 * 1020.0);
  for (double deg = 0.0; deg <= 90.0; deg += 0.25) {
    EXPECT_GE(std::abs(reflection_coefficient(over(light), deg * kDegree, 1e3)), normal * (1.0 - 1e-12)) << deg;
  }
  // A faster, denser bottom (n < 1 < m) has no such angle: (n^2 - 1) / (m^2 - 1) < 0.
  const AcousticMedium sand{1700.0, 0.0, 0.0, 0.0, 1900.0};
  for (double deg = 0.0; deg <= 90.0; deg += 0.25) {
    EXPECT_GT(std::abs(reflection_coefficient(over(sand), deg * kDegree, 1e3)), 0.2) << deg;
  }
}

TEST(Halfspace, ReflectionTendsToMinusOneAtGrazingIncidence) {
  const std::vector<AcousticMedium> bottoms{{1700.0, 0.0, 0.0, 0.0, 1900.0},
                                            {1700.0, 2.0, 0.0, 0.0, 1900.0},
                                            {1450.0, 0.1, 0.0, 0.0, 1300.0},
                                            {1800.0, 1.0, 400.0, 5.0, 2000.0},
                                            {3000.0, 0.1, 1700.0, 0.2, 2500.0}};
  for (const AcousticMedium& b : bottoms) {
    EXPECT_LT(std::abs(reflection_coefficient(over(b), 0.0, 1e3) + 1.0), 1e-15);
    EXPECT_LT(std::abs(reflection_coefficient(over(b), 1e-7, 1e3) + 1.0), 1e-4);
  }
}

/// Brekhovskikh & Lysanov (Fundamentals of Ocean Acoustics, ch. 2) for water over a solid, with
/// angles from the normal: R = (Z_p cos^2 2t_s + Z_s sin^2 2t_s - Z_w) / (same + Z_w),
/// Z = rho c / cos t, sin t = c p; complex speeds for loss, cos t = c q on the decaying branch.
Std fluid_solid(const AcousticMedium& b, double theta, double f) {
  const double omega = 2.0 * std::numbers::pi * f;
  const double p = std::cos(theta) / kWater.compressional_speed;
  const auto complex_speed = [&](double c, double alpha) { return 1.0 / Std(1.0 / c, alpha / omega); };
  const Std cp = complex_speed(b.compressional_speed, b.compressional_attenuation);
  const Std cs = complex_speed(b.shear_speed, b.shear_attenuation);
  const auto cosine = [&](Std c) {
    Std q = std::sqrt(1.0 / (c * c) - p * p);
    if (q.imag() < 0.0) q = -q;
    return c * q;
  };
  const Std sin_s = cs * p, cos_s = cosine(cs);
  const Std zw = kWater.density * kWater.compressional_speed / std::sin(theta);
  const Std zp = b.density * cp / cosine(cp), zs = b.density * cs / cos_s;
  const Std cos2 = 1.0 - 2.0 * sin_s * sin_s, sin2 = 2.0 * sin_s * cos_s;
  const Std z = zp * cos2 * cos2 + zs * sin2 * sin2;
  return (z - zw) / (z + zw);
}

TEST(ElasticHalfspace, IsTheFluidSolidClosedForm) {
  const std::vector<AcousticMedium> bottoms{{1800.0, 0.0, 400.0, 0.0, 2000.0},
                                            {1800.0, 1.0, 400.0, 8.0, 2000.0},
                                            {3000.0, 0.0, 1700.0, 0.0, 2500.0},
                                            {3000.0, 0.3, 1400.0, 0.9, 2500.0}};
  for (const AcousticMedium& b : bottoms) {
    for (double deg = 0.5; deg <= 90.0; deg += 0.5) {
      const Std r = reflection_coefficient(over(b), deg * kDegree, 2e3);
      EXPECT_LT(std::abs(r - fluid_solid(b, deg * kDegree, 2e3)), 1e-12) << b.shear_speed << " " << deg;
    }
  }
}

TEST(ElasticHalfspace, BecomesTheFluidAsTheShearSpeedVanishes) {
  for (double deg = 1.0; deg <= 90.0; deg += 1.0) {
    const Std elastic = reflection_coefficient(over({1700.0, 0.5, 1e-2, 0.0, 1900.0}), deg * kDegree, 1e3);
    const Std fluid = reflection_coefficient(over({1700.0, 0.5, 0.0, 0.0, 1900.0}), deg * kDegree, 1e3);
    EXPECT_LT(std::abs(elastic - fluid), 1e-6) << deg;
  }
}

TEST(ElasticHalfspace, ConservesEnergyWithoutLoss) {
  // Shear slower than water (one critical angle, P) and faster (two: P and S).
  for (const AcousticMedium& b : {AcousticMedium{1800.0, 0.0, 600.0, 0.0, 2000.0},
                                  AcousticMedium{3000.0, 0.0, 1700.0, 0.0, 2500.0}}) {
    for (double deg = 0.25; deg <= 90.0; deg += 0.25) {
      const InterfaceWaves w = interface_waves(kWater, b, deg * kDegree, 1e3);
      const double transmitted =
          b.density * (w.p_vertical_slowness.real() * std::norm(w.transmitted_p) +
                       w.s_vertical_slowness.real() * std::norm(w.transmitted_s)) /
          (kWater.density * w.water_vertical_slowness.real());
      EXPECT_NEAR(std::norm(w.reflection) + transmitted, 1.0, 1e-12) << b.shear_speed << " " << deg;
    }
  }
}

TEST(Layers, OfTheHalfspacesOwnMaterialChangeNothing) {
  for (const AcousticMedium& b : {AcousticMedium{1700.0, 0.3, 0.0, 0.0, 1900.0},
                                  AcousticMedium{1800.0, 0.3, 500.0, 2.0, 2000.0}}) {
    for (const double h : {0.01, 1.0, 30.0}) {
      for (double deg = 1.0; deg <= 90.0; deg += 7.0) {
        const Std bare = reflection_coefficient(over(b), deg * kDegree, 1e3);
        const Std layered = reflection_coefficient(over(b, {{b, h}, {b, 2.0 * h}}), deg * kDegree, 1e3);
        EXPECT_LT(std::abs(layered - bare), 1e-13) << b.shear_speed << " " << h << " " << deg;
      }
    }
  }
}

TEST(Layers, QuarterWaveMatchingLayerReflectsNothing) {
  const AcousticMedium bottom{2000.0, 0.0, 0.0, 0.0, 2200.0};
  const double z_water = 1500.0 * 1000.0, z_bottom = 2000.0 * 2200.0;
  const double c_layer = 1650.0, f = 5e3;
  const AcousticMedium layer{c_layer, 0.0, 0.0, 0.0, std::sqrt(z_water * z_bottom) / c_layer};
  const double quarter = c_layer / (4.0 * f);
  EXPECT_LT(std::abs(reflection_coefficient(over(bottom, {{layer, quarter}}), std::numbers::pi / 2.0, f)), 1e-14);
  // Half a wavelength is transparent instead: R is the bare bottom's.
  EXPECT_NEAR(std::abs(reflection_coefficient(over(bottom, {{layer, 2.0 * quarter}}), std::numbers::pi / 2.0, f)),
              std::abs(reflection_coefficient(over(bottom), std::numbers::pi / 2.0, f)), 1e-14);
}

TEST(Layers, LosslessStackBeyondEveryCriticalAngleReflectsTotally) {
  // Nothing propagates in the half-space below grazing angles with cos theta > c_w / c_s(half-space),
  // and the layers keep all energy: |R| = 1, whatever the layers' evanescent and propagating waves.
  const AcousticMedium solid_layer{1700.0, 0.0, 400.0, 0.0, 1900.0};
  const AcousticMedium fluid_layer{1600.0, 0.0, 0.0, 0.0, 1700.0};
  const AcousticMedium rock{3500.0, 0.0, 2000.0, 0.0, 2600.0};
  const double limit = std::acos(1500.0 / 2000.0);
  for (double theta = 0.5 * kDegree; theta < limit; theta += 2.0 * kDegree) {
    const Std r = reflection_coefficient(
        over(rock, {{fluid_layer, 3.0}, {solid_layer, 0.7}, {fluid_layer, 0.2}, {solid_layer, 2.5}}), theta, 2e3);
    EXPECT_NEAR(std::abs(r), 1.0, 1e-12) << theta;
  }
}

TEST(Layers, ThickLossyStacksAtHighFrequencyStayFiniteAndShowTheTopLayer) {
  // 100 kHz, 10 layers of 10 m with 26-50 dB/m (sand at 100 kHz: about 30 dB/m): a wave returning
  // from below the top layer is e^{-60} weaker or less, so R is the top layer's as a half-space.
  // Propagator products would overflow here (e^{+alpha h} per layer, e^{+600} over the stack).
  const double f = 1e5;
  for (const bool elastic : {false, true}) {
    std::vector<MediumLayer> layers;
    for (int i = 0; i < 10; ++i) {
      const double cs = elastic ? 200.0 + 30.0 * i : 0.0;
      layers.push_back({{1600.0 + 20.0 * i, 3.0 + 0.3 * i, cs, elastic ? 20.0 : 0.0, 1700.0 + 30.0 * i}, 10.0});
    }
    const AcousticMedium rock{3000.0, 0.1, elastic ? 1500.0 : 0.0, elastic ? 0.2 : 0.0, 2500.0};
    for (double deg = 0.5; deg <= 90.0; deg += 0.5) {
      const Std r = reflection_coefficient(over(rock, layers), deg * kDegree, f);
      ASSERT_TRUE(std::isfinite(r.real()) && std::isfinite(r.imag())) << deg;
      const Std top = reflection_coefficient(over(layers.front().medium), deg * kDegree, f);
      EXPECT_LT(std::abs(r - top), 1e-12) << elastic << " " << deg;
    }
  }
}

TEST(BandAverage, OfAFrequencyIndependentBottomIsItsPower) {
  const AcousticMedium sand{1700.0, 0.0, 0.0, 0.0, 1900.0};
  const std::vector<double> angles{10.0 * kDegree, 45.0 * kDegree, 80.0 * kDegree};
  const std::vector<double> power =
      band_averaged_power([&](double) { return over(sand); }, angles, 1e3, 1.0 / 3.0, 7);
  for (std::size_t i = 0; i < angles.size(); ++i) {
    EXPECT_NEAR(power[i], std::norm(rayleigh(1700.0, 1900.0, angles[i])), 1e-14);
  }
  // A layer's interference averages out over a band wide against its resonance spacing c/(2h): at
  // normal incidence the mean of |(a + b e^{i phi}) / (1 + a b e^{i phi})|^2 over phi is the incoherent
  // sum (a^2 + b^2 - 2 a^2 b^2) / (1 - a^2 b^2) of the interfaces' coefficients a and b.
  const AcousticMedium layer{1600.0, 0.0, 0.0, 0.0, 1500.0};
  const auto layered = [&](double) { return over(sand, {{layer, 50.0}}); };
  const std::vector<double> normal{std::numbers::pi / 2.0};
  const double a = (1600.0 * 1500.0 - 1500.0 * 1000.0) / (1600.0 * 1500.0 + 1500.0 * 1000.0);
  const double b = (1700.0 * 1900.0 - 1600.0 * 1500.0) / (1700.0 * 1900.0 + 1600.0 * 1500.0);
  const double incoherent = (a * a + b * b - 2.0 * a * a * b * b) / (1.0 - a * a * b * b);
  const double wide = band_averaged_power(layered, normal, 1e3, 1.0, 801).front();
  EXPECT_NEAR(wide / incoherent, 1.0, 0.02);
  const double single = band_averaged_power(layered, normal, 1e3, 1.0, 1).front();
  EXPECT_GT(std::abs(single / incoherent - 1.0), 0.05);  // one frequency: the interference remains
}

TEST(Seabed, FromModelsUsesTheirWavesAndDensity) {
  const auto gs = std::make_shared<GrainShearingModel>();
  SeabedModel seabed;
  seabed.halfspace = {gs, gs->default_values(), 0.0};
  const LayeredHalfspace at = layered_halfspace_at(seabed, 1e3);
  const Wave p = gs->evaluate(gs->default_values(), 1e3, false), s = gs->evaluate_shear(gs->default_values(), 1e3, false);
  EXPECT_EQ(at.halfspace.compressional_speed, p.speed);
  EXPECT_EQ(at.halfspace.shear_attenuation, s.attenuation);
  EXPECT_EQ(at.halfspace.density, *gs->bulk_density(gs->default_values()));
  seabed.fluid_only = true;
  EXPECT_EQ(layered_halfspace_at(seabed, 1e3).halfspace.shear_speed, 0.0);
}

/// A layered model from the catalog is its parts: its stack equals the one built part by part, its
/// parameters are the half-space's then lN.thickness and lN.NAME, and its own wave is the top
/// layer's with the gradient in the top layer's places.
TEST(Seabed, LayeredModelIsItsParts) {
  const auto model = make_sediment_model("layered:grain-shearing+edfm");
  const auto gs = make_sediment_model("grain-shearing");
  const auto edfm = make_sediment_model("edfm");
  const std::size_t below = edfm->parameters().size();
  ASSERT_EQ(model->parameters().size(), below + 1 + gs->parameters().size());
  EXPECT_EQ(model->parameters()[below].name, "l1.thickness");
  EXPECT_EQ(model->parameters()[below + 1].name, "l1." + gs->parameters()[0].name);
  std::vector<double> values = edfm->default_values();
  values.push_back(0.8);
  for (double v : gs->default_values()) values.push_back(v);
  SeabedModel by_hand;
  by_hand.layers.push_back({gs, gs->default_values(), 0.8});
  by_hand.halfspace = {edfm, edfm->default_values(), 0.0};
  const SeabedModel described = seabed_of(model, values, by_hand.water_speed, by_hand.water_density);
  for (double f : {500.0, 5e3}) {
    for (double angle : {0.1, 0.5, 1.2}) {
      EXPECT_EQ(reflection_coefficient(layered_halfspace_at(described, f), angle, f),
                reflection_coefficient(layered_halfspace_at(by_hand, f), angle, f));
    }
  }
  const Wave top = gs->evaluate(gs->default_values(), 2e3, true);
  const Wave own = model->evaluate(values, 2e3, true);
  EXPECT_EQ(own.speed, top.speed);
  EXPECT_EQ(own.attenuation, top.attenuation);
  for (std::size_t i = 0; i <= below; ++i) EXPECT_EQ(own.d_speed[i], 0.0);
  for (std::size_t i = 0; i < top.d_speed.size(); ++i) EXPECT_EQ(own.d_speed[below + 1 + i], top.d_speed[i]);
  EXPECT_THROW((void)make_sediment_model("layered:edfm"), std::invalid_argument);
  EXPECT_THROW((void)make_sediment_model("layered:edfm++edfm"), std::invalid_argument);
}

TEST(Reflection, RefusesImpossibleInput) {
  EXPECT_THROW((void)reflection_coefficient(over({-1.0, 0.0, 0.0, 0.0, 1900.0}), 0.3, 1e3), std::invalid_argument);
  EXPECT_THROW((void)reflection_coefficient(over({1700.0, -0.1, 0.0, 0.0, 1900.0}), 0.3, 1e3), std::invalid_argument);
  EXPECT_THROW((void)reflection_coefficient(over({1700.0, 0.0, 0.0, 0.0, 1900.0}), 2.0, 1e3), std::invalid_argument);
  EXPECT_THROW((void)reflection_coefficient(over({1700.0, 0.0, 0.0, 0.0, 1900.0}), 0.3, 0.0), std::invalid_argument);
  EXPECT_THROW((void)reflection_coefficient(over({1700.0, 0.0, 0.0, 0.0, 1900.0}, {{kWater, -1.0}}), 0.3, 1e3),
               std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::sediment
