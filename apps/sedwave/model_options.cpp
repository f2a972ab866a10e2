#include "model_options.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "option_checks.hpp"
#include "output_paths.hpp"
#include "site_file.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::app {

namespace {

void apply_value(inversion::ParameterSpec& spec, const std::optional<double>& value, const std::vector<double>& bounds) {
  if (bounds.size() == 2) {
    spec.lower = bounds[0];
    spec.upper = bounds[1];
  }
  if (value) spec.value = *value;
}

bool names_in_list(const std::string& list, std::initializer_list<const char*> names) {
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    for (const char* name : names) {
      if (item == name) return true;
    }
  }
  return false;
}

/// "NAME=REST" split at the first '='; throws naming the option.
std::pair<std::string, std::string> name_and_value(const std::string& item, const char* option) {
  const auto at = item.find('=');
  if (at == std::string::npos || at == 0 || at + 1 == item.size()) {
    throw UsageError(std::string(option) + " '" + item + "': expected NAME=" +
                     (std::string(option) == "--set" ? "VALUE" : "LO,HI"));
  }
  return {item.substr(0, at), item.substr(at + 1)};
}

double number_in(const std::string& text, const std::string& item, const char* option) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(x)) {
    throw UsageError(std::string(option) + " '" + item + "': '" + text + "' is not a finite number");
  }
  return x;
}

/// The parameters a --set or --bounds names (for choices they imply, e.g. a given permeability).
bool names_parameter(const ModelOptions& o, const std::string& name) {
  for (const auto* list : {&o.set_values, &o.set_bounds}) {
    for (const std::string& item : *list) {
      if (item.starts_with(name + "=")) return true;
    }
  }
  return names_in_list(o.fit, {name.c_str()});
}

/// The damping is one parameter, given as gamma or as e_n: options naming both forms conflict.
bool uses_restitution(const ModelOptions& o) {
  const bool gamma_named = names_in_list(o.fit, {"gamma"}) || o.gamma || !o.gamma_bounds.empty() ||
                           names_parameter(o, "gamma");
  const bool en_named = names_in_list(o.fit, {"en", "e_n"}) || o.restitution || !o.restitution_bounds.empty() ||
                        names_parameter(o, "e_n");
  if (gamma_named && en_named) {
    throw std::invalid_argument(
        "the damping is one parameter, given either as the dashpot gamma (--gamma, --gamma-bounds, --fit gamma) or "
        "as the restitution e_n (--en, --en-bounds, --fit en); these options name both");
  }
  return en_named;
}

}  // namespace

std::shared_ptr<const sediment::SedimentModel> make_model(const ModelOptions& o) {
  const sediment::ModelChoices choices{uses_restitution(o) ? sediment::DampingForm::Restitution
                                                           : sediment::DampingForm::Gamma,
                                       names_parameter(o, "permeability") || names_parameter(o, "pore_size")};
  return sediment::make_sediment_model(o.model, choices);
}

/// Refuses a start value or search bound outside the parameter's physical range, naming both.
void check_physical(const inversion::ParameterSpec& spec, const sediment::Parameter& range, const std::string& model) {
  const auto outside = [&](double x) { return !(x >= range.lower && x <= range.upper); };
  if (outside(spec.value) || outside(spec.lower) || outside(spec.upper)) {
    std::ostringstream msg;
    msg << "model '" << model << "': " << spec.name << " (value " << spec.value << ", search bounds [" << spec.lower
        << ", " << spec.upper << "]) must lie within its physical range [" << range.lower << ", " << range.upper
        << "] " << range.unit << " (sedwave models)";
    throw std::invalid_argument(msg.str());
  }
}

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

/// The options that name one parameter each: its value and, for the contact's parameters, its
/// search bounds (an empty bounds option: the parameter has none).
struct Shorthand {
  const char* parameter;
  const std::optional<double>& value;
  const char* value_option;
  const std::vector<double>& bounds;
  const char* bounds_option;
};

std::array<Shorthand, 5> shorthands(const ModelOptions& o) {
  static const std::vector<double> kNoBounds;
  return {{{"kappa", o.kappa, "--kappa", o.kappa_bounds, "--kappa-bounds"},
           {"d", o.diameter, "--d", o.diameter_bounds, "--d-bounds"},
           {"gamma", o.gamma, "--gamma", o.gamma_bounds, "--gamma-bounds"},
           {"e_n", o.restitution, "--en", o.restitution_bounds, "--en-bounds"},
           {"rho_s", o.density, "--density", kNoBounds, ""}}};
}

/// One parameter given through two options (--set kappa= twice, --kappa with --set kappa=, --bounds
/// twice, --kappa-bounds with --bounds kappa=) would keep one of the values silently: refused, naming
/// both options.
void refuse_repeated_parameters(const ModelOptions& o) {
  const auto check = [](const std::vector<std::pair<std::string, std::string>>& given, const char* verb) {
    for (std::size_t i = 0; i < given.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (given[i].first == given[j].first) {
          throw UsageError(given[j].second + " and " + given[i].second + " both " + verb + " " + given[i].first +
                           ": give one");
        }
      }
    }
  };
  std::vector<std::pair<std::string, std::string>> values, bounds;  // (parameter, option as given)
  for (const Shorthand& h : shorthands(o)) {
    if (h.value) values.emplace_back(h.parameter, h.value_option);
  }
  for (const std::string& item : o.set_values) {
    values.emplace_back(name_and_value(item, "--set").first, "--set '" + item + "'");
  }
  for (const Shorthand& h : shorthands(o)) {
    if (!h.bounds.empty()) bounds.emplace_back(h.parameter, h.bounds_option);
  }
  for (const std::string& item : o.set_bounds) {
    bounds.emplace_back(name_and_value(item, "--bounds").first, "--bounds '" + item + "'");
  }
  check(values, "set");
  check(bounds, "bound");
}

/// Search bounds move only a free parameter: on a fixed one they would be ignored.
void refuse_bounds_on_fixed(const ModelOptions& o, const inversion::FitParameters& p) {
  const auto refuse_if_fixed = [&](const std::string& name, const std::string& option) {
    for (const auto& s : p.spec) {
      if (s.name == name && !s.free) {
        throw UsageError(option + " bounds " + name + ", which is fixed (--fit " +
                         (o.fit.empty() ? std::string("default: the model's typical set") : "'" + o.fit + "'") +
                         "): name it in --fit, or drop the bounds");
      }
    }
  };
  for (const Shorthand& h : shorthands(o)) {
    if (!h.bounds.empty()) refuse_if_fixed(h.parameter, h.bounds_option);
  }
  for (const std::string& item : o.set_bounds) {
    refuse_if_fixed(name_and_value(item, "--bounds").first, "--bounds '" + item + "'");
  }
}

}  // namespace

inversion::FitParameters make_parameters(const ModelOptions& o, const sediment::SedimentModel& model, ModelUse use,
                                         std::vector<std::string>* site_notes,
                                         std::vector<inversion::SitePrior>* site_priors) {
  refuse_repeated_parameters(o);
  inversion::FitParameters p(model.parameters());
  if (use == ModelUse::Fit) {
    p.set_free_from_list(!o.fit.empty() ? o.fit : sediment::typical_free_parameters(model));
  }
  const auto named = [&](const char* name, const char* option) -> inversion::ParameterSpec& {
    try {
      return p.spec[p.index_of(name)];
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string(option) + ": " + e.what() + " in model '" + model.name() + "'");
    }
  };
  for (const Shorthand& h : shorthands(o)) {
    if (h.value || !h.bounds.empty()) apply_value(named(h.parameter, h.value_option), h.value, h.bounds);
  }
  inversion::SetBy set_by;  // parameters whose value the command line gives directly, and by which option
  for (const Shorthand& h : shorthands(o)) {
    if (h.value) set_by[h.parameter] = h.value_option;
  }
  for (const std::string& item : o.set_values) {
    const auto [name, text] = name_and_value(item, "--set");
    named(name.c_str(), "--set").value = number_in(text, item, "--set");
    set_by[name] = "--set '" + item + "'";
  }
  std::vector<std::string> notes;
  std::vector<inversion::SitePrior> priors;
  const auto apply = [&](const inversion::Site& site) {
    try {
      inversion::SiteApplied applied = inversion::apply_site(site, model, p, set_by);
      notes.insert(notes.end(), applied.notes.begin(), applied.notes.end());
      priors.insert(priors.end(), applied.priors.begin(), applied.priors.end());
    } catch (const inversion::SiteConflict& e) {
      throw UsageError(e.what());
    }
  };
  apply(site_of_options(o));
  if (!o.site.empty()) apply(read_site_file(o.site));
  if (site_priors) *site_priors = priors;
  if (site_notes) *site_notes = notes;
  for (const std::string& item : o.set_bounds) {
    const auto [name, text] = name_and_value(item, "--bounds");
    const auto comma = text.find(',');
    if (comma == std::string::npos) throw UsageError("--bounds '" + item + "': expected NAME=LO,HI");
    inversion::ParameterSpec& spec = named(name.c_str(), "--bounds");
    spec.lower = number_in(text.substr(0, comma), item, "--bounds");
    spec.upper = number_in(text.substr(comma + 1), item, "--bounds");
  }
  if (use == ModelUse::Fit) refuse_bounds_on_fixed(o, p);
  for (int i = 0; i < p.size(); ++i) check_physical(p.spec[i], model.parameters()[i], model.name());
  p.validate();
  return p;
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
