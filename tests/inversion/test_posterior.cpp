// The posterior of a sediment model's parameters (posterior.hpp): where the data determine a
// parameter well the posterior is the Gaussian of the linearised fit; where they leave a direction
// unseen, that parameter's marginal is its prior and the report says so.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/predictive.hpp"
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

// The stop test judges the model's derived quantities beside its parameters: a converged run has
// every derived quantity that moves with the free parameters as well mixed as they are (kept steps
// >= 50 tau, i.e. ESS >= 50 walkers, and ESS >= 400; R-hat < 1.05). On the shipped field data with
// the lattice chain and a grain-size prior, tau = gamma / kappa mixes more slowly than kappa, d and
// gamma: judged on the parameters alone the run stopped after 750 steps with tau's ESS at 533.
// A derived quantity that the free parameters do not move (the saturated lattice's Wood speed, set
// by the fixed porosity: a constant, with no R-hat) does not hold a run back. One ensemble: the
// saturated chain's kappa and gamma are left to their flat priors, which makes its default run
// tempered, and the same judging in a tempered run costs 20 times more here.
TEST(Posterior, JudgesTheDerivedQuantitiesThatMoveAndNotTheConstantOnes) {
  const ObservationSet field = read_observation_csv(SEDWAVE_SOURCE_DIR "/data/field/zhou2009_regression.csv");
  for (const char* name : {"lattice", "saturated-lattice"}) {
    SCOPED_TRACE(name);
    const auto model = sediment::make_sediment_model(name);
    FitParameters start(model->parameters());
    start.set_free_from_list("kappa,d,gamma");
    start.spec[start.index_of("kappa")].value = 1e6;
    start.spec[start.index_of("gamma")].value = 5.0;
    const FitOptions fit_options{.method = FitMethod::Ceres, .profile_likelihood = false};
    const FitResult best = fit(field, *model, start, fit_options);
    const PosteriorResult p = sample_posterior(field, *model, best, make_priors(best.fitted, {"d=log-normal:3e-4,0.3"}),
                                               fit_options, {.seed = 1, .temperatures = 0});
    ASSERT_TRUE(p.converged) << p.advice;
    int moving = 0;
    for (const PosteriorQuantity& q : p.derived) {
      SCOPED_TRACE(q.name);
      if (q.lower_95 == q.upper_95) {
        EXPECT_EQ(std::string(name), "saturated-lattice");  // only its Wood speed is fixed
        continue;
      }
      ++moving;
      EXPECT_GE(q.effective_samples, std::max(400.0, 50.0 * p.walkers)) << "after " << p.steps << " steps";
      EXPECT_LT(q.split_rhat, 1.05);
    }
    EXPECT_GE(moving, 4);  // c0 or the Biot frequency, tau, f_star, gamma_hat, kappa_over_hertz
  }
}

/// A sand's contact: kappa 2e6 N/m, d 0.3 mm, gamma 10 kg/s (f* ~ 32 kHz).
FitParameters sand_contact() {
  FitParameters p;
  p.spec[p.index_of("kappa")].value = 2e6;
  p.spec[p.index_of("d")].value = 3e-4;
  p.spec[p.index_of("gamma")].value = 10.0;
  return p;
}

// The continuum chain at frequencies far below the crossover sees kappa*d^-1 ... only through c0 and
// tau: d is not informed (its direction kappa*d*gamma is unseen). With a log-normal prior on d, the
// posterior of d is that prior, and the report says so. One ensemble (the prior on d closes the
// ridge, but only just at kappa's linearised sd of 0.5, which by default would make the run
// tempered; the tempered sampler is checked against a closed form below).
TEST(Posterior, AnUnseenParameterFollowsItsPriorAndIsSaidToBePriorDominated) {
  const forward::ContinuumModel continuum;
  const auto frame = grain_contact_model(continuum, DampingForm::Gamma);
  FitParameters truth = sand_contact();
  const ObservationSet data = synthetic_observations(*frame, truth, {100.0, 3e4, 15, 0.05, 0.005, 5});
  FitParameters start = truth;
  start.spec[start.index_of("kappa")].lower = 1e4;
  start.spec[start.index_of("kappa")].upper = 1e9;
  start.spec[start.index_of("d")].lower = 1e-5;
  start.spec[start.index_of("d")].upper = 1e-2;
  start.spec[start.index_of("gamma")].lower = 1e-2;
  start.spec[start.index_of("gamma")].upper = 1e4;
  const FitOptions fit_options{.method = FitMethod::Ceres, .profile_likelihood = false};
  const FitResult best = fit(data, *frame, start, fit_options);
  const std::vector<Prior> priors = make_priors(best.fitted, {"d=log-normal:3e-4,0.5"});
  const PosteriorResult p = sample_posterior(data, *frame, best, priors, fit_options,
                                             {.steps = 3000, .seed = 7, .temperatures = 0});
  const PosteriorQuantity& d = by_name(p.parameters, "d");
  EXPECT_TRUE(d.prior_dominated);
  // The prior's median 3e-4 m and 68 % half-width 0.5 in ln, to Monte Carlo error.
  EXPECT_NEAR(std::log(d.median / 3e-4), 0.0, 0.15);
  EXPECT_NEAR(0.5 * std::log(d.upper_68 / d.lower_68), 0.5, 0.1);
  // c0 and tau stay determined: their posteriors are narrow whatever d does.
  for (const PosteriorQuantity& c : p.derived) {
    if (c.name == "c0" || c.name == "tau") {
      EXPECT_LT(std::log(c.upper_68 / c.lower_68), 0.2) << c.name;
    }
  }
}

// Where the fit leaves a direction to the prior, the posterior is sampled by parallel tempering, and
// it follows that direction to the prior's bounds. The continuum chain far below its crossover sees
// only c0 ~ sqrt(kappa / d) and tau = gamma / kappa, so along kappa ~ d, gamma ~ d (in ln: (1, 1, 1))
// the likelihood is flat; with log-uniform priors whose bounds on kappa and gamma lie beyond the
// ridge's ends, the marginal of ln d is its prior's: uniform on [ln 3e-5, ln 1e-3] (closed form). Where
// the data determine every parameter (the first test's EDFM set) one ensemble runs, and where a
// log-normal prior on d (sd of ln 0.3) closes the same ridge too.
TEST(Posterior, IsTemperedWhereTheFitLeavesADirectionOpenAndFollowsItToThePriorsBounds) {
  const forward::ContinuumModel continuum;
  const auto frame = grain_contact_model(continuum, DampingForm::Gamma);
  const FitParameters truth = sand_contact();
  const ObservationSet data = synthetic_observations(*frame, truth, {100.0, 1e3, 12, 0.05, 0.005, 5});
  FitParameters start = truth;
  const auto bound = [&](const char* name, double lower, double upper) {
    start.spec[start.index_of(name)].lower = lower;
    start.spec[start.index_of(name)].upper = upper;
  };
  bound("kappa", 1e4, 1e9);
  bound("d", 3e-5, 1e-3);
  bound("gamma", 1e-2, 1e4);
  const FitOptions fit_options{.method = FitMethod::Ceres, .profile_likelihood = false};
  const FitResult best = fit(data, *frame, start, fit_options);
  const std::vector<Prior> priors = make_priors(best.fitted, {});
  // The premise of the closed form: ln L is flat along (1, 1, 1) out to d's bounds.
  const sampling::PriorAndLikelihood density = evidence_integrand(data, *frame, best, priors, fit_options);
  const std::vector<double> ln_best = best.fitted.log_values();
  const std::vector<int> free = best.fitted.free_indices();  // kappa, d, gamma
  const Eigen::Vector3d at_best(ln_best[free[0]], ln_best[free[1]], ln_best[free[2]]);
  const double ln_d = at_best(1);
  for (const double end : {std::log(3e-5), std::log(1e-3)}) {
    EXPECT_NEAR(density.log_likelihood(at_best + Eigen::Vector3d::Constant(end - ln_d)),
                density.log_likelihood(at_best), 0.05);
  }
  const PosteriorResult p = sample_posterior(data, *frame, best, priors, fit_options, {.seed = 7});
  ASSERT_TRUE(p.converged) << p.advice;
  EXPECT_GE(p.temperatures, PosteriorOptions::kAutoTemperatures);
  const PosteriorQuantity& d = by_name(p.parameters, "d");
  const double lo = std::log(3e-5), width = std::log(1e-3 / 3e-5);
  // Quantiles of a uniform, to Monte Carlo error (ESS >= 400: sd of the 2.5 % point ~0.03 width).
  EXPECT_NEAR(std::log(d.lower_95), lo + 0.025 * width, 0.1 * width);
  EXPECT_NEAR(std::log(d.median), lo + 0.5 * width, 0.1 * width);
  EXPECT_NEAR(std::log(d.upper_95), lo + 0.975 * width, 0.1 * width);
  EXPECT_TRUE(d.prior_dominated);
  const std::vector<Prior> closing = make_priors(best.fitted, {"d=log-normal:3e-4,0.3"});
  const PosteriorResult closed =
      sample_posterior(data, *frame, best, closing, fit_options, {.steps = 250, .check_every = 0});
  EXPECT_EQ(closed.temperatures, 0);

  const auto edfm = sediment::make_sediment_model("edfm");
  FitParameters determined(edfm->parameters());
  determined.set_free_from_list("porosity,permeability");
  const ObservationSet edfm_data = synthetic_observations(*edfm, determined, {100.0, 1e5, 20, 0.02, 0.003, 11});
  const FitResult edfm_best = fit(edfm_data, *edfm, determined, fit_options);
  const PosteriorResult one = sample_posterior(edfm_data, *edfm, edfm_best, make_priors(edfm_best.fitted, {}),
                                               fit_options, {.steps = 4000, .seed = 3});
  EXPECT_EQ(one.temperatures, 0);
}

// A fit that ends on a search bound (here d, which these data do not see) is a valid start for the
// posterior: the value on the bound lies inside the bounds and inside the default prior.
TEST(Posterior, StartsFromAFitOnASearchBound) {
  const forward::LatticeModel lattice;
  const auto frame = grain_contact_model(lattice, DampingForm::Gamma);
  FitParameters truth = sand_contact();
  truth.spec[truth.index_of("kappa")].value = 9e5;
  truth.spec[truth.index_of("gamma")].value = 5.0;
  const ObservationSet data = synthetic_observations(*frame, truth, {1e4, 1e6, 15, 0.1, 0.01, 2});
  FitParameters start = truth;
  start.spec[start.index_of("kappa")].value = 1e6;
  start.spec[start.index_of("gamma")].value = 1.0;
  start.spec[start.index_of("d")].lower = 1e-5;
  start.spec[start.index_of("d")].upper = 1e-2;
  const FitOptions options{.method = FitMethod::Global, .profile_likelihood = false};
  const FitResult best = fit(data, *frame, start, options);
  ASSERT_TRUE(by_name(best.parameters, "d").at_bound) << "the premise: d ends on a bound";
  PosteriorResult p;
  EXPECT_NO_THROW(p = sample_posterior(data, *frame, best, make_priors(best.fitted, {}), options, {.steps = 200}));
  EXPECT_GT(p.samples.rows(), 0);
}

// A quantile commutes with a monotone map: where the model's speed and attenuation move one way with
// the one free parameter, the band's median is the model at the parameter's median. The continuum
// chain's speed c0 = d sqrt(kappa / m) rises with kappa, and below the crossover its attenuation
// (~ omega^2 gamma d / (2 m c0^3)) falls with it.
TEST(PredictiveBand, QuantilesAreTheModelAtTheParameterQuantilesForAMonotoneModel) {
  const forward::ContinuumModel continuum;
  const auto frame = grain_contact_model(continuum, DampingForm::Gamma);
  FitParameters truth = sand_contact();
  truth.set_free_from_list("kappa");
  const ObservationSet data = synthetic_observations(*frame, truth, {100.0, 3e4, 8, 0.05, 0.005, 5});
  const FitResult best = fit(data, *frame, truth, {.method = FitMethod::Ceres, .profile_likelihood = false});
  // 401 log-normal draws of kappa: the median is one of them exactly.
  std::mt19937_64 random(5);
  std::normal_distribution<double> normal(0.0, 0.2);
  Eigen::MatrixXd draws(401, 1);
  for (Eigen::Index i = 0; i < draws.rows(); ++i) draws(i, 0) = 2e6 * std::exp(normal(random));
  const std::vector<double> frequencies{200.0, 2000.0};
  const PredictiveBand band = predictive_band("continuum", *frame, best, draws, frequencies, 1000);
  ASSERT_EQ(band.frequency_hz.size(), 2u);
  EXPECT_EQ(band.draws, 401);
  std::vector<double> kappas(draws.data(), draws.data() + draws.size());
  std::sort(kappas.begin(), kappas.end());
  std::vector<double> values = best.fitted.values();
  values[static_cast<std::size_t>(best.fitted.index_of("kappa"))] = kappas[200];
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const sediment::Wave at_median = frame->evaluate(values, frequencies[i], false);
    EXPECT_NEAR(band.speed[i][2] / at_median.speed, 1.0, 1e-12);
    EXPECT_NEAR(band.attenuation[i][2] / at_median.attenuation, 1.0, 1e-12);
    // Ordered quantiles, and a band as wide as the draws make it (c0 ~ sqrt(kappa): ~0.1 in ln at 68 %).
    for (std::size_t q = 1; q < kBandQuantiles.size(); ++q) EXPECT_LT(band.speed[i][q - 1], band.speed[i][q]);
    EXPECT_NEAR(std::log(band.speed[i][3] / band.speed[i][1]), 0.2, 0.04);
  }
  ASSERT_EQ(band.residual.size(), best.residuals.size());
  for (std::size_t r = 0; r < band.residual.size(); ++r) {
    const PointResidual& p = best.residuals[r];
    const sediment::Wave w = frame->evaluate(values, p.observation.frequency_hz, false);
    const double median = p.observation.quantity == Quantity::Attenuation ? w.attenuation : w.speed;
    EXPECT_NEAR(band.residual[r], (p.observation.value - median) / p.sigma, 1e-9);
  }
}

// The samples' HDF5 file: one dataset per free parameter of shape {walkers, kept steps}, walker w's
// chain in row w, with its unit.
TEST(PosteriorSamplesFile, HoldsEachWalkersChainWithItsUnit) {
  PosteriorResult p;
  p.walkers = 4;
  p.steps = 6;
  p.sample_names = {"kappa", "d"};
  p.sample_units = {"N/m", "m"};
  p.samples.resize(12, 2);  // 4 walkers x 3 kept steps, walker-major as pooled_samples makes it
  for (Eigen::Index r = 0; r < 12; ++r) p.samples.row(r) << 1e6 + static_cast<double>(r), 1e-4 * static_cast<double>(r + 1);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "sedwave_test_samples.h5";
  write_posterior_samples_hdf5(path, p);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t set = H5Dopen2(file, "kappa", H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  hsize_t dims[2] = {0, 0};
  ASSERT_EQ(H5Sget_simple_extent_ndims(space), 2);
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], 4u);
  EXPECT_EQ(dims[1], 3u);
  std::vector<double> values(12);
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  EXPECT_EQ(values[3 * 2 + 1], p.samples(7, 0));  // walker 2, kept step 1
  const hid_t attribute = H5Aopen(set, "unit", H5P_DEFAULT);
  const hid_t type = H5Aget_type(attribute);
  std::string unit(H5Tget_size(type), '\0');
  H5Aread(attribute, type, unit.data());
  EXPECT_EQ(unit.substr(0, 3), "N/m");
  H5Tclose(type);
  H5Aclose(attribute);
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sedwave::inversion
