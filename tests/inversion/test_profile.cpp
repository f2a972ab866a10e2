// Likelihood profiles: which ends the data close and which a search bound does. A toy model whose
// sound speed sees only the ratio x / y (a straight ridge, as a grain contact's kappa d gamma) and
// whose attenuation, where it is observed, sees x alone; its chi^2 is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"

namespace sedwave::inversion {
namespace {

/// speed = 1500 m/s sqrt(x / y), attenuation = 0.1 Np/m x; x and y dimensionless.
class RatioModel final : public sediment::SedimentModel {
 public:
  std::string name() const override { return "ratio"; }
  std::string summary() const override { return "a test model: speed sees x / y, attenuation x"; }
  const std::vector<sediment::Parameter>& parameters() const override { return parameters_; }
  sediment::Wave evaluate(std::span<const double> v, double, bool derivatives) const override {
    sediment::Wave w;
    w.speed = 1500.0 * std::sqrt(v[0] / v[1]);
    w.attenuation = 0.1 * v[0];
    if (derivatives) {
      w.d_speed = {0.5 * w.speed / v[0], -0.5 * w.speed / v[1]};
      w.d_attenuation = {0.1, 0.0};
    }
    return w;
  }

 private:
  std::vector<sediment::Parameter> parameters_{{"x", "1", 1.5, 1e-3, 1e3, true, "test", true},
                                               {"y", "1", 1.5, 1e-3, 1e3, true, "test", true}};
};

/// x and y free from 1.5, x searched over [0.01, 100] and y over [y_lower, y_upper].
FitParameters ratio_parameters(const RatioModel& model, double y_lower, double y_upper) {
  FitParameters p(model.parameters());
  for (ParameterSpec& spec : p.spec) spec.free = true;
  p.spec[0].lower = 0.01;
  p.spec[0].upper = 100.0;
  p.spec[1].lower = y_lower;
  p.spec[1].upper = y_upper;
  return p;
}

Observation row(Quantity quantity, double value, double sigma, const std::string& unit) {
  return {quantity, 1000.0, value, sigma, unit, "test", 1};
}

FitResult fit_from_truth(const ObservationSet& data, const RatioModel& model, const FitParameters& p) {
  return fit(data, model, p, FitOptions{.method = FitMethod::Ceres, .profile_likelihood = true});
}

// Speed alone at 1 %: chi^2 is flat along x = y, and the profile of x follows it until y reaches its
// bound (1 or 2), where chi^2 climbs within a few per cent of x. That closing is the bound's, not the
// data's: both ends of x are open, and x is not determined. y's own ends reach its own bounds.
TEST(Profile, AnEndHeldByAnotherParametersBoundIsOpen) {
  const RatioModel model;
  ObservationSet data;
  data.observations.push_back(row(Quantity::SoundSpeed, 1500.0, 15.0, "m/s"));
  const FitResult r = fit_from_truth(data, model, ratio_parameters(model, 1.0, 2.0));
  const ParameterResult& x = by_name(r.parameters, "x");
  EXPECT_FALSE(x.profile_lower.has_value()) << "closed at " << x.profile_lower.value_or(0.0);
  EXPECT_FALSE(x.profile_upper.has_value()) << "closed at " << x.profile_upper.value_or(0.0);
  EXPECT_FALSE(x.determined);
  const ParameterResult& y = by_name(r.parameters, "y");
  EXPECT_FALSE(y.profile_lower.has_value());
  EXPECT_FALSE(y.profile_upper.has_value());
}

// Attenuation sees x to 1 %, speed the ratio only to 30 %, and y's upper bound 1.51 lies just inside
// x's 68 % interval [1.5 e^-0.01, 1.5 e^0.01]: at x's upper end y sits on its bound, yet lifting it
// would lower chi^2 there by (0.5 ln(1.515 / 1.51) / 0.3)^2 ~ 3e-5 of the 1 that closes it. The data
// close that end; it stays where the closed form puts it.
TEST(Profile, AnEndTheDataCloseStaysClosedWhenABoundIsNear) {
  const RatioModel model;
  ObservationSet data;
  data.observations.push_back(row(Quantity::Attenuation, 0.15, 0.0015, "Np/m"));
  data.observations.push_back(row(Quantity::SoundSpeed, 1500.0, 450.0, "m/s"));
  const double y_upper = 1.51;
  const FitResult r = fit_from_truth(data, model, ratio_parameters(model, 1e-3, y_upper));
  const ParameterResult& x = by_name(r.parameters, "x");
  ASSERT_TRUE(x.profile_lower.has_value());
  ASSERT_TRUE(x.profile_upper.has_value());
  // Attenuation residual (0.1 x - 0.15) / 0.0015 = 1 at x = 1.5 +- 0.015 (the speed term adds < 1e-4).
  EXPECT_NEAR(*x.profile_lower, 1.485, 1e-3);
  EXPECT_NEAR(*x.profile_upper, 1.515, 1e-3);
  EXPECT_GT(*x.profile_upper, y_upper) << "the premise: y is on its bound at x's upper end";
  EXPECT_TRUE(x.determined);
}

}  // namespace
}  // namespace sedwave::inversion
