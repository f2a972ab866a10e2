// A model's derived quantities (SedimentModel::derived_quantities, derived_values): every one is
// described, its gradient agrees with central differences, its value with a closed form written
// out here, and its meaning with a limit of the model's own wave. And the catalog takes a model of
// a program's own (register_model).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/edfm.hpp"
#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/saturated_granular.hpp"

namespace sedwave::sediment {
namespace {

std::vector<std::shared_ptr<const SedimentModel>> every_model() {
  std::vector<std::shared_ptr<const SedimentModel>> all = model_examples();
  all.push_back(make_sediment_model("continuum", {DampingForm::Restitution, false}));
  all.push_back(make_sediment_model("saturated-lattice"));  // permeability from Kozeny-Carman
  return all;
}

double derived(const SedimentModel& model, const std::vector<double>& v, const std::string& name) {
  const std::vector<DerivedQuantity>& qs = model.derived_quantities();
  const auto it = std::find_if(qs.begin(), qs.end(), [&](const DerivedQuantity& q) { return q.name == name; });
  if (it == qs.end()) throw std::invalid_argument(model.name() + " derives no " + name);
  return model.derived_values(v, false)[static_cast<std::size_t>(it - qs.begin())].value;
}

double local_slope(const SedimentModel& model, const std::vector<double>& v, double f) {
  const double h = 1e-3;
  return std::log(model.evaluate(v, f * (1 + h), false).attenuation / model.evaluate(v, f * (1 - h), false).attenuation) /
         std::log((1 + h) / (1 - h));
}

TEST(DerivedQuantities, EveryModelDescribesAndDifferentiatesItsOwn) {
  for (const auto& model : every_model()) {
    SCOPED_TRACE(model->name());
    const std::vector<DerivedQuantity>& qs = model->derived_quantities();
    EXPECT_FALSE(qs.empty()) << "every shipped model derives at least one quantity";
    const std::vector<double> v = model->default_values();
    const std::vector<DerivedValue> at = model->derived_values(v, true);
    ASSERT_EQ(at.size(), qs.size());
    for (std::size_t k = 0; k < qs.size(); ++k) {
      SCOPED_TRACE(qs[k].name);
      EXPECT_FALSE(qs[k].unit.empty());
      EXPECT_FALSE(qs[k].meaning.empty());
      const bool has_range = qs[k].plausible_upper > qs[k].plausible_lower;
      EXPECT_TRUE(has_range || (qs[k].plausible_lower == 0.0 && qs[k].plausible_upper == 0.0));
      if (has_range) {
        EXPECT_FALSE(qs[k].plausible_basis.empty());
      }
      ASSERT_EQ(at[k].gradient.size(), v.size());
      EXPECT_GT(at[k].value, 0.0);
      EXPECT_NEAR(model->derived_values(v, false)[k].value, at[k].value, 1e-14 * at[k].value) << "same with Jets";
      // Central differences with a relative step 1e-6: truncation ~1e-12 and rounding ~1e-10
      // relative to q, so 1e-6 of |q| / value_i is a safe bound for a correct gradient.
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double h = 1e-6 * v[i];
        std::vector<double> up = v, down = v;
        up[i] += h;
        down[i] -= h;
        const double fd = (model->derived_values(up, false)[k].value - model->derived_values(down, false)[k].value) /
                          (2.0 * h);
        EXPECT_NEAR(at[k].gradient[i], fd, 1e-6 * at[k].value / v[i] + 1e-6 * std::abs(fd))
            << "d " << qs[k].name << " / d " << model->parameters()[i].name;
      }
    }
  }
}

// tau = gamma/kappa, f* = 1/(2 pi tau), gamma_hat = gamma/sqrt(kappa m), m = rho_s pi d^3/6;
// kappa_over_hertz against the site relation evaluated at this d (which also checks kappa_Hertz ~ d).
TEST(DerivedQuantities, GrainContactClosedForms) {
  const auto model = make_sediment_model("lattice");
  const double kappa = 2e6, d = 3e-4, gamma = 10.0, rho = 2650.0;
  const std::vector<double> v{kappa, d, gamma, rho};
  const double m = rho * std::numbers::pi * d * d * d / 6.0;
  EXPECT_NEAR(derived(*model, v, "tau") / (gamma / kappa), 1.0, 1e-14);
  EXPECT_NEAR(derived(*model, v, "f_star") / (kappa / (2.0 * std::numbers::pi * gamma)), 1.0, 1e-14);
  EXPECT_NEAR(derived(*model, v, "gamma_hat") / (gamma / std::sqrt(kappa * m)), 1.0, 1e-14);
  const double hertz = hertz_kappa_at_pressure(kQuartz, d, 1e4, 0.38, kDensePackCoordination);
  EXPECT_NEAR(derived(*model, v, "kappa_over_hertz") / (kappa / hertz), 1.0, 1e-12);
  // c0 is the f -> 0 limit of the model's own wave (omega_hat = 2 pi f sqrt(m/kappa) ~ 1e-8 here).
  EXPECT_NEAR(derived(*model, v, "c0") / model->evaluate(v, 1.0, false).speed, 1.0, 1e-9);
  EXPECT_NEAR(derived(*model, v, "c0") / (d * std::sqrt(kappa / m)), 1.0, 1e-14);
}

// For e_n, gamma_hat = sqrt(2) zeta with zeta = -ln e / sqrt(pi^2 + ln^2 e) (a Hooke collision of two
// equal grains), and tau = gamma_hat sqrt(kappa m) / kappa.
TEST(DerivedQuantities, RestitutionClosedForms) {
  const auto model = make_sediment_model("lattice", {DampingForm::Restitution, false});
  const double kappa = 2e6, d = 3e-4, e = 0.3, rho = 2650.0;
  const double m = rho * std::numbers::pi * d * d * d / 6.0;
  const double zeta = -std::log(e) / std::sqrt(std::numbers::pi * std::numbers::pi + std::log(e) * std::log(e));
  const std::vector<double> v{kappa, d, e, rho};
  EXPECT_NEAR(derived(*model, v, "gamma_hat") / (std::numbers::sqrt2 * zeta), 1.0, 1e-14);
  EXPECT_NEAR(derived(*model, v, "tau") / (std::numbers::sqrt2 * zeta * std::sqrt(kappa * m) / kappa), 1.0, 1e-14);
}

// EDFM: far below Biot's frequency the pore water moves with the frame, the effective density is the
// bulk density and the speed Wood's (Williams 2001); attenuation grows as f^2 there and as f^(1/2)
// far above it, so the local slope of ln alpha over ln f tells f_c's meaning.
TEST(DerivedQuantities, WoodSpeedAndBiotFrequencyAreTheEdfmLimits) {
  const EffectiveDensityFluidModel model;
  const std::vector<double> v = model.default_values();
  using P = PoreSpace;
  const double beta = v[P::kPorosity];
  const double k_wood = 1.0 / (beta / v[P::kWaterBulk] + (1.0 - beta) / v[P::kGrainBulk]);
  const double rho = beta * v[P::kWaterDensity] + (1.0 - beta) * v[P::kGrainDensity];
  const double fc = v[P::kViscosity] * beta / (2.0 * std::numbers::pi * v[P::kWaterDensity] * v[P::kPermeability]);
  EXPECT_NEAR(derived(model, v, "wood_speed") / std::sqrt(k_wood / rho), 1.0, 1e-14);
  EXPECT_NEAR(derived(model, v, "biot_frequency") / fc, 1.0, 1e-14);
  EXPECT_NEAR(model.evaluate(v, 1e-4 * fc, false).speed / std::sqrt(k_wood / rho), 1.0, 1e-6);
  EXPECT_NEAR(local_slope(model, v, 1e-3 * fc), 2.0, 0.01);
  EXPECT_NEAR(local_slope(model, v, 1e3 * fc), 0.5, 0.05);
}

// The saturated frame with Kozeny-Carman: biot_frequency uses k = d^2 beta^3 / (180 (1 - beta)^2).
TEST(DerivedQuantities, SaturatedFrameBiotFrequencyUsesKozenyCarman) {
  const auto model = make_sediment_model("saturated-lattice");
  const std::vector<double> v = model->default_values();
  const double d = v[1], beta = v[SaturatedGranularModel::kPorosity];
  const double k = d * d * beta * beta * beta / (180.0 * (1.0 - beta) * (1.0 - beta));
  const double fc = v[SaturatedGranularModel::kViscosity] * beta /
                    (2.0 * std::numbers::pi * v[SaturatedGranularModel::kWaterDensity] * k);
  EXPECT_NEAR(derived(*model, v, "biot_frequency") / fc, 1.0, 1e-14);
  EXPECT_THROW((void)derived(*model, v, "c0"), std::invalid_argument) << "c0 is the dry frame's speed";
}

// GS and VGS(lambda): with (almost) no intergranular shearing (gamma_p = gamma_s = 1 Pa, chi ~ 5e-10)
// the wave is Wood's suspension at any frequency (Buckingham 2000); VGS(lambda) turns viscous
// (attenuation ~ f^2) well below 1/(2 pi tau_p).
TEST(DerivedQuantities, GrainShearingWoodSpeedAndViscousFrequency) {
  const GrainShearingModel gs;
  std::vector<double> v = gs.default_values();
  using G = GrainShearingParameters;
  v[G::kGammaP] = v[G::kGammaS] = 1.0;
  EXPECT_NEAR(derived(gs, v, "wood_speed") / gs.evaluate(v, 1e3, false).speed, 1.0, 1e-8);
  const ViscousGrainShearingModel vgs;
  const std::vector<double> w = vgs.default_values();
  const double fp = 1.0 / (2.0 * std::numbers::pi * w[G::kViscousTime]);
  EXPECT_NEAR(derived(vgs, w, "viscous_frequency") / fp, 1.0, 1e-14);
  EXPECT_NEAR(local_slope(vgs, w, 1e-4 * fp), 2.0, 0.01);
}

/// A program's own model: a fluid of speed c with attenuation a0 (f / 1 kHz) [Np/m].
class LinearLossFluid final : public JetEvaluated<LinearLossFluid> {
 public:
  static constexpr int kParameters = 2;
  [[nodiscard]] std::string name() const override { return "test-linear-loss"; }
  [[nodiscard]] std::string summary() const override { return "a fluid with attenuation proportional to f"; }
  [[nodiscard]] const std::vector<Parameter>& parameters() const override { return parameters_; }
  template <typename T>
  WaveOf<T> wave(const T* v, double frequency_hz) const {
    return {v[1] * (frequency_hz / 1e3), v[0]};
  }

 private:
  std::vector<Parameter> parameters_{{"c", "m/s", 1600.0, 100.0, 1e4, false, "speed"},
                                     {"a0", "Np/m", 0.1, 1e-6, 1e3, true, "attenuation at 1 kHz"}};
};

TEST(Catalog, TakesAModelOfTheProgramsOwn) {
  register_model("test-linear-loss", [] { return std::make_shared<const LinearLossFluid>(); });
  const auto model = make_sediment_model("test-linear-loss");
  EXPECT_EQ(model->name(), "test-linear-loss");
  EXPECT_DOUBLE_EQ(model->evaluate(std::vector<double>{1600.0, 0.2}, 2e3, false).attenuation, 0.4);
  EXPECT_EQ(model->typical_free_parameters(), "c,a0") << "all parameters unless the model says";
  EXPECT_TRUE(model->derived_quantities().empty());
  EXPECT_EQ(model->dimensionless_engine(), nullptr);
  const std::vector<std::string> names = sediment_model_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "test-linear-loss"), names.end());
  const auto examples = model_examples();
  EXPECT_TRUE(std::any_of(examples.begin(), examples.end(), [](const auto& m) { return m->name() == "test-linear-loss"; }));
  // A taken name is refused, a built-in one as well; the built-in models are untouched.
  EXPECT_THROW(register_model("test-linear-loss", [] { return std::make_shared<const LinearLossFluid>(); }),
               std::invalid_argument);
  EXPECT_THROW(register_model("biot-stoll", [] { return std::make_shared<const LinearLossFluid>(); }),
               std::invalid_argument);
  EXPECT_THROW(register_model("lattice", [] { return std::make_shared<const LinearLossFluid>(); }),
               std::invalid_argument);
  // So is an entry whose own test would take a name the catalog lists (it would shadow that model).
  EXPECT_THROW(register_model({{"test-any-biot"},
                               [](const std::string&, const ModelChoices&) { return std::make_shared<const LinearLossFluid>(); },
                               [](const std::string& spec) { return spec.find("biot") != std::string::npos; },
                               {}}),
               std::invalid_argument);
  EXPECT_EQ(make_sediment_model("biot-stoll")->name(), "biot-stoll");
  EXPECT_EQ(make_sediment_model("saturated-continuum")->name(), "saturated-continuum");
  EXPECT_THROW((void)make_sediment_model("no-such-model"), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::sediment
