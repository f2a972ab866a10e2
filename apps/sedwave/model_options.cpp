#include "model_options.hpp"

#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::app {

namespace {

/// The command line's site options as a Site (the same value a site file fills); the conversion
/// (inversion/site.hpp) refuses a parameter the model lacks, since these options name one model.
inversion::Site site_of_options(const ModelOptions& o) {
  if (o.water_temperature.has_value() != o.salinity.has_value()) {
    throw UsageError("--water-temperature and --salinity go together");
  }
  const auto value = [](const std::optional<double>& x, const char* option) -> std::optional<inversion::SiteValue> {
    if (!x) return std::nullopt;
    return inversion::SiteValue{*x, option};
  };
  inversion::Site site;
  site.source = "command line";
  site.phi = value(o.phi, "--phi");
  site.porosity = value(o.porosity, "--porosity");
  site.bulk_density = value(o.bulk_density, "--bulk-density");
  site.depth = value(o.depth, "--depth");
  site.effective_pressure = value(o.effective_pressure, "--effective-pressure");
  site.water_temperature = value(o.water_temperature, "--water-temperature");
  site.salinity = value(o.salinity, "--salinity");
  return site;
}

}  // namespace

inversion::ModelSetup setup_of(const ModelOptions& o) {
  inversion::ModelSetup setup;
  setup.model = o.model;
  setup.free = o.fit;
  // The options that name one parameter each: its value and, for the contact's parameters, its
  // search bounds. A message about the parameter's name names the value's option.
  const auto shorthand = [&](const char* parameter, const std::optional<double>& value, const char* value_option,
                             const std::vector<double>& bounds, const char* bounds_option) {
    if (value) setup.values.push_back({parameter, *value, value_option, ""});
    if (bounds.size() == 2) setup.bounds.push_back({parameter, bounds[0], bounds[1], bounds_option, value_option});
  };
  shorthand("kappa", o.kappa, "--kappa", o.kappa_bounds, "--kappa-bounds");
  shorthand("d", o.diameter, "--d", o.diameter_bounds, "--d-bounds");
  shorthand("gamma", o.gamma, "--gamma", o.gamma_bounds, "--gamma-bounds");
  shorthand("e_n", o.restitution, "--en", o.restitution_bounds, "--en-bounds");
  shorthand("rho_s", o.density, "--density", {}, "");
  try {
    for (const std::string& item : o.set_values) setup.add_value(item, "--set");
    for (const std::string& item : o.set_bounds) setup.add_bounds(item, "--bounds");
  } catch (const inversion::SetupError& e) {
    throw UsageError(e.what());
  }
  setup.site = site_of_options(o);
  if (!o.site.empty()) setup.site_file = o.site;
  return setup;
}

inversion::Candidate candidate_of(const inversion::ModelSetup& setup, ModelUse use) {
  try {
    return inversion::make_candidate(setup, use);
  } catch (const inversion::SetupError& e) {
    throw UsageError(e.what());
  }
}

void add_model_options(CLI::App& cmd, ModelOptions& o, ModelUse use) {
  const bool fit = use == ModelUse::Fit;
  std::string models;
  for (const std::string& name : sediment::sediment_model_names()) models += (models.empty() ? "" : " | ") + name;
  cmd.add_option("--model", o.model,
                 "sediment model: " + models + " (table: FILE.h5[?interpolate=correction][&extrapolate=theory|long-wavelength], docs/tables.md; "
                 "each model's parameters: sedwave models)")
      ->capture_default_str();
  const std::string role = fit ? ": start value, or the value if fixed" : "";
  if (fit) {
    cmd.add_option("--fit", o.fit,
                   "free parameters, comma-separated (others fixed); default: the model's typical set (kappa,d,gamma "
                   "for grain contacts, gamma|en for the damping; sedwave models)")
        ->check(non_empty_list());
  }
  cmd.add_option("--set", o.set_values, "NAME=VALUE: a parameter's value [SI]" + role + " (repeatable)");
  cmd.add_option("--kappa", o.kappa, "contact stiffness [N/m]" + role)->check(finite_positive());
  cmd.add_option("--d", o.diameter, "grain diameter [m]" + role)->check(finite_positive());
  auto* gamma = cmd.add_option("--gamma", o.gamma, "normal dashpot [kg/s]" + role)->check(finite_positive());
  auto* en = cmd.add_option("--en", o.restitution, "restitution coefficient e_n in (0, 1)" + role)
                 ->check(finite_in(1e-6, 0.999999));
  if (!fit) gamma->excludes(en);
  cmd.add_option("--density", o.density, "grain density rho_s [kg/m^3] (same as --set rho_s=VALUE; default 2650)")
      ->check(finite_in(100.0, 25000.0));
  // What users measure at a site (docs/models/site-inputs.md).
  cmd.add_option("--phi", o.phi, "site: mean grain size in Krumbein phi units, d = 2^-phi mm (sets d)")
      ->check(finite_in(-10.0, 14.0));
  cmd.add_option("--porosity", o.porosity, "site: porosity [1] (sets porosity; in Hertz for --depth)")
      ->check(finite_in(1e-6, 0.999999));
  cmd.add_option("--bulk-density", o.bulk_density, "site: wet bulk density [kg/m^3] (sets porosity)")
      ->check(finite_positive());
  cmd.add_option("--depth", o.depth,
                 "site: depth below the seafloor [m]; kappa from the Hertz stiffness of quartz grains at its effective "
                 "pressure (sets kappa)")
      ->check(finite_in(0.0, 1000.0));
  cmd.add_option("--effective-pressure", o.effective_pressure,
                 "site: mean effective pressure [Pa]; kappa from Hertz as for --depth (sets kappa)")
      ->check(finite_positive());
  cmd.add_option("--water-temperature", o.water_temperature,
                 "site: bottom-water temperature [deg C], with --salinity (sets rho_w, K_w, eta)")
      ->check(finite_in(-2.0, 40.0));
  cmd.add_option("--salinity", o.salinity, "site: salinity [ppt], with --water-temperature")->check(finite_in(0.0, 45.0));
  cmd.add_option("--site", o.site,
                 "site file (TOML): grain size, porosity, depth, water, e_n range as priors (--method posterior, "
                 "compare) or values (fixed parameters); docs/inversion.md, \"Site files\"")
      ->check(CLI::ExistingFile);
  if (!fit) return;
  cmd.add_option("--bounds", o.set_bounds, "NAME=LO,HI: a parameter's search bounds [SI] (repeatable)");
  cmd.add_option("--kappa-bounds", o.kappa_bounds, "LO,HI [N/m]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--d-bounds", o.diameter_bounds, "LO,HI [m]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--gamma-bounds", o.gamma_bounds, "LO,HI [kg/s]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--en-bounds", o.restitution_bounds, "LO,HI")->delimiter(',')->expected(2)
      ->check(finite_in(1e-6, 0.999999));
}

}  // namespace sedwave::app
