// Model comparison as a library call (sedwave/inversion/comparison.hpp): a user ranks models with
// one call. On data synthesised by one model, that model ranks first by a margin far beyond the
// evidence's uncertainty; the ranking is the same bit for bit on 1 and on 3 threads; a site's
// priors reach the candidates that have the parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sedwave/inversion/comparison.hpp"
#include "sedwave/inversion/report.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::inversion {
namespace {

/// EDFM at porosity 0.42 and permeability 3e-11 m^2, 12 frequencies from 100 Hz to 100 kHz with 2 %
/// attenuation and 0.3 % sound-speed noise.
ObservationSet edfm_data() {
  const auto edfm = sediment::make_sediment_model("edfm");
  FitParameters truth(edfm->parameters());
  truth.spec[truth.index_of("porosity")].value = 0.42;
  truth.spec[truth.index_of("permeability")].value = 3e-11;
  return synthetic_observations(*edfm, truth, {100.0, 1e5, 12, 0.02, 0.003, 7});
}

ComparisonOptions quick(int threads) {
  ComparisonOptions options;
  options.evidence.temperatures = 8;
  options.evidence.steps = 400;
  options.threads = threads;
  return options;
}

/// The same ranking, bit for bit, from another thread count (the jobs finish in another order).
void expect_the_same_ranking(const Ranking& threaded, const Ranking& ranking) {
  ASSERT_EQ(threaded.models.size(), ranking.models.size());
  for (std::size_t i = 0; i < ranking.models.size(); ++i) {
    EXPECT_EQ(threaded.models[i].evidence.log_evidence, ranking.models[i].evidence.log_evidence);
    EXPECT_EQ(threaded.models[i].widened.log_evidence, ranking.models[i].widened.log_evidence);
    EXPECT_EQ(threaded.models[i].evidence.method, ranking.models[i].evidence.method);
    EXPECT_EQ(threaded.models[i].fit.chi2, ranking.models[i].fit.chi2);
  }
  EXPECT_EQ(threaded.order, ranking.order);
}

TEST(CompareModels, RanksTheModelThatMadeTheDataFirstWithOneCall) {
  const ObservationSet data = edfm_data();
  Site site;  // what a site file would give: porosity 0.42 +- 0.03
  site.porosity = SiteValue{0.42, "site.toml:2: key 'porosity.mean'"};
  site.porosity_sd = SiteValue{0.03, "site.toml:3: key 'porosity.sd'"};
  site.source = "site file site.toml";
  // By name from the catalog, or from a model object the caller made (e.g. a model of its own).
  const std::vector<Candidate> candidates{make_candidate("grain-shearing", site),
                                          make_candidate(sediment::make_sediment_model("edfm"), site)};
  EXPECT_EQ(candidates[1].label, "edfm");
  const Ranking ranking = compare_models(data, candidates, quick(1));

  ASSERT_EQ(ranking.models.size(), 2u);
  EXPECT_EQ(ranking.models[0].model, "grain-shearing");  // in the candidates' order
  EXPECT_EQ(ranking.best().model, "edfm");
  const ComparedModel& edfm = ranking.models[1];
  const ComparedModel& gs = ranking.models[0];
  const double margin = edfm.evidence.log_evidence - gs.evidence.log_evidence;
  EXPECT_GT(margin, 5.0 * std::hypot(edfm.evidence.uncertainty, gs.evidence.uncertainty) + 1.0);
  EXPECT_EQ(ranking.order_widened.front(), 1);  // a prior ten times wider does not turn it round
  // The site's porosity prior reached the model that has porosity free.
  ASSERT_FALSE(edfm.priors.empty());
  EXPECT_EQ(edfm.priors.front().rfind("porosity: normal(mean 0.42, sd 0.03)", 0), 0u) << edfm.priors.front();
  EXPECT_NE(edfm.priors.front().find("(site file site.toml)"), std::string::npos);
  EXPECT_EQ(edfm.band.frequency_hz.size(), curve_frequencies(data).size());

  expect_the_same_ranking(compare_models(data, candidates, quick(3)), ranking);
}

// A model that does not describe the data at all (the lattice's chi^2 on EDFM's data is in the
// thousands) has ln Z <= ln L_max = -chi^2_min / 2, since the prior integrates to 1. Where that bound
// lies far below a model's converged ln Z it decides the ranking, and the comparison states it,
// labelled as a bound, instead of running tempering; the same on 1 and on 2 threads.
TEST(CompareModels, StatesABoundForAModelFarBelowAnother) {
  const ObservationSet data = edfm_data();
  const std::vector<Candidate> candidates{make_candidate("lattice"), make_candidate("edfm")};
  const Ranking ranking = compare_models(data, candidates, quick(1));
  const ComparedModel& lattice = ranking.models[0];
  const ComparedModel& edfm = ranking.models[1];
  ASSERT_GT(lattice.fit.chi2, 1000.0);
  ASSERT_TRUE(edfm.evidence.converged);
  for (const ModelEvidence* e : {&lattice.evidence, &lattice.widened}) {
    EXPECT_EQ(e->method, kUpperBoundMethod);
    EXPECT_EQ(e->log_evidence, -0.5 * lattice.fit.chi2);
    EXPECT_FALSE(e->converged);  // a bound, never an estimate
    EXPECT_EQ(e->steps, 0);      // no tempering ran
    EXPECT_LE(e->highest_drawn_log_likelihood, e->log_evidence);  // the cubature's draws: none above the fit
  }
  EXPECT_LT(lattice.evidence.log_evidence, edfm.evidence.log_evidence - 100.0);
  EXPECT_TRUE(ranking.converged());  // the ranking is decided
  EXPECT_EQ(ranking.best().model, "edfm");
  EXPECT_EQ(lattice.evidence.samples.rows(), 1);  // the band: the best fit's curve alone
  EXPECT_EQ(lattice.band.frequency_hz.size(), curve_frequencies(data).size());

  expect_the_same_ranking(compare_models(data, candidates, quick(2)), ranking);
}

TEST(CompareModels, RefusesNoModelsAndPriorsThatDoNotMatch) {
  EXPECT_THROW((void)compare_models(edfm_data(), {}), std::invalid_argument);
  Candidate broken = make_candidate("edfm");
  broken.priors.pop_back();
  EXPECT_THROW((void)compare_models(edfm_data(), {broken}), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::inversion

namespace sedwave::inversion {
namespace {

const FitOptions kGlobal{.method = FitMethod::Global, .profile_likelihood = false};

// Importance sampling around the fit serves a posterior that is one peak, and refuses a ridge that
// only the priors' bounds close: the lattice chain's kappa and d from sound speeds far below its
// dispersion, which see c0 = d sqrt(kappa / m) alone. Both columns come from the same evaluations.
TEST(ImportanceEvidence, ServesAPeakAndRefusesARidge) {
  const auto chain = sediment::make_sediment_model("lattice");
  const FitParameters truth(chain->parameters());
  for (const bool ridge : {false, true}) {
    ObservationSet data = synthetic_observations(*chain, truth, ridge ? SyntheticDesign{100.0, 300.0, 20, 0.05, 0.01, 101}
                                                                      : SyntheticDesign{100.0, 1e5, 20, 0.05, 0.01, 1});
    if (ridge) std::erase_if(data.observations, [](const Observation& o) { return o.quantity != Quantity::SoundSpeed; });
    FitParameters start = truth;
    start.set_free_from_list("kappa,d");
    const FitResult best = fit(data, *chain, start, kGlobal);
    const std::vector<Prior> priors = make_priors(best.fitted, {});
    const std::vector<ModelEvidence> e =
        importance_sampled_evidence(data, *chain, best, {priors, widened(priors, 10.0)}, kGlobal, {});
    ASSERT_EQ(e.size(), 2u);
    for (const ModelEvidence& column : e) {
      EXPECT_EQ(column.fallback_reason.empty(), !ridge) << column.fallback_reason;
      EXPECT_EQ(column.evaluations, e[0].evaluations);
      if (!ridge) {
        EXPECT_LE(column.uncertainty, 0.05);
      }
    }
    if (!ridge) {
      EXPECT_LE(e[0].evaluations, 10000);
    }
  }
}

}  // namespace
}  // namespace sedwave::inversion
