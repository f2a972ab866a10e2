// The shear waves of the sediment models against the closed forms and limits of their sources:
// Buckingham's GS closed forms (2005), the VGS(λ) shear time constant's defining condition (both
// waves turn viscous at one wavelength, Buckingham 2010) and its GS limit, Biot's shear wave in its
// low-frequency limit (the pore fluid moves with the frame: k_s^2 = omega^2 rho / mu), and the
// saturated frame's shear modulus from its Poisson ratio. Gradients against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "sedwave/sediment/biot_stoll.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/edfm.hpp"
#include "sedwave/sediment/grain_contact.hpp"
#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/saturated_granular.hpp"
#include "sediment_test_support.hpp"

namespace sedwave::sediment {
namespace {

using Std = std::complex<double>;

double bulk_density_of(const std::vector<double>& v) {  // GS order: porosity, rho_s, rho_w
  return v[0] * v[2] + (1.0 - v[0]) * v[1];
}

TEST(GrainShearingShear, MatchesBuckinghamsClosedForms) {
  const GrainShearingModel gs;
  const std::vector<double> v = gs.default_values();
  const double n = v[GrainShearingModel::kStrainHardening];
  const double reference_speed = std::sqrt(v[GrainShearingModel::kGammaS] / bulk_density_of(v));
  for (const double f : {10.0, 1e3, 1e5, 1e6}) {
    const double omega = testing::kTwoPi * f;
    const Wave w = gs.evaluate_shear(v, f, false);
    const double speed = reference_speed * std::pow(omega, n / 2.0) / std::cos(n * std::numbers::pi / 4.0);
    EXPECT_NEAR(w.speed / speed, 1.0, 1e-13) << f;
    EXPECT_NEAR(w.attenuation / (omega * std::tan(n * std::numbers::pi / 4.0) / speed), 1.0, 1e-12) << f;
  }
}

TEST(GrainShearingShear, TendsToALosslessElasticFrameAsTheIndexVanishes) {
  const GrainShearingModel gs;
  std::vector<double> v = gs.default_values();
  v[GrainShearingModel::kStrainHardening] = 1e-3;
  const double reference_speed = std::sqrt(v[GrainShearingModel::kGammaS] / bulk_density_of(v));
  const Wave w = gs.evaluate_shear(v, 1.0 / testing::kTwoPi, false);  // omega T = 1: (omega T)^n = 1
  EXPECT_NEAR(w.speed / reference_speed, 1.0, 1e-6);
  // alpha_s / k_s = tan(n pi/4) ~ n pi/4: the loss per wavelength vanishes with n.
  EXPECT_NEAR(w.attenuation * w.speed, std::tan(1e-3 * std::numbers::pi / 4.0), 1e-15);
}

/// c_p or c_s at omega = 1/tau of VGS(λ), evaluated by the model.
double speed_at_transition(const SedimentModel& m, const std::vector<double>& v, double tau, bool shear) {
  const double f = 1.0 / (testing::kTwoPi * tau);
  return (shear ? m.evaluate_shear(v, f, false) : m.evaluate(v, f, false)).speed;
}

TEST(ViscousGrainShearingShear, ShearTimeGivesOneTransitionWavelength) {
  const ViscousGrainShearingModel vgs;
  for (const double tau_p : {1.2e-4, 1e-6, 1e-2}) {
    std::vector<double> v = vgs.default_values();
    v[ViscousGrainShearingModel::kViscousTime] = tau_p;
    const double tau_s = vgs.derived_values(v, false)[2].value;
    // The defining condition c_s(1/tau_s) tau_s = c_p(1/tau_p) tau_p, each side from the model's waves.
    const double shear = speed_at_transition(vgs, v, tau_s, true) * tau_s;
    const double compressional = speed_at_transition(vgs, v, tau_p, false) * tau_p;
    EXPECT_NEAR(shear / compressional, 1.0, 1e-12) << tau_p;
    EXPECT_GT(tau_s, tau_p);  // the slower wave needs longer to cover the same wavelength
  }
}

TEST(ViscousGrainShearingShear, IsGrainShearingFarAboveItsTransition) {
  const ViscousGrainShearingModel vgs;
  const std::vector<double> v = vgs.default_values();
  const double tau_s = vgs.derived_values(v, false)[2].value;
  const double n = v[ViscousGrainShearingModel::kStrainHardening];
  const double reference_speed = std::sqrt(v[ViscousGrainShearingModel::kGammaS] / bulk_density_of(v));
  const double f = 1e6 / (testing::kTwoPi * tau_s);  // omega tau_s = 1e6
  const double omega = testing::kTwoPi * f;
  const Wave w = vgs.evaluate_shear(v, f, false);
  EXPECT_NEAR(w.speed / (reference_speed * std::pow(omega, n / 2.0) / std::cos(n * std::numbers::pi / 4.0)), 1.0, 1e-5);
}

TEST(ViscousGrainShearingShear, IsViscousFarBelowItsTransition) {
  const ViscousGrainShearingModel vgs;
  const std::vector<double> v = vgs.default_values();
  const double tau_s = vgs.derived_values(v, false)[2].value;
  const double n = v[ViscousGrainShearingModel::kStrainHardening];
  const double reference_speed = std::sqrt(v[ViscousGrainShearingModel::kGammaS] / bulk_density_of(v));
  const double f = 1e-6 / (testing::kTwoPi * tau_s);
  const double omega = testing::kTwoPi * f;
  // Psi_s -> i omega T^n tau_s^(1-n): k_s = (omega / c_s0) (i omega tau_s^(1-n))^(-1/2).
  const Std k = omega / reference_speed / std::sqrt(Std(0.0, omega * std::pow(tau_s, 1.0 - n)));
  const Wave w = vgs.evaluate_shear(v, f, false);
  EXPECT_NEAR(w.speed / (omega / k.real()), 1.0, 1e-5);
  EXPECT_NEAR(w.attenuation / -k.imag(), 1.0, 1e-5);
}

/// Biot's shear wave at low frequency, to first order in the relative motion of fluid and frame
/// (Stoll 1989, ch. 2): m~ -> i eta / (k omega) makes rho_f^2 / m~ -> -i rho_f^2 k omega / eta, so
///   k_s^2 = omega^2 (rho + i rho_f^2 k omega / eta) / mu,
/// the fluid moving with the frame (k_s^2 = omega^2 rho / mu) plus its first viscous loss.
Std low_frequency_biot_shear(double omega, double rho, double rho_f, double permeability, double viscosity, Std mu) {
  return omega * std::sqrt(Std(rho, rho_f * rho_f * permeability * omega / viscosity) / mu);
}

TEST(BiotStollShear, FluidMovesWithTheFrameAtLowFrequency) {
  const BiotStollModel bs;
  const std::vector<double> v = bs.default_values();
  const double rho = v[PoreSpace::kPorosity] * v[PoreSpace::kWaterDensity] +
                     (1.0 - v[PoreSpace::kPorosity]) * v[PoreSpace::kGrainDensity];
  const Std mu(v[BiotStollModel::kFrameShear], -v[BiotStollModel::kFrameShear] * v[BiotStollModel::kShearDecrement] / std::numbers::pi);
  for (const double f : {1e-3, 1e-1}) {
    const double omega = testing::kTwoPi * f;
    const Std k = low_frequency_biot_shear(omega, rho, v[PoreSpace::kWaterDensity], v[PoreSpace::kPermeability],
                                           v[PoreSpace::kViscosity], mu);
    const Wave w = bs.evaluate_shear(v, f, false);
    EXPECT_NEAR(w.speed / (omega / k.real()), 1.0, 1e-6) << f;
    EXPECT_NEAR(w.attenuation / k.imag(), 1.0, 1e-6) << f;
  }
  EXPECT_EQ(*bs.bulk_density(v), rho);
}
TEST(SaturatedGranularShear, FrameShearModulusFollowsFromThePoissonRatio) {
  const SaturatedGranularModel sat(testing::chain("lattice"), DampingForm::Gamma, PermeabilityFrom::KozenyCarman);
  std::vector<double> v = sat.default_values();
  v[SaturatedGranularModel::kKappa] = 1e6;
  v[SaturatedGranularModel::kDiameter] = 3e-4;
  v[SaturatedGranularModel::kDamping] = 5.0;
  const double f = 1e-1;
  const double omega = testing::kTwoPi * f;
  // The dry frame's own wave, from the dry model.
  const GrainContactModel dry(testing::chain("lattice"), DampingForm::Gamma);
  const std::vector<double> dry_values{v[0], v[1], v[2], v[3]};
  const Wave frame = dry.evaluate(dry_values, f, false);
  const double porosity = v[SaturatedGranularModel::kPorosity], nu = v[SaturatedGranularModel::kFramePoisson];
  const Std k_frame(omega / frame.speed, frame.attenuation);
  const Std p_wave_modulus = (1.0 - porosity) * v[SaturatedGranularModel::kGrainDensity] * omega * omega /
                             (k_frame * k_frame);
  const Std mu = p_wave_modulus * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
  const double rho = *sat.bulk_density(v);
  EXPECT_DOUBLE_EQ(rho, porosity * v[SaturatedGranularModel::kWaterDensity] +
                            (1.0 - porosity) * v[SaturatedGranularModel::kGrainDensity]);
  // Kozeny-Carman: k = d^2 beta^3 / (180 (1 - beta)^2).
  const double d = v[SaturatedGranularModel::kDiameter];
  const double permeability = d * d * porosity * porosity * porosity / (180.0 * (1.0 - porosity) * (1.0 - porosity));
  const Std k = low_frequency_biot_shear(omega, rho, v[SaturatedGranularModel::kWaterDensity], permeability,
                                         v[SaturatedGranularModel::kViscosity], mu);
  const Wave w = sat.evaluate_shear(v, f, false);
  EXPECT_NEAR(w.speed / (omega / k.real()), 1.0, 1e-6);
  EXPECT_NEAR(w.attenuation / k.imag(), 1.0, 1e-6);
}

void expect_shear_gradient_matches_central_differences(const SedimentModel& m, const std::vector<double>& v,
                                                       double f) {
  const Wave w = m.evaluate_shear(v, f, true);
  ASSERT_EQ(w.d_speed.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double h = 1e-6 * v[i];
    std::vector<double> up = v, down = v;
    up[i] += h;
    down[i] -= h;
    const Wave a = m.evaluate_shear(up, f, false), b = m.evaluate_shear(down, f, false);
    const double d_speed = (a.speed - b.speed) / (2.0 * h), d_alpha = (a.attenuation - b.attenuation) / (2.0 * h);
    EXPECT_NEAR(w.d_speed[i], d_speed, 1e-6 * std::abs(w.speed / v[i]) + 1e-7 * std::abs(d_speed))
        << m.name() << " " << m.parameters()[i].name;
    EXPECT_NEAR(w.d_attenuation[i], d_alpha, 1e-6 * std::abs(w.attenuation / v[i]) + 1e-7 * std::abs(d_alpha))
        << m.name() << " " << m.parameters()[i].name;
  }
}

TEST(ShearGradients, AreExact) {
  const GrainShearingModel gs;
  const ViscousGrainShearingModel vgs;
  const BiotStollModel bs;
  expect_shear_gradient_matches_central_differences(gs, gs.default_values(), 3e3);
  expect_shear_gradient_matches_central_differences(vgs, vgs.default_values(), 3e3);
  expect_shear_gradient_matches_central_differences(bs, bs.default_values(), 3e3);
  const SaturatedGranularModel sat(testing::chain("lattice"), DampingForm::Gamma, PermeabilityFrom::KozenyCarman);
  std::vector<double> v = sat.default_values();
  v[SaturatedGranularModel::kKappa] = 1e6;
  v[SaturatedGranularModel::kDiameter] = 3e-4;
  v[SaturatedGranularModel::kDamping] = 5.0;
  expect_shear_gradient_matches_central_differences(sat, v, 3e3);
}

TEST(Shear, ModelsWithoutAShearWaveSaySo) {
  const EffectiveDensityFluidModel edfm;
  EXPECT_FALSE(edfm.has_shear());
  EXPECT_THROW((void)edfm.evaluate_shear(edfm.default_values(), 1e3, false), std::logic_error);
  EXPECT_TRUE(edfm.bulk_density(edfm.default_values()).has_value());
  const auto dry = make_sediment_model("lattice");
  EXPECT_FALSE(dry->has_shear());
  EXPECT_FALSE(dry->bulk_density(dry->default_values()).has_value());
  for (const char* name : {"grain-shearing", "vgs-lambda", "biot-stoll", "saturated-lattice"}) {
    EXPECT_TRUE(make_sediment_model(name)->has_shear()) << name;
    EXPECT_FALSE(make_sediment_model(name)->shear_summary().empty()) << name;
  }
}

}  // namespace
}  // namespace sedwave::sediment
