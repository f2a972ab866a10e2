#include "model_options.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "option_checks.hpp"
#include "output_paths.hpp"
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

inversion::FitParameters make_parameters(const ModelOptions& o, const sediment::SedimentModel& model, ModelUse use) {
  inversion::FitParameters p(model.parameters());
  if (use == ModelUse::Fit) {
    const std::string fit = !o.fit.empty() ? o.fit : p.starts_with_grain_contact() ? "kappa,d," + p.spec[2].name : "";
    if (fit.empty()) {
      std::string names;
      for (const auto& s : p.spec) names += (names.empty() ? "" : ",") + s.name;
      throw UsageError("model '" + model.name() + "': give --fit with the parameters to fit, among " + names);
    }
    p.set_free_from_list(fit);
  }
  const auto named = [&](const char* name, const char* option) -> inversion::ParameterSpec& {
    try {
      return p.spec[p.index_of(name)];
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string(option) + ": " + e.what() + " in model '" + model.name() + "'");
    }
  };
  if (o.kappa || !o.kappa_bounds.empty()) apply_value(named("kappa", "--kappa"), o.kappa, o.kappa_bounds);
  if (o.diameter || !o.diameter_bounds.empty()) apply_value(named("d", "--d"), o.diameter, o.diameter_bounds);
  if (o.gamma || !o.gamma_bounds.empty()) apply_value(named("gamma", "--gamma"), o.gamma, o.gamma_bounds);
  if (o.restitution || !o.restitution_bounds.empty()) {
    apply_value(named("e_n", "--en"), o.restitution, o.restitution_bounds);
  }
  if (o.density) apply_value(named("rho_s", "--density"), o.density, {});
  for (const std::string& item : o.set_values) {
    const auto [name, text] = name_and_value(item, "--set");
    named(name.c_str(), "--set").value = number_in(text, item, "--set");
  }
  for (const std::string& item : o.set_bounds) {
    const auto [name, text] = name_and_value(item, "--bounds");
    const auto comma = text.find(',');
    if (comma == std::string::npos) throw UsageError("--bounds '" + item + "': expected NAME=LO,HI");
    inversion::ParameterSpec& spec = named(name.c_str(), "--bounds");
    spec.lower = number_in(text.substr(0, comma), item, "--bounds");
    spec.upper = number_in(text.substr(comma + 1), item, "--bounds");
  }
  for (int i = 0; i < p.size(); ++i) check_physical(p.spec[i], model.parameters()[i], model.name());
  p.validate();
  return p;
}

void add_model_options(CLI::App& cmd, ModelOptions& o, ModelUse use) {
  const bool fit = use == ModelUse::Fit;
  std::string models;
  for (const std::string& name : sediment::sediment_model_names()) models += (models.empty() ? "" : " | ") + name;
  cmd.add_option("--model", o.model,
                 "sediment model: " + models + " (table: FILE.h5[?extrapolate=theory|long-wavelength], docs/tables.md; "
                 "each model's parameters: sedwave models)")
      ->capture_default_str();
  const std::string role = fit ? ": start value, or the value if fixed" : "";
  if (fit) {
    cmd.add_option("--fit", o.fit,
                   "free parameters, comma-separated (others fixed); default kappa,d,gamma for models with grain "
                   "contacts (gamma|en for the damping)");
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
  if (!fit) return;
  cmd.add_option("--bounds", o.set_bounds, "NAME=LO,HI: a parameter's search bounds [SI] (repeatable)");
  cmd.add_option("--kappa-bounds", o.kappa_bounds, "LO,HI [N/m]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--d-bounds", o.diameter_bounds, "LO,HI [m]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--gamma-bounds", o.gamma_bounds, "LO,HI [kg/s]")->delimiter(',')->expected(2)->check(finite_positive());
  cmd.add_option("--en-bounds", o.restitution_bounds, "LO,HI")->delimiter(',')->expected(2)
      ->check(finite_in(1e-6, 0.999999));
}

}  // namespace sedwave::app
