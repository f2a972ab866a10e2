// The posterior of a sediment model's parameters (posterior.hpp): where the data determine a
// parameter well the posterior is the Gaussian of the linearised fit; where they leave a direction
// unseen, that parameter's marginal is its prior and the report says so.
#include <gtest/gtest.h>

#include <cmath>

#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::inversion {
namespace {

// EDFM, porosity and permeability from 40 precise observations: the likelihood is nearly Gaussian
// in ln(parameters), so with flat (log-uniform) priors the posterior median is the best fit and its
// 68 % half-width the linearised sigma, to Monte Carlo error (ESS >= 400: ~5 % of a sd).
TEST(Posterior, MatchesTheLinearisedGaussianWhereTheDataDetermineTheParameters) {
  const auto model = sediment::make_sediment_model("edfm");
  FitParameters truth(model->parameters());
  truth.set_free_from_list("porosity,permeability");
  truth.spec[truth.index_of("porosity")].value = 0.42;
  truth.spec[truth.index_of("permeability")].value = 3e-11;
  const ObservationSet data = synthetic_observations(*model, truth, {100.0, 1e5, 20, 0.02, 0.003, 11});
  const FitOptions fit_options{.method = FitMethod::Ceres, .profile_likelihood = false};
  const FitResult best = fit(data, *model, truth, fit_options);
  const PosteriorResult p =
      sample_posterior(data, *model, best, make_priors(best.fitted, {}), fit_options, {.steps = 4000, .seed = 3});
  EXPECT_TRUE(p.converged) << p.advice;
  for (const PosteriorQuantity& q : p.parameters) {
    SCOPED_TRACE(q.name);
    const ParameterResult& r = best.parameters[static_cast<std::size_t>(best.fitted.index_of(q.name))];
    const double half_width = 0.5 * std::log(q.upper_68 / q.lower_68);  // ln units
    EXPECT_NEAR(std::log(q.median / r.value), 0.0, 0.15 * r.log_sigma);
    EXPECT_NEAR(half_width / r.log_sigma, 1.0, 0.15);
    EXPECT_FALSE(q.prior_dominated);
  }
}

// The continuum chain at frequencies far below the crossover sees kappa*d^-1 ... only through c0 and
// tau: d is not informed (its direction kappa*d*gamma is unseen). With a log-normal prior on d, the
// posterior of d is that prior, and the report says so.
TEST(Posterior, AnUnseenParameterFollowsItsPriorAndIsSaidToBePriorDominated) {
  const forward::ContinuumModel continuum;
  const auto frame = grain_contact_model(continuum, DampingForm::Gamma);
  FitParameters truth;
  truth.spec[kKappa].value = 2e6;
  truth.spec[kDiameter].value = 3e-4;
  truth.spec[kDamping].value = 10.0;
  const ObservationSet data = synthetic_observations(*frame, truth, {100.0, 3e4, 15, 0.05, 0.005, 5});
  FitParameters start = truth;
  start.spec[kKappa].lower = 1e4;
  start.spec[kKappa].upper = 1e9;
  start.spec[kDiameter].lower = 1e-5;
  start.spec[kDiameter].upper = 1e-2;
  start.spec[kDamping].lower = 1e-2;
  start.spec[kDamping].upper = 1e4;
  const FitOptions fit_options{.method = FitMethod::Ceres, .profile_likelihood = false};
  const FitResult best = fit(data, *frame, start, fit_options);
  const std::vector<Prior> priors = make_priors(best.fitted, {"d=log-normal:3e-4,0.5"});
  const PosteriorResult p = sample_posterior(data, *frame, best, priors, fit_options, {.steps = 3000, .seed = 7});
  const PosteriorQuantity& d = p.parameters[kDiameter];
  EXPECT_TRUE(d.prior_dominated);
  // The prior's median 3e-4 m and 68 % half-width 0.5 in ln, to Monte Carlo error.
  EXPECT_NEAR(std::log(d.median / 3e-4), 0.0, 0.15);
  EXPECT_NEAR(0.5 * std::log(d.upper_68 / d.lower_68), 0.5, 0.1);
  // c0 and tau stay determined: their posteriors are narrow whatever d does.
  for (const PosteriorQuantity& c : p.combinations) {
    if (c.name == "c0" || c.name == "tau") {
      EXPECT_LT(std::log(c.upper_68 / c.lower_68), 0.2) << c.name;
    }
  }
}

}  // namespace
}  // namespace sedwave::inversion
