// Fits with every sediment model (sediment/catalog.hpp) through the same solver: each model's own
// synthetic data, fitted back from a start away from the truth, must give the truth within the
// reported uncertainty; parameters of another model are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/jet_evaluated.hpp"

namespace sedwave::inversion {
namespace {

struct Case {
  std::string model;
  std::vector<std::pair<std::string, double>> truth;  ///< free parameters and their true values
  double lowest_hz, highest_hz;
};

FitParameters with(const sediment::SedimentModel& model, const Case& c, double start_factor) {
  FitParameters p(model.parameters());
  for (const auto& [name, value] : c.truth) {
    ParameterSpec& s = p.spec[p.index_of(name)];
    s.value = value * start_factor;
    s.free = true;
  }
  return p;
}

// Each model's free parameters are ones its wave determines over the band (others stay at their
// defaults). Noise 2 % on attenuation, 0.5 % on speed; seeds fixed, so the test is deterministic.
TEST(SedimentFits, EveryModelRecoversItsTruthWithinItsUncertainty) {
  const std::vector<Case> cases{
      {"saturated-lattice", {{"kappa", 5.0e5}, {"gamma", 10.0}}, 100.0, 1.0e5},
      {"edfm", {{"porosity", 0.4}, {"permeability", 2.0e-11}}, 100.0, 1.0e5},
      {"biot-stoll", {{"K_b", 5.0e7}, {"permeability", 2.0e-11}}, 100.0, 1.0e5},
      {"grain-shearing", {{"gamma_p", 3.0e8}, {"n", 0.09}}, 100.0, 1.0e5},
      {"vgs-lambda", {{"gamma_p", 3.0e8}, {"tau_p", 1.0e-4}}, 100.0, 1.0e5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.model);
    const auto model = sediment::make_sediment_model(c.model);
    const FitParameters truth = with(*model, c, 1.0);
    const ObservationSet data = synthetic_observations(*model, truth, {c.lowest_hz, c.highest_hz, 20, 0.02, 0.005, 7});
    const FitResult r = fit(data, *model, with(*model, c, 1.3), FitOptions{.method = FitMethod::Ceres});
    ASSERT_TRUE(r.converged) << r.solver_message;
    EXPECT_LT(r.chi2, 40 + 3 * std::sqrt(80.0)) << "40 observations";
    for (const auto& [name, value] : c.truth) {
      const ParameterResult& p = r.parameters[static_cast<std::size_t>(truth.index_of(name))];
      EXPECT_TRUE(p.determined) << name;
      EXPECT_LT(std::abs(std::log(p.value / value)), 3.0 * p.log_sigma + 1e-9)
          << name << " = " << p.value << " +- " << p.sigma << ", truth " << value;
    }
  }
}

TEST(SedimentFits, ParametersOfAnotherModelAreRefused) {
  const auto edfm = sediment::make_sediment_model("edfm");
  const auto gs = sediment::make_sediment_model("grain-shearing");
  FitParameters p(gs->parameters());
  p.set_free_from_list("n");
  const ObservationSet data = synthetic_observations(*edfm, FitParameters(edfm->parameters()), {1e2, 1e4, 5, 0.1, 0.01, 1});
  try {
    (void)fit(data, *edfm, p, FitOptions{.method = FitMethod::Ceres});
    FAIL() << "grain-shearing parameters accepted by edfm";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not those of model 'edfm'"), std::string::npos) << e.what();
  }
}

// A sand (d >= 62.5 um) whose fitted porosity is that of a mud is flagged, with its cause.
TEST(SedimentFits, SandWithMudPorosityIsFlagged) {
  const auto model = sediment::make_sediment_model("saturated-continuum");
  FitParameters truth(model->parameters());
  truth.spec[truth.index_of("kappa")].value = 5.0e5;
  truth.spec[truth.index_of("d")].value = 3.0e-4;
  truth.spec[truth.index_of("gamma")].value = 10.0;
  truth.spec[truth.index_of("porosity")].value = 0.8;
  const ObservationSet data = synthetic_observations(*model, truth, {100.0, 1.0e5, 12, 0.02, 0.005, 3});
  FitParameters start = truth;
  start.set_free_from_list("kappa,porosity");
  const FitResult r = fit(data, *model, start, FitOptions{.method = FitMethod::Ceres, .profile_likelihood = false});
  bool flagged = false;
  for (const PlausibilityFlag& f : r.flags) flagged = flagged || (f.quantity == "porosity" && f.message.find("sand") != std::string::npos);
  EXPECT_TRUE(flagged);
}

/// A program's own model: a fluid of speed c [m/s] whose attenuation a0 (f / 1 kHz) [Np/m] makes
/// the loss per wavelength alpha lambda = a0 c / 1 kHz the same at every f. Its plausible range is
/// set below the truth used here so that the flag must fire.
class LinearLossFluid final : public sediment::JetEvaluated<LinearLossFluid> {
 public:
  static constexpr int kParameters = 2;
  [[nodiscard]] std::string name() const override { return "test-linear-loss-fluid"; }
  [[nodiscard]] std::string summary() const override { return "a fluid with attenuation proportional to f"; }
  [[nodiscard]] const std::vector<sediment::Parameter>& parameters() const override { return parameters_; }
  [[nodiscard]] const std::vector<sediment::DerivedQuantity>& derived_quantities() const override { return derived_; }
  template <typename T>
  sediment::WaveOf<T> wave(const T* v, double frequency_hz) const {
    return {v[1] * (frequency_hz / 1e3), v[0]};
  }
  template <typename T>
  std::vector<T> derived(const T* v) const {
    return {v[1] * v[0] / 1e3};
  }

 private:
  std::vector<sediment::Parameter> parameters_{{"c", "m/s", 1500.0, 100.0, 1e4, false, "speed"},
                                               {"a0", "Np/m", 0.05, 1e-6, 1e3, true, "attenuation at 1 kHz"}};
  std::vector<sediment::DerivedQuantity> derived_{
      {"loss_per_wavelength", "1", "alpha lambda", 1e-3, 1e-2, "a test range", "too low", "too high"}};
};

// A registered model of the program's own goes through the library's fit by name: its derived
// quantity is reported with an interval that covers the truth, and judged by its own range.
TEST(OwnModel, RegisteredFitsAndIsJudgedByItsOwnDerivedQuantities) {
  sediment::register_model("test-linear-loss-fluid", [] { return std::make_shared<const LinearLossFluid>(); });
  const auto model = sediment::make_sediment_model("test-linear-loss-fluid");
  FitParameters truth(model->parameters());
  truth.set_free_from_list(model->typical_free_parameters());
  truth.spec[truth.index_of("c")].value = 1600.0;
  truth.spec[truth.index_of("a0")].value = 0.1;
  const ObservationSet data = synthetic_observations(*model, truth, {100.0, 1e5, 20, 0.02, 0.003, 7});
  FitParameters start = truth;
  start.spec[start.index_of("c")].value = 1500.0;
  start.spec[start.index_of("a0")].value = 0.05;
  const FitResult r = fit(data, *model, start, {.method = FitMethod::Ceres});
  const DerivedResult& loss = by_name(r.derived, "loss_per_wavelength");
  ASSERT_TRUE(loss.determined);
  EXPECT_LT(std::abs(std::log(loss.value / 0.16)), 3.0 * loss.log_sigma) << loss.value << " +- " << loss.sigma;
  const bool flagged = std::any_of(r.flags.begin(), r.flags.end(), [](const PlausibilityFlag& f) {
    return f.quantity == "loss_per_wavelength" && f.message.find("too high") != std::string::npos;
  });
  EXPECT_TRUE(flagged) << "0.16 lies above the model's plausible range [1e-3, 1e-2]";
}

}  // namespace
}  // namespace sedwave::inversion
