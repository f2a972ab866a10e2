#include "sedwave/inversion/parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sedwave::inversion {
namespace {

std::vector<ParameterSpec> specs_of(const std::vector<sediment::Parameter>& parameters) {
  std::vector<ParameterSpec> spec;
  for (const sediment::Parameter& p : parameters) {
    spec.push_back({p.name, p.unit, p.default_value, p.lower, p.upper, false});
  }
  return spec;
}

bool is_damping_name(const std::string& name) { return name == "gamma" || name == "en" || name == "e_n"; }

}  // namespace

FitParameters::FitParameters() : spec(specs_of(sediment::grain_contact_parameters(DampingForm::Gamma))) {
  for (const char* name : {"kappa", "d", "gamma"}) spec[index_of(name)].free = true;
}

FitParameters::FitParameters(const std::vector<sediment::Parameter>& parameters) : spec(specs_of(parameters)) {}

int FitParameters::index_of(const std::string& name) const {
  for (int i = 0; i < size(); ++i) {
    if (spec[i].name == name) return i;
  }
  std::string accepted;
  for (const ParameterSpec& s : spec) accepted += (accepted.empty() ? "" : ", ") + s.name;
  throw std::invalid_argument("unknown parameter '" + name + "' (accepted: " + accepted + ")");
}

int FitParameters::damping_index() const {
  for (int i = 0; i < size(); ++i) {
    if (spec[i].name == "gamma" || spec[i].name == "e_n") return i;
  }
  return -1;
}

DampingForm FitParameters::damping_form() const {
  const int i = damping_index();
  return i >= 0 && spec[i].name == "e_n" ? DampingForm::Restitution : DampingForm::Gamma;
}

void FitParameters::set_damping_form(DampingForm form) {
  const int i = damping_index();
  if (i < 0) throw std::invalid_argument("this model has no contact damping to switch");
  const bool was_free = spec[i].free;
  for (const sediment::Parameter& p : sediment::grain_contact_parameters(form)) {
    if (p.name == "gamma" || p.name == "e_n") spec[i] = {p.name, p.unit, p.default_value, p.lower, p.upper, was_free};
  }
}

void FitParameters::set_free_from_list(const std::string& list, const std::string& origin) {
  const std::string given = origin.empty() ? "--fit '" + list + "'" : origin;
  for (ParameterSpec& s : spec) s.free = false;
  std::stringstream stream(list);
  std::string name;
  std::string damping_named;  // "gamma" or "en" once the damping is named
  while (std::getline(stream, name, ',')) {
    int index = -1;
    if (damping_index() >= 0 && is_damping_name(name)) {
      const std::string form_name = name == "gamma" ? "gamma" : "en";
      if (!damping_named.empty() && damping_named != form_name) {
        throw std::invalid_argument(given + " names both gamma and en: the damping is one parameter, "
                                    "given either as the dashpot gamma or as the restitution e_n; choose one");
      }
      damping_named = form_name;
      const DampingForm form = name == "gamma" ? DampingForm::Gamma : DampingForm::Restitution;
      if (form != damping_form()) set_damping_form(form);
      index = damping_index();
    } else {
      try {
        index = index_of(name);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(given + ": " + e.what());
      }
    }
    if (spec[index].free) throw std::invalid_argument(given + " names '" + name + "' twice");
    spec[index].free = true;
  }
  if (free_indices().empty()) throw std::invalid_argument("no parameter to fit in '" + list + "'");
}

std::vector<int> FitParameters::free_indices() const {
  std::vector<int> free;
  for (int i = 0; i < size(); ++i) {
    if (spec[i].free) free.push_back(i);
  }
  return free;
}

std::vector<double> FitParameters::values() const {
  std::vector<double> v;
  for (const ParameterSpec& s : spec) v.push_back(s.value);
  return v;
}

std::vector<double> FitParameters::log_values() const {
  std::vector<double> v;
  for (const ParameterSpec& s : spec) v.push_back(std::log(s.value));
  return v;
}

void FitParameters::validate() const {
  for (const ParameterSpec& s : spec) {
    if (!(s.lower > 0.0) || !(s.upper > s.lower)) {
      std::ostringstream msg;
      msg << "bounds of " << s.name << " [" << s.lower << ", " << s.upper << "] must satisfy 0 < lower < upper";
      throw std::invalid_argument(msg.str());
    }
    if (!(s.value >= s.lower && s.value <= s.upper)) {
      std::ostringstream msg;
      msg << s.name << " = " << s.value << " " << s.unit << " lies outside its bounds [" << s.lower << ", " << s.upper
          << "] " << s.unit;
      throw std::invalid_argument(msg.str());
    }
  }
}

void FitParameters::require_parameters_of(const sediment::SedimentModel& model) const {
  const std::vector<sediment::Parameter>& ps = model.parameters();
  bool same = ps.size() == spec.size();
  for (std::size_t i = 0; same && i < ps.size(); ++i) same = ps[i].name == spec[i].name;
  if (!same) {
    std::string names;
    for (const sediment::Parameter& p : ps) names += (names.empty() ? "" : ", ") + p.name;
    throw std::invalid_argument("the parameters given are not those of model '" + model.name() + "' (" + names + ")");
  }
}

}  // namespace sedwave::inversion
