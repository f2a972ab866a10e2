// The grain-contact family as a sediment model: the SI mapping and its exact gradient.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "sedwave/sediment/grain_contact.hpp"
#include "sediment_test_support.hpp"

namespace sedwave::sediment {
namespace {

using testing::chain;

// At omega_hat -> 0 the chain's speed is its speed scale d sqrt(kappa/m) (c_hat = 1), a closed form
// whose gradient is known: d c / d kappa = c / (2 kappa), d c / d d = -c / (2 d), d c / d rho_s = -c / (2 rho_s).
TEST(GrainContactModel, LowFrequencySpeedIsTheChainSpeedScale) {
  const GrainContactModel model(chain("lattice"), DampingForm::Gamma);
  const std::vector<double> v{1.0e6, 3.0e-4, 1.0, 2650.0};
  const double m = 2650.0 * std::numbers::pi * std::pow(3.0e-4, 3) / 6.0;
  const double c = 3.0e-4 * std::sqrt(1.0e6 / m);
  const Wave w = model.evaluate(v, 1.0, true);
  EXPECT_NEAR(w.speed / c, 1.0, 1e-9);
  EXPECT_NEAR(w.d_speed[0] * 2.0 * v[0] / c, 1.0, 1e-6);
  EXPECT_NEAR(w.d_speed[1] * 2.0 * v[1] / c, -1.0, 1e-6);
  EXPECT_NEAR(w.d_speed[3] * 2.0 * v[3] / c, -1.0, 1e-6);
}

// The gradient against central differences at a dispersive point (omega_hat ~ 0.3, gamma_hat ~ 0.5).
TEST(GrainContactModel, GradientMatchesFiniteDifferences) {
  for (const DampingForm form : {DampingForm::Gamma, DampingForm::Restitution}) {
    const GrainContactModel model(chain("lattice"), form);
    std::vector<double> v{1.0e6, 3.0e-4, form == DampingForm::Gamma ? 1.0 : 0.6, 2650.0};
    const double f = 2.0e5;
    const Wave w = model.evaluate(v, f, true);
    for (int i = 0; i < 4; ++i) {
      const double h = 1e-6 * v[i];
      std::vector<double> up = v, down = v;
      up[i] += h;
      down[i] -= h;
      const Wave a = model.evaluate(up, f, false), b = model.evaluate(down, f, false);
      EXPECT_NEAR(w.d_attenuation[i], (a.attenuation - b.attenuation) / (2 * h), 1e-5 * std::abs(w.attenuation / v[i]))
          << "parameter " << i;
      EXPECT_NEAR(w.d_speed[i], (a.speed - b.speed) / (2 * h), 1e-5 * std::abs(w.speed / v[i])) << "parameter " << i;
    }
  }
}

TEST(GrainContactModel, RefusesValuesOutsideTheirRangeNamingThem) {
  const GrainContactModel model(chain("continuum"), DampingForm::Restitution);
  std::vector<double> v = model.default_values();
  v[GrainContactModel::kDamping] = 1.5;
  try {
    model.check_values(v);
    FAIL() << "e_n = 1.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("e_n = 1.5"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)model.index_of("gamma"), std::invalid_argument);
  EXPECT_EQ(model.index_of("e_n"), GrainContactModel::kDamping);
}

}  // namespace
}  // namespace sedwave::sediment
