// Setting up a study (setup.hpp): one conversion from what a user says to a ready-to-fit model, with
// every mistake named by where it was said.
#include <gtest/gtest.h>

#include <string>

#include "sedwave/inversion/setup.hpp"

namespace sedwave::inversion {
namespace {

std::string setup_error(const ModelSetup& setup, SetupUse use = SetupUse::Fit) {
  try {
    (void)make_candidate(setup, use);
  } catch (const SetupError& e) {
    return e.what();
  } catch (const std::invalid_argument&) {
    return "(another error)";
  }
  return "(no error)";
}

TEST(ModelSetup, ValuesBoundsAndFreeSetReachTheParameters) {
  ModelSetup setup;
  setup.model = "biot-stoll";
  setup.free = "porosity,permeability";
  setup.add_value("delta_b=0.02", "--set");
  setup.add_bounds("porosity=0.3,0.5", "--bounds");
  const Candidate c = make_candidate(setup);
  EXPECT_EQ(c.label, "biot-stoll");
  const ParameterSpec& porosity = c.parameters.spec[static_cast<std::size_t>(c.parameters.index_of("porosity"))];
  EXPECT_TRUE(porosity.free);
  EXPECT_EQ(porosity.lower, 0.3);
  EXPECT_EQ(porosity.upper, 0.5);
  EXPECT_EQ(c.parameters.spec[static_cast<std::size_t>(c.parameters.index_of("delta_b"))].value, 0.02);
  EXPECT_FALSE(c.parameters.spec[static_cast<std::size_t>(c.parameters.index_of("delta_b"))].free);
  EXPECT_EQ(c.given.at("delta_b"), "--set 'delta_b=0.02'");
  EXPECT_EQ(c.priors.size(), c.parameters.spec.size());
}

TEST(ModelSetup, MistakesNameWhereTheyWereMade) {
  ModelSetup twice;
  twice.values.push_back({"kappa", 1e6, "--kappa", ""});
  twice.add_value("kappa=2e6", "--set");
  EXPECT_EQ(setup_error(twice), "--kappa and --set 'kappa=2e6' both set kappa: give one");

  ModelSetup unknown;
  unknown.model = "edfm";
  unknown.values.push_back({"kappa", 1e6, "values['kappa']", ""});
  EXPECT_NE(setup_error(unknown).find("values['kappa']: "), std::string::npos);
  EXPECT_NE(setup_error(unknown).find("in model 'edfm'"), std::string::npos);

  ModelSetup fixed_bounds;
  fixed_bounds.add_bounds("rho_s=2000,3000", "--bounds");
  EXPECT_NE(setup_error(fixed_bounds).find("--bounds 'rho_s=2000,3000' bounds rho_s, which is fixed"), std::string::npos);

  ModelSetup setup;
  EXPECT_THROW(setup.add_value("kappa", "--set"), SetupError);
  EXPECT_THROW(setup.add_value("kappa=abc", "--set"), SetupError);
  EXPECT_THROW(setup.add_bounds("kappa=1e4", "--bounds"), SetupError);
}

TEST(ModelSetup, SharedSettingsSkipWhatAModelLacks) {
  ModelSetup setup;
  setup.model = "edfm";
  setup.add_value("kappa=1e6", "--set");  // the grain contact's: EDFM has no kappa
  setup.priors = {"kappa=log-uniform:1e4,1e8"};
  setup.shared = true;
  const Candidate c = make_candidate(setup);
  EXPECT_FALSE(c.given.contains("kappa"));
  setup.shared = false;
  EXPECT_NE(setup_error(setup).find("in model 'edfm'"), std::string::npos);
}

TEST(ModelSetup, ForwardRunsNeedTheValuesNoDefaultStandsFor) {
  ModelSetup setup;  // the lattice chain: kappa, d and the damping have no typical value
  Candidate c = make_candidate(setup, SetupUse::Truth);
  EXPECT_EQ(values_not_given(c), (std::vector<std::string>{"kappa", "d", "gamma"}));
  EXPECT_TRUE(c.parameters.free_indices().empty());
  setup.values = {{"kappa", 1e6, "--kappa", ""}, {"d", 3e-4, "--d", ""}, {"e_n", 0.5, "--en", ""}};
  c = make_candidate(setup, SetupUse::Truth);
  EXPECT_TRUE(values_not_given(c).empty());
  EXPECT_EQ(c.parameters.damping_form(), DampingForm::Restitution);
}

TEST(ModelSetup, AValueOutsideItsPhysicalRangeIsNotASetupMistake) {
  ModelSetup setup;
  setup.values.push_back({"d", 5.0, "--d", ""});
  EXPECT_THROW((void)make_candidate(setup), std::invalid_argument);
  EXPECT_EQ(setup_error(setup), "(another error)");
}

TEST(ModelSetup, ASiteFileSetsValuesAndPriors) {
  ModelSetup setup;
  setup.model = "biot-stoll";
  setup.free = "porosity,permeability";
  setup.site_file = std::string(SEDWAVE_SOURCE_DIR) + "/data/sites/medium_sand.toml";
  const Candidate c = make_candidate(setup);
  EXPECT_FALSE(c.notes.empty());
  const Prior& porosity = c.priors[static_cast<std::size_t>(c.parameters.index_of("porosity"))];
  EXPECT_NE(porosity.source.find("medium_sand.toml"), std::string::npos);
}

}  // namespace
}  // namespace sedwave::inversion
