// Site knowledge, typed (sedwave/inversion/site.hpp): one conversion for a site file's values and
// the command line's, checked against the worked example of docs/models/site-inputs.md (evaluated by
// hand there), with the model's own densities in Hertz, typed priors, and conflicts named.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sedwave/inversion/site.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/site.hpp"

namespace sedwave::inversion {
namespace {

SiteValue value(double x, const std::string& origin) { return {x, origin}; }

/// The worked example's site: medium sand of phi 1.5, porosity 0.38, 1 m deep, water 15 deg C, 35 ppt;
/// as a site file gives it (with uncertainties, skipping what a model lacks) or as options.
Site worked_example(bool as_file) {
  Site site;
  const auto origin = [&](const char* key, const char* option) {
    return as_file ? std::string("site.toml:1: key '") + key + "'" : std::string(option);
  };
  site.phi = value(1.5, origin("grain_size.phi", "--phi"));
  site.porosity = value(0.38, origin("porosity.mean", "--porosity"));
  site.depth = value(1.0, origin("depth.metres", "--depth"));
  site.water_temperature = value(15.0, origin("water.temperature_c", "--water-temperature"));
  site.salinity = value(35.0, origin("water.salinity_ppt", "--salinity"));
  if (as_file) {
    site.phi_sd = value(0.5, "site.toml:2: key 'grain_size.phi_sd'");
    site.porosity_sd = value(0.03, "site.toml:4: key 'porosity.sd'");
    site.kappa_sd_ln = value(1.0, "site.toml:6: key 'depth.kappa_sd_ln'");
    site.source = "site file site.toml";
    site.skip_missing_parameters = true;
  } else {
    site.source = "command line";
  }
  return site;
}

double value_of(const FitParameters& p, const std::string& name) { return p.spec[p.index_of(name)].value; }

TEST(Site, FileAndOptionsGiveIdenticalFixedValues) {
  const auto model = sediment::make_sediment_model("saturated-lattice");
  FitParameters from_file(model->parameters()), from_options(model->parameters());
  SetBy file_set, options_set;
  const SiteApplied file = apply_site(worked_example(true), *model, from_file, file_set);
  const SiteApplied options = apply_site(worked_example(false), *model, from_options, options_set);
  EXPECT_TRUE(file.priors.empty());  // every parameter fixed: a prior's median is the value
  for (int i = 0; i < from_file.size(); ++i) {
    SCOPED_TRACE(from_file.spec[i].name);
    EXPECT_EQ(from_file.spec[i].value, from_options.spec[i].value);  // bit for bit
  }
  EXPECT_NE(value_of(from_file, "kappa"), model->parameters()[0].default_value);
  // The same notes, the file's saying where they came from.
  ASSERT_EQ(file.notes.size(), options.notes.size());
  for (std::size_t i = 0; i < file.notes.size(); ++i) {
    EXPECT_EQ(file.notes[i], options.notes[i] + " (site file site.toml)");
  }
}

TEST(Site, WorkedExampleMatchesTheHandValues) {
  // docs/models/site-inputs.md: d = 3.5355e-4 m, rho_w = 1025.972 kg/m^3, K_w = 2.3291e9 Pa,
  // eta = 1.2199e-3 Pa s, kappa = 8.216e4 N/m (to the digits printed there).
  const auto model = sediment::make_sediment_model("saturated-lattice");
  FitParameters p(model->parameters());
  SetBy set_by;
  (void)apply_site(worked_example(false), *model, p, set_by);
  EXPECT_NEAR(value_of(p, "d"), 3.5355e-4, 0.00005e-4);
  EXPECT_NEAR(value_of(p, "porosity"), 0.38, 1e-15);
  EXPECT_NEAR(value_of(p, "rho_w"), 1025.972, 0.0005);
  EXPECT_NEAR(value_of(p, "K_w"), 2.3291e9, 0.00005e9);
  EXPECT_NEAR(value_of(p, "eta"), 1.2199e-3, 0.00005e-3);
  EXPECT_NEAR(value_of(p, "kappa"), 8.216e4, 0.0005e4);
}

TEST(Site, HertzUsesTheModelsOwnGrainDensity) {
  // Denser grains weigh more at 1 m: the effective stress, and with it kappa ~ p'^(1/3), grows.
  const auto model = sediment::make_sediment_model("saturated-lattice");
  FitParameters quartz(model->parameters()), heavy(model->parameters());
  heavy.spec[heavy.index_of("rho_s")].value = 5000.0;
  SetBy a{}, b{{"rho_s", "--density"}};
  (void)apply_site(worked_example(false), *model, quartz, a);
  (void)apply_site(worked_example(false), *model, heavy, b);
  const double rho_w = value_of(heavy, "rho_w");
  // sigma_v' = (1 - beta) (rho_s - rho_w) g z: the ratio of the two stresses, to the power 1/3.
  const double ratio = std::cbrt((5000.0 - rho_w) / (2650.0 - rho_w));
  EXPECT_NEAR(value_of(heavy, "kappa") / value_of(quartz, "kappa"), ratio, 1e-12);
}

TEST(Site, UncertaintiesBecomeTypedPriorsOfFreeParameters) {
  const auto model = sediment::make_sediment_model("saturated-lattice");
  FitParameters p(model->parameters());
  p.set_free_from_list("kappa,d,gamma,porosity");
  SetBy set_by;
  const SiteApplied applied = apply_site(worked_example(true), *model, p, set_by);
  ASSERT_EQ(applied.priors.size(), 3u);
  const SitePrior& d = applied.priors[0];
  EXPECT_EQ(d.parameter, "d");
  EXPECT_EQ(d.prior.kind, PriorKind::LogNormal);
  EXPECT_EQ(d.prior.a, sediment::diameter_from_phi(1.5));  // full precision, not a printed number
  EXPECT_DOUBLE_EQ(d.prior.b, 0.5 * std::numbers::ln2);
  EXPECT_EQ(d.prior.source, "site file site.toml");
  EXPECT_EQ(applied.priors[1].parameter, "porosity");
  EXPECT_EQ(applied.priors[1].prior.kind, PriorKind::Normal);
  EXPECT_EQ(applied.priors[2].parameter, "kappa");
  EXPECT_EQ(applied.priors[2].prior.a, value_of(p, "kappa"));  // the start is the prior's median
  std::vector<Prior> priors = default_priors(p);
  apply_site_priors(p, applied.priors, priors);
  const Prior& on_d = priors[static_cast<std::size_t>(p.index_of("d"))];
  EXPECT_EQ(on_d.lower, p.spec[p.index_of("d")].lower);
  EXPECT_EQ(on_d.upper, p.spec[p.index_of("d")].upper);
}

/// The message of what `f` throws as E (empty if it does not throw that).
template <class E, class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

TEST(Site, ConflictsAndMissingParametersAreNamed) {
  const auto saturated = sediment::make_sediment_model("saturated-lattice");
  FitParameters p(saturated->parameters());
  SetBy set_by{{"d", "--d"}};
  EXPECT_EQ(message_of<SiteConflict>([&] { (void)apply_site(worked_example(false), *saturated, p, set_by); }),
            "--phi and --d both set d: give one");
  const auto lattice = sediment::make_sediment_model("lattice");
  // The dry lattice has no pore water and no porosity, yet takes both into Hertz at depth, from the
  // command line as from a file: the same kappa either way.
  SetBy from_flags_set_by, from_file_set_by;
  FitParameters from_flags(lattice->parameters()), from_file(lattice->parameters());
  EXPECT_NO_THROW((void)apply_site(worked_example(false), *lattice, from_flags, from_flags_set_by));
  EXPECT_NO_THROW((void)apply_site(worked_example(true), *lattice, from_file, from_file_set_by));
  EXPECT_EQ(value_of(from_flags, "kappa"), value_of(from_file, "kappa"));
  EXPECT_NE(value_of(from_flags, "kappa"), value_of(FitParameters(lattice->parameters()), "kappa"));
  // Without a depth or a bulk density the water has nothing to do there: refused from the command
  // line (skipped from a file, which serves every model of a comparison).
  Site water_only;
  water_only.water_temperature = value(15.0, "--water-temperature");
  water_only.salinity = value(35.0, "--salinity");
  SetBy none;
  FitParameters q(lattice->parameters());
  EXPECT_EQ(message_of<SiteConflict>([&] { (void)apply_site(water_only, *lattice, q, none); }),
            "--water-temperature: model 'lattice' has no pore-water parameters");
  Site porosity_only;
  porosity_only.porosity = value(0.38, "--porosity");
  EXPECT_EQ(message_of<SiteConflict>([&] { (void)apply_site(porosity_only, *lattice, q, none); }),
            "--porosity: model 'lattice' has no parameter 'porosity'");
  SetBy none_again;
  FitParameters r(lattice->parameters());
  EXPECT_NO_THROW((void)apply_site(worked_example(true), *lattice, r, none_again));
  Site no_grain_size = worked_example(true);
  no_grain_size.phi.reset();
  SetBy empty;
  FitParameters s(lattice->parameters());
  EXPECT_EQ(message_of<std::invalid_argument>([&] { (void)apply_site(no_grain_size, *lattice, s, empty); })
                .rfind("site.toml:1: key 'depth.metres': the Hertz stiffness needs the grain size", 0),
            0u);
}

}  // namespace
}  // namespace sedwave::inversion
