// The saturated granular model: limits against the dry frame, Wood, Gassmann and Kozeny-Carman,
// and its gradient against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>
#include <numbers>
#include <vector>

#include "sedwave/sediment/saturated_granular.hpp"
#include "sediment_test_support.hpp"

namespace sedwave::sediment {
namespace {

using S = SaturatedGranularModel;

using testing::chain;

TEST(SaturatedGranularModel, NamesItsFrameAndItsPermeabilitySource) {
  const S given(chain("lattice"), DampingForm::Gamma, PermeabilityFrom::Parameter);
  const S derived(chain("lattice"), DampingForm::Restitution, PermeabilityFrom::KozenyCarman);
  EXPECT_EQ(given.name(), "saturated-lattice");
  EXPECT_EQ(given.parameters().size(), 13u);
  EXPECT_EQ(derived.parameters().size(), 11u);
  EXPECT_NE(derived.summary().find("Kozeny-Carman"), std::string::npos);
  EXPECT_EQ(given.index_of("permeability"), S::kPermeability);
  EXPECT_EQ(derived.index_of("e_n"), S::kDamping);
  EXPECT_THROW((void)derived.index_of("permeability"), std::invalid_argument);
  for (const S* m : {&given, &derived}) EXPECT_NO_THROW(m->check_values(m->default_values()));
}

// With a vacuum in the pores the fast wave is the dry frame wave: M_frame = rho_frame (omega/k)^2
// put back into a medium of density (1 - beta) rho_s.
TEST(SaturatedGranularModel, VacuumInThePoresGivesTheDryFrameExactly) {
  for (const char* frame : {"lattice", "continuum"}) {
    const S saturated(chain(frame), DampingForm::Gamma, PermeabilityFrom::Parameter);
    const GrainContactModel dry(chain(frame), DampingForm::Gamma);
    std::vector<double> v = saturated.default_values();
    v[S::kWaterDensity] = 1e-6;
    v[S::kWaterBulk] = 1e-3;
    const std::vector<double> frame_values{v[S::kKappa], v[S::kDiameter], v[S::kDamping], v[S::kGrainDensity]};
    for (const double f : {1e3, 3e4, 1e5}) {
      const Wave w = saturated.evaluate(v, f, false), expected = dry.evaluate(frame_values, f, false);
      EXPECT_NEAR(w.speed / expected.speed, 1.0, 1e-7) << frame << " " << f;
      EXPECT_NEAR(w.attenuation / expected.attenuation, 1.0, 1e-6) << frame << " " << f;
    }
  }
}

TEST(SaturatedGranularModel, AVanishingFrameAtLowFrequencyGivesWoodWithoutAttenuation) {
  const S model(chain("lattice"), DampingForm::Gamma, PermeabilityFrom::Parameter);
  std::vector<double> v = model.default_values();
  v[S::kKappa] = 1e-3;  // frame P-wave modulus ~ 1e-3 Pa against K_Wood ~ 5 GPa
  const double f = 1e-4;
  const Wave w = model.evaluate(v, f, false);
  const double wood = wood_speed(v[S::kPorosity], v[S::kGrainDensity], v[S::kGrainBulk], v[S::kWaterDensity],
                                 v[S::kWaterBulk]);
  EXPECT_NEAR(w.speed / wood, 1.0, 1e-7);
  EXPECT_LT(w.attenuation, 1e-6 * 2 * std::numbers::pi * f / w.speed);
}

// The frame's own P-wave modulus at low frequency: its chain speed c0 = d sqrt(kappa/m) gives
// M_b = (1 - beta) rho_s c0^2; Gassmann then gives the locked-fluid speed.
double gassmann_speed(const std::vector<double>& v) {
  const double m = v[S::kGrainDensity] * std::numbers::pi * std::pow(v[S::kDiameter], 3) / 6.0;
  const double c0 = v[S::kDiameter] * std::sqrt(v[S::kKappa] / m);
  const double beta = v[S::kPorosity], nu = v[S::kFramePoisson];
  const double p_wave = (1 - beta) * v[S::kGrainDensity] * c0 * c0;
  const double kb = p_wave * (1 + nu) / (3 * (1 - nu)), mu = p_wave * (1 - 2 * nu) / (2 * (1 - nu));
  const double ks = v[S::kGrainBulk], kw = v[S::kWaterBulk];
  const double k_sat = kb + (1 - kb / ks) * (1 - kb / ks) / (beta / kw + (1 - beta) / ks - kb / (ks * ks));
  const double rho = beta * v[S::kWaterDensity] + (1 - beta) * v[S::kGrainDensity];
  return std::sqrt((k_sat + 4.0 / 3.0 * mu) / rho);
}

TEST(SaturatedGranularModel, LowFrequencyAndHighViscosityGiveGassmann) {
  const S model(chain("lattice"), DampingForm::Gamma, PermeabilityFrom::Parameter);
  std::vector<double> v = model.default_values();
  v[S::kKappa] = 1e6;  // a stiff frame so Gassmann's frame term matters (M_b ~ 2.6e9 Pa)
  EXPECT_NEAR(model.evaluate(v, 1e-4, false).speed / gassmann_speed(v), 1.0, 1e-6);
  // eta -> infinity: locked fluid at 1 kHz, where the frame (omega_hat ~ 1e-3) is still dispersion-free.
  v[S::kViscosity] = 1e9;
  EXPECT_NEAR(model.evaluate(v, 1e3, false).speed / gassmann_speed(v), 1.0, 1e-6);
}

TEST(SaturatedGranularModel, VanishingViscosityGivesTheTortuosityCoupledLimit) {
  const S model(chain("lattice"), DampingForm::Gamma, PermeabilityFrom::Parameter);
  std::vector<double> v = model.default_values();
  v[S::kKappa] = 1e6;
  v[S::kViscosity] = 1e-20;  // viscous terms vanish as sqrt(eta)
  const double f = 1e3;  // frame dispersion-free: M_b = (1 - beta) rho_s c0^2
  const double m = v[S::kGrainDensity] * std::numbers::pi * std::pow(v[S::kDiameter], 3) / 6.0;
  const double c0 = v[S::kDiameter] * std::sqrt(v[S::kKappa] / m);
  const double beta = v[S::kPorosity], nu = v[S::kFramePoisson], rf = v[S::kWaterDensity];
  const double p_wave = (1 - beta) * v[S::kGrainDensity] * c0 * c0;
  const double kb = p_wave * (1 + nu) / (3 * (1 - nu)), mu = p_wave * (1 - 2 * nu) / (2 * (1 - nu));
  // Biot 1956a non-dissipative fast wave with the tortuosity-coupled fluid mass alpha rho_f / beta.
  const double ks = v[S::kGrainBulk], kw = v[S::kWaterBulk];
  const double d = ks * (1 + beta * (ks / kw - 1));
  const double h = (ks - kb) * (ks - kb) / (d - kb) + kb + 4.0 / 3.0 * mu, c = ks * (ks - kb) / (d - kb),
               mm = ks * ks / (d - kb);
  const double rho = beta * rf + (1 - beta) * v[S::kGrainDensity], mass = v[S::kTortuosity] * rf / beta;
  const double qa = h * mm - c * c, qb = h * mass + rho * mm - 2 * c * rf, qc = rho * mass - rf * rf;
  const double fast = 1.0 / std::sqrt((qb - std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa));
  const Wave w = model.evaluate(v, f, false);
  EXPECT_NEAR(w.speed / fast, 1.0, 1e-6);
  EXPECT_GT(w.speed, gassmann_speed(v) * 1.0001);  // above the locked-fluid speed: it is a different limit
}

TEST(SaturatedGranularModel, KozenyCarmanModeEqualsGivenPermeabilityAtTheClosedForms) {
  const S given(chain("continuum"), DampingForm::Gamma, PermeabilityFrom::Parameter);
  const S derived(chain("continuum"), DampingForm::Gamma, PermeabilityFrom::KozenyCarman);
  std::vector<double> v = given.default_values();
  v[S::kDiameter] = 3e-4;
  v[S::kPorosity] = 0.38;
  const double d = v[S::kDiameter], beta = v[S::kPorosity];
  v[S::kPermeability] = d * d * beta * beta * beta / (180.0 * (1 - beta) * (1 - beta));
  v[S::kPoreSize] = d * beta / (3.0 * (1 - beta));
  const std::vector<double> short_v(v.begin(), v.begin() + S::kDerivedParameters);
  for (const double f : {1e2, 1e4, 1e5}) {
    const Wave a = given.evaluate(v, f, false), b = derived.evaluate(short_v, f, false);
    EXPECT_NEAR(a.speed, b.speed, 1e-12 * a.speed);
    EXPECT_NEAR(a.attenuation, b.attenuation, 1e-12 * a.attenuation);
  }
}

TEST(SaturatedGranularModel, GradientMatchesCentralDifferences) {
  for (const auto& [mode, form] : {std::pair{PermeabilityFrom::Parameter, DampingForm::Gamma},
                                   std::pair{PermeabilityFrom::KozenyCarman, DampingForm::Restitution}}) {
    const S model(chain("lattice"), form, mode);
    const std::vector<double> v = model.default_values();
    for (const double f : {3e3, 1e5}) {
      const Wave w = model.evaluate(v, f, true);
      ASSERT_EQ(w.d_speed.size(), v.size());
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double h = 1e-6 * std::abs(v[i]);  // every default is nonzero
        std::vector<double> up = v, down = v;
        up[i] += h;
        down[i] -= h;
        const Wave a = model.evaluate(up, f, false), b = model.evaluate(down, f, false);
        const double scale = std::abs(v[i]);
        EXPECT_NEAR(w.d_speed[i], (a.speed - b.speed) / (2 * h), 1e-5 * w.speed / scale)
            << model.parameters()[i].name << " f " << f;
        EXPECT_NEAR(w.d_attenuation[i], (a.attenuation - b.attenuation) / (2 * h), 1e-5 * w.attenuation / scale)
            << model.parameters()[i].name << " f " << f;
      }
    }
  }
}

}  // namespace
}  // namespace sedwave::sediment
