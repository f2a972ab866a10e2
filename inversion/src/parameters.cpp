#include "sedwave/inversion/parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sedwave::inversion {

void FitParameters::set_damping_form(DampingForm form) {
  damping = form;
  const bool was_free = spec[kDamping].free;
  // e_n < 1 strictly: e_n = 1 means no dashpot, where attenuation (fitted in log space) vanishes.
  spec[kDamping] = form == DampingForm::Gamma ? ParameterSpec{1.0e-2, 1.0e-12, 1.0e8, was_free}
                                              : ParameterSpec{0.5, 1.0e-6, 0.999999, was_free};
}

void FitParameters::set_free_from_list(const std::string& list) {
  for (ParameterSpec& s : spec) s.free = false;
  std::stringstream stream(list);
  std::string name;
  std::string damping_named;  // "gamma" or "en" once the damping is named
  while (std::getline(stream, name, ',')) {
    int index = -1;
    if (name == "kappa") {
      index = kKappa;
    } else if (name == "d") {
      index = kDiameter;
    } else if (name == "gamma" || name == "en" || name == "e_n") {
      const std::string form_name = name == "gamma" ? "gamma" : "en";
      if (!damping_named.empty() && damping_named != form_name) {
        throw std::invalid_argument("--fit '" + list + "' names both gamma and en: the damping is one parameter, "
                                    "given either as the dashpot gamma or as the restitution e_n; choose one");
      }
      damping_named = form_name;
      const DampingForm form = name == "gamma" ? DampingForm::Gamma : DampingForm::Restitution;
      if (form != damping) set_damping_form(form);
      index = kDamping;
    } else {
      throw std::invalid_argument("unknown fit parameter '" + name + "' in --fit '" + list +
                                  "' (accepted: kappa, d, gamma, en)");
    }
    if (spec[index].free) throw std::invalid_argument("--fit '" + list + "' names '" + name + "' twice");
    spec[index].free = true;
  }
  if (free_indices().empty()) throw std::invalid_argument("no parameter to fit in '" + list + "'");
}

std::vector<int> FitParameters::free_indices() const {
  std::vector<int> free;
  for (int i = 0; i < kParameterCount; ++i) {
    if (spec[i].free) free.push_back(i);
  }
  return free;
}

std::array<double, kParameterCount> FitParameters::log_values() const {
  return {std::log(spec[0].value), std::log(spec[1].value), std::log(spec[2].value)};
}

void FitParameters::validate() const {
  if (!(density > 0.0)) throw std::invalid_argument("grain density must be positive");
  for (int i = 0; i < kParameterCount; ++i) {
    const ParameterSpec& s = spec[i];
    const std::string name = parameter_name(i, damping);
    if (!(s.lower > 0.0) || !(s.upper > s.lower)) {
      throw std::invalid_argument("bounds of " + name + " must satisfy 0 < lower < upper");
    }
    if (!(s.value >= s.lower && s.value <= s.upper)) {
      std::ostringstream msg;
      msg << name << " = " << s.value << " lies outside its bounds [" << s.lower << ", " << s.upper << "]";
      throw std::invalid_argument(msg.str());
    }
  }
}

std::string parameter_name(int index, DampingForm form) {
  switch (index) {
    case kKappa: return "kappa";
    case kDiameter: return "d";
    default: return form == DampingForm::Gamma ? "gamma" : "e_n";
  }
}

std::string parameter_unit(int index, DampingForm form) {
  switch (index) {
    case kKappa: return "N/m";
    case kDiameter: return "m";
    default: return form == DampingForm::Gamma ? "kg/s" : "1";
  }
}

}  // namespace sedwave::inversion
