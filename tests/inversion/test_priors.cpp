// Priors in theta = ln(value): each is a normalised density over the search bounds (the sampler
// and a log evidence rely on it), has the shape its name says, and bad specifications are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sedwave/inversion/priors.hpp"

namespace sedwave::inversion {
namespace {

ParameterSpec kappa_spec() { return {"kappa", "N/m", 1e5, 1e3, 1e7, true}; }

/// Integral of exp(ln p(theta)) over [ln lower, ln upper] by the midpoint rule (the densities are
/// smooth inside and cut at the support's ends, which 2e5 cells resolve to 1e-5).
double total_mass(const Prior& p) {
  const double lo = std::log(p.lower), hi = std::log(p.upper);
  const int n = 200000;
  const double h = (hi - lo) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += std::exp(p.log_density_theta(lo + (i + 0.5) * h));
  return sum * h;
}

TEST(Priors, EveryKindIsNormalisedOverTheSearchBounds) {
  const ParameterSpec s = kappa_spec();
  for (const char* text : {"uniform:2e3,5e6", "log-uniform:1e4,1e6", "normal:1e5,3e4", "log-normal:8e4,0.5",
                           "log-normal:2e3,1.5"}) {
    SCOPED_TRACE(text);
    EXPECT_NEAR(total_mass(parse_prior(text, s)), 1.0, 1e-4);
  }
  EXPECT_NEAR(total_mass(default_prior(s)), 1.0, 1e-4);
}

TEST(Priors, ShapesAreWhatTheirNamesSay) {
  const ParameterSpec s = kappa_spec();
  // log-uniform: the same density at every theta inside, zero outside.
  const Prior lu = parse_prior("log-uniform:1e4,1e6", s);
  EXPECT_DOUBLE_EQ(lu.log_density_theta(std::log(2e4)), lu.log_density_theta(std::log(5e5)));
  EXPECT_EQ(lu.log_density_theta(std::log(5e3)), -INFINITY);
  // uniform in the value: p(theta) grows as e^theta.
  const Prior u = parse_prior("uniform:2e3,5e6", s);
  EXPECT_NEAR(u.log_density_theta(std::log(2e6)) - u.log_density_theta(std::log(1e6)), std::log(2.0), 1e-12);
  // log-normal: symmetric in ln about the median, one sd down by 1/2 in ln p.
  const Prior ln = parse_prior("log-normal:8e4,0.5", s);
  const double t0 = std::log(8e4);
  EXPECT_NEAR(ln.log_density_theta(t0 + 0.3), ln.log_density_theta(t0 - 0.3), 1e-12);
  EXPECT_NEAR(ln.log_density_theta(t0) - ln.log_density_theta(t0 + 0.5), 0.5, 1e-12);
}

TEST(Priors, BadSpecificationsAreRefusedWithTheAcceptedForms) {
  const ParameterSpec s = kappa_spec();
  const auto refuses = [&](const std::string& text, const std::string& words) {
    try {
      (void)parse_prior(text, s);
      ADD_FAILURE() << text << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refuses("gauss:1,2", "unknown kind 'gauss' (accepted: uniform:A,B");
  refuses("uniform:5,1", "needs A < B");
  refuses("normal:1e5,-1", "sd must be positive");
  refuses("uniform:1e8,1e9", "does not meet the search bounds");
  refuses("log-normal:1e5,abc", "'abc' is not a finite number");
  refuses("normal", "expected KIND:A,B");
  FitParameters p;  // kappa, d, gamma free; rho_s fixed
  EXPECT_THROW((void)make_priors(p, {"rho_s=normal:2650,50"}), std::invalid_argument);
  EXPECT_THROW((void)make_priors(p, {"kappa=log-normal:1e5,1", "kappa=log-normal:1e5,2"}), std::invalid_argument);
  EXPECT_THROW((void)make_priors(p, {"porosity=uniform:0.3,0.5"}), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::inversion
