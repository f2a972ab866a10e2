// Synthetic inversions: data generated from known parameters are recovered within their stated
// uncertainties, and what the data cannot determine is reported as such.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/table_model.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/identifiability.hpp"
#include "sedwave/inversion/residuals.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::inversion {
namespace {

// A sand-like contact whose lattice dispersion reaches kd ~ 1 at 1 MHz: c0 ~ 1.7 km/s,
// f* = 20 kHz, gamma_hat ~ 48 (overdamped contacts, as real sediments need).
constexpr double kKappaTrue = 1.0e6;   // N/m
constexpr double kDiameterTrue = 2.7e-4;  // m
constexpr double kGammaTrue = 7.96;    // kg/s

FitParameters true_parameters() {
  FitParameters p;
  p.spec[p.index_of("kappa")].value = kKappaTrue;
  p.spec[p.index_of("d")].value = kDiameterTrue;
  p.spec[p.index_of("gamma")].value = kGammaTrue;
  return p;
}

/// Attenuation and sound speed at 25 log-spaced frequencies each from 10 Hz to 1 MHz, with 5%
/// Gaussian noise and sigma = 5% of the noise-free value.
ObservationSet synthetic_data(const forward::DispersionModel& model, const FitParameters& p, unsigned seed) {
  return synthetic_observations(model, p, SyntheticDesign{.seed = seed});
}

const DerivedResult& derived(const FitResult& r, const std::string& name) {
  for (const DerivedResult& c : r.derived) {
    if (c.name == name) return c;
  }
  throw std::runtime_error("no combination " + name);
}

void expect_within_3_sigma(const FitResult& r, const std::string& name, double truth) {
  const DerivedResult& c = derived(r, name);
  ASSERT_TRUE(c.determined) << name;
  EXPECT_LT(std::abs(std::log(c.value / truth)), 3.0 * c.log_sigma)
      << name << " = " << c.value << " +- " << c.sigma << ", truth " << truth;
}

TEST(SyntheticInversion, LatticeRecoversDeterminedCombinations) {
  // Several noise realisations, so a pass is not the luck of one seed.
  const forward::LatticeModel lattice;
  const forward::GrainScales<double> truth{kKappaTrue, kDiameterTrue, 2650.0};
  int claimed_diameter = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ObservationSet data = synthetic_data(lattice, true_parameters(), seed);
    FitParameters start = true_parameters();
    start.spec[start.index_of("kappa")].value = 3.0e6;
    start.spec[start.index_of("d")].value = 1.0e-4;
    start.spec[start.index_of("gamma")].value = 20.0;
    const FitResult r = fit(data, lattice, start, FitOptions{.method = FitMethod::Global});
    EXPECT_TRUE(r.converged) << r.solver_message;
    expect_within_3_sigma(r, "c0", truth.speed_scale());
    expect_within_3_sigma(r, "tau", kGammaTrue / kKappaTrue);
    expect_within_3_sigma(r, "f_star", kKappaTrue / (2.0 * std::numbers::pi * kGammaTrue));
    // 50 points with 5% noise: chi2 within loose 99.9% bounds for ~47 dof.
    EXPECT_GT(r.chi2, 20.0);
    EXPECT_LT(r.chi2, 85.0);
    claimed_diameter += by_name(r.parameters, "d").determined ? 1 : 0;
  }
  // With gamma_hat ~ 48 the sound speed rises so fast that kd stays below 0.15 even at 1 MHz: the
  // lattice correction (~(kd)^2/24) is below the noise and d is normally not determined. Noise can
  // fake the correction, though (seed 4 prefers d ~ 8x too large by Delta chi^2 ~ 10, with both
  // profile sides closed); docs/inversion.md discusses this. Demand it stays the exception.
  EXPECT_LE(claimed_diameter, 1);
}

// kappa_over_hertz compares kappa with the Hertz stiffness the site inputs use for their kappa prior:
// kappa_H = (6 E*^2 R F)^(1/3), E* = E / (2 (1 - nu^2)), R = d/4 (Johnson 1985, ch. 4), at the mean
// contact force F = pi d^2 P / (Z (1 - beta)) of a dense random quartz pack (Digby 1981; Z = 9,
// beta = 0.38) at P = 10 kPa. One relation for both, so a kappa at its site prior reads as 1.
TEST(SyntheticInversion, KappaOverHertzIsTheSitePriorsHertzRelation) {
  const forward::LatticeModel lattice;
  const FitResult r = fit(synthetic_data(lattice, true_parameters(), 1), lattice, true_parameters(),
                          FitOptions{.method = FitMethod::Ceres, .profile_likelihood = false});
  const double d = by_name(r.parameters, "d").value;
  const double young = 9.45e10, poisson = 0.074;  // quartz (Mavko et al. 2009, table 7.1)
  const double e_star = young / (2.0 * (1.0 - poisson * poisson));
  const double force = std::numbers::pi * d * d * 1.0e4 / (9.0 * (1.0 - 0.38));
  const double hertz = std::cbrt(6.0 * e_star * e_star * (d / 4.0) * force);
  EXPECT_NEAR(derived(r, "kappa_over_hertz").value / (by_name(r.parameters, "kappa").value / hertz), 1.0, 1e-9);
}

TEST(SyntheticInversion, LatticeDeterminesDiameterWhenKdReachesOne) {
  // A weakly damped contact (gamma_hat = 0.05) keeps c ~ c0, so 1 MHz reaches kd ~ 1 and the
  // lattice's dispersion reveals d itself.
  const forward::LatticeModel lattice;
  FitParameters truth = true_parameters();
  const forward::GrainScales<double> scales{kKappaTrue, kDiameterTrue, 2650.0};
  truth.spec[truth.index_of("gamma")].value = scales.gamma(0.05);
  const ObservationSet data = synthetic_data(lattice, truth, 1);
  FitParameters start = truth;
  start.spec[start.index_of("kappa")].value = 3.0e6;
  start.spec[start.index_of("d")].value = 1.0e-4;
  const FitResult r = fit(data, lattice, start, FitOptions{.method = FitMethod::Global});
  EXPECT_EQ(r.rank, 3);
  const ParameterResult& d = by_name(r.parameters, "d");
  ASSERT_TRUE(d.determined);
  EXPECT_LT(std::abs(std::log(d.value / kDiameterTrue)), 3.0 * d.log_sigma);
  expect_within_3_sigma(r, "gamma_hat", 0.05);
}

TEST(SyntheticInversion, ContinuumFlagsDiameterAsNotDetermined) {
  const forward::LatticeModel lattice;
  const forward::ContinuumModel continuum;
  const ObservationSet data = synthetic_data(lattice, true_parameters(), 42);
  const FitResult r = fit(data, continuum, true_parameters(), FitOptions{.method = FitMethod::Global});
  EXPECT_EQ(r.rank, 2);  // only c0 and tau are visible to the continuum chain
  EXPECT_FALSE(by_name(r.parameters, "d").determined);
  EXPECT_FALSE(by_name(r.parameters, "kappa").determined);
  EXPECT_FALSE(by_name(r.parameters, "gamma").determined);
  EXPECT_TRUE(derived(r, "c0").determined);
  EXPECT_TRUE(derived(r, "tau").determined);
  EXPECT_TRUE(derived(r, "f_star").determined);
  EXPECT_FALSE(derived(r, "gamma_hat").determined);
  ASSERT_EQ(r.weak_directions.size(), 1u);
  EXPECT_TRUE(r.weak_directions[0].unseen);
  EXPECT_EQ(r.weak_directions[0].direction, "kappa^1 * d^1 * gamma^1");
}

// The shipped driven table of five N = 10^4 packings (docs/inversion.md, "Does a 3D table determine
// d?"). Sand-like truth: kappa from the field fit, d = 0.3 mm; a lab band over omega_hat = 0.1-0.6
// (137-826 kHz), sound speed to 1 %, attenuation to 10 %. Data and fit share the table, so this
// tests what the model can resolve, not the table's own error (the docs cross-check on disjoint
// packings).
struct DrivenTableCase {
  forward::table::TableModel table{forward::table::read_table(SEDWAVE_SOURCE_DIR "/data/tables/field_w3_driven.h5"),
                                   "table"};
  forward::GrainScales<double> scales{2.8e6, 3.0e-4, 2650.0};

  FitParameters truth(double gamma_hat) const {
    FitParameters p;
    p.spec[p.index_of("kappa")].value = scales.kappa;
    p.spec[p.index_of("d")].value = scales.diameter;
    p.spec[p.index_of("gamma")].value = scales.gamma(gamma_hat);
    return p;
  }
  SyntheticDesign lab_band(unsigned seed) const {
    const double to_hz = 1.0 / (2.0 * std::numbers::pi * scales.time_scale());
    return {0.1 * to_hz, 0.6 * to_hz, 12, 0.1, 0.01, seed};
  }
  /// A local fit of kappa, d, gamma from a start 10-20 % off the truth (the table has no value far
  /// outside, so a global search over the default bounds would see little of it).
  FitResult fit_table(const ObservationSet& data, const FitParameters& truth) const {
    FitParameters start = truth;
    start.spec[start.index_of("kappa")].value *= 0.9;
    start.spec[start.index_of("d")].value *= 0.9;
    start.spec[start.index_of("gamma")].value *= 1.2;
    return fit(data, table, start, FitOptions{.method = FitMethod::Ceres});
  }
};

// A table's sigma enters the fit as model uncertainty; one that leaves out packing-to-packing
// variation (a table of one packing) makes every interval too narrow, and the fit must say so.
TEST(SyntheticInversion, OnePackingTableIsFlagged) {
  const DrivenTableCase c;
  const FitParameters truth = c.truth(10.0);
  const ObservationSet data = synthetic_observations(c.table, truth, c.lab_band(1));
  const auto model_flags = [](const FitResult& r) {
    return std::count_if(r.flags.begin(), r.flags.end(), [](const PlausibilityFlag& f) { return f.quantity == "model"; });
  };
  EXPECT_EQ(model_flags(c.fit_table(data, truth)), 0) << "an ensemble of 5 packings is flagged";

  const forward::table::DispersionTable& ensemble = c.table.table();
  forward::table::TableMetadata one = ensemble.metadata();
  ASSERT_EQ(one.packings, 5);
  one.packings = 1;
  forward::table::DispersionTable single(ensemble.grid(), one);
  for (std::size_t g = 0; g < ensemble.n_gamma(); ++g)
    for (std::size_t w = 0; w < ensemble.n_omega(); ++w) single.set(g, w, ensemble.at(g, w));
  const forward::table::TableModel one_packing{std::move(single), "one"};
  FitParameters start = truth;
  start.spec[start.index_of("kappa")].value *= 0.9;
  const FitResult r = fit(data, one_packing, start, FitOptions{.method = FitMethod::Ceres, .profile_likelihood = false});
  ASSERT_EQ(model_flags(r), 1);
  const auto flag = std::find_if(r.flags.begin(), r.flags.end(), [](const PlausibilityFlag& f) { return f.quantity == "model"; });
  EXPECT_NE(flag->message.find("one packing"), std::string::npos) << flag->message;
}

TEST(SyntheticInversion, DrivenTableDeterminesDiameterTheContinuumCannot) {
  // gamma_hat = 10, the overdamped contacts of real sand: the 3D dispersion at 5-60 grains per
  // wavelength depends on omega_hat and gamma_hat apart, not on their product alone.
  const DrivenTableCase c;
  const forward::ContinuumModel continuum;
  const FitParameters truth = c.truth(10.0);
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ObservationSet data = synthetic_observations(c.table, truth, c.lab_band(seed));
    const FitResult r = c.fit_table(data, truth);
    const ParameterResult& d = by_name(r.parameters, "d");
    ASSERT_TRUE(d.determined) << d.value << " +- " << d.sigma;
    EXPECT_LT(d.log_sigma, 0.3);
    EXPECT_LT(std::abs(std::log(d.value / c.scales.diameter)), 3.0 * d.log_sigma) << d.value << " +- " << d.sigma;
    EXPECT_LT(r.chi2, 45.0);  // 24 observations, 3 parameters: a loose 99.9 % bound
    const FitResult k = fit(data, continuum, truth, FitOptions{.method = FitMethod::Global});
    EXPECT_EQ(k.rank, 2);
    EXPECT_FALSE(by_name(k.parameters, "d").determined);
    EXPECT_GT(k.chi2, r.chi2 + 9.0) << "the continuum should fit the 3D shape worse";
  }
}

TEST(SyntheticInversion, LatticeFitOf3DDataFindsADiameterTooLarge) {
  // The same data fitted with the 1D lattice: its dispersion (kd ~ 1) mimics the 3D one with a
  // lattice spacing about three grains long, and fits as well (chi2 within a few). So d is
  // determined only relative to a model; docs/inversion.md.
  const DrivenTableCase c;
  const forward::LatticeModel lattice;
  const FitParameters truth = c.truth(10.0);
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ObservationSet data = synthetic_observations(c.table, truth, c.lab_band(seed));
    const FitResult l = fit(data, lattice, truth, FitOptions{.method = FitMethod::Global});
    const ParameterResult& d = by_name(l.parameters, "d");
    ASSERT_TRUE(d.determined);
    EXPECT_GT(d.value, 2.0 * c.scales.diameter);
    EXPECT_LT(l.chi2, 45.0);
  }
}

TEST(SyntheticInversion, DrivenTableCannotDetermineDiameterOfStronglyOverdampedContacts) {
  // gamma_hat = 50 over the same band: omega_hat * gamma_hat = 5-30, where the 3D dispersion is
  // again a function of the product alone within these errors, and d drops out.
  const DrivenTableCase c;
  const FitParameters truth = c.truth(50.0);
  int claimed = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    const FitResult r = c.fit_table(synthetic_observations(c.table, truth, c.lab_band(seed)), truth);
    claimed += by_name(r.parameters, "d").determined ? 1 : 0;
  }
  EXPECT_LE(claimed, 1);
}

TEST(SyntheticInversion, GlobalMethodConvergesFromBadlyScaledStart) {
  const forward::LatticeModel lattice;
  const ObservationSet data = synthetic_data(lattice, true_parameters(), 7);
  FitParameters start = true_parameters();
  start.spec[start.index_of("kappa")].value = kKappaTrue * 1e4;
  start.spec[start.index_of("d")].value = kDiameterTrue * 1e-4;
  start.spec[start.index_of("gamma")].value = kGammaTrue * 1e4;
  const FitResult global = fit(data, lattice, start, FitOptions{.method = FitMethod::Global});
  const FitResult reference = fit(data, lattice, true_parameters(), FitOptions{.method = FitMethod::Ceres});
  EXPECT_NEAR(global.chi2, reference.chi2, 1e-6 * reference.chi2);
  const forward::GrainScales<double> truth{kKappaTrue, kDiameterTrue, 2650.0};
  expect_within_3_sigma(global, "c0", truth.speed_scale());
  expect_within_3_sigma(global, "tau", kGammaTrue / kKappaTrue);
}

TEST(SyntheticInversion, RestitutionParameterisation) {
  // e_n maps to gamma_hat = sqrt(2) zeta(e_n) <= sqrt(2): a weakly damped chain.
  const forward::LatticeModel lattice;
  FitParameters truth = true_parameters();
  truth.set_damping_form(DampingForm::Restitution);
  truth.spec[truth.index_of("e_n")].value = 0.5;
  const ObservationSet data = synthetic_data(lattice, truth, 3);
  FitParameters start = truth;
  start.set_free_from_list("kappa,en");
  start.spec[start.index_of("e_n")].value = 0.9;
  start.spec[start.index_of("kappa")].value = 3e5;
  const FitResult r = fit(data, lattice, start, FitOptions{.method = FitMethod::Global});
  const ParameterResult& e = by_name(r.parameters, "e_n");
  EXPECT_EQ(e.name, "e_n");
  ASSERT_TRUE(e.determined);
  EXPECT_LT(std::abs(std::log(e.value / 0.5)), 3.0 * e.log_sigma);
  EXPECT_TRUE(by_name(r.parameters, "d").determined);  // fixed: known exactly
  EXPECT_FALSE(by_name(r.parameters, "d").free);
}

TEST(SyntheticInversion, CeresAndNloptMethodsReachTheSameMinimum) {
  const forward::ContinuumModel continuum;
  FitParameters p = true_parameters();
  p.set_free_from_list("kappa,gamma");
  const ObservationSet data = synthetic_data(continuum, p, 11);
  const FitResult local = fit(data, continuum, p, FitOptions{.method = FitMethod::Ceres});
  const FitResult search = fit(data, continuum, p, FitOptions{.method = FitMethod::NLopt});
  EXPECT_TRUE(local.converged);
  EXPECT_NEAR(search.chi2 / local.chi2, 1.0, 1e-2);  // DIRECT-L alone is only approximate
  ASSERT_TRUE(search.global.has_value());
}

TEST(Identifiability, NullSpaceOfAKnownJacobian) {
  // Residuals depend on x0 - x1 and x2 only: the direction (1, 1, 0) is unseen.
  Eigen::MatrixXd J(4, 3);
  J << 1, -1, 0, 2, -2, 1, 0, 0, 3, -1, 1, 1;
  const JacobianAnalysis a = analyze_jacobian(J);
  EXPECT_EQ(a.rank, 2);
  const Eigen::MatrixXd cov = (J.transpose() * J).completeOrthogonalDecomposition().pseudoInverse();
  Eigen::Vector3d difference(1, -1, 0), sum(1, 1, 0);
  EXPECT_TRUE(determine(difference, a, cov, 10.0).determined);
  EXPECT_FALSE(determine(sum, a, cov, 10.0).determined);
  EXPECT_EQ(describe_direction(a.null_space.col(0), {"a", "b", "c"}), "a^1 * b^1");
}

}  // namespace
}  // namespace sedwave::inversion
