#include "sedwave/inversion/setup.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "sedwave/inversion/site_file.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::inversion {
namespace {

/// "NAME=REST" split at the first '='; throws naming the option and what it expects.
std::pair<std::string, std::string> name_and_rest(const std::string& item, const std::string& option,
                                                  const char* expected) {
  const auto at = item.find('=');
  if (at == std::string::npos || at == 0 || at + 1 == item.size()) {
    throw SetupError(option + " '" + item + "': expected NAME=" + expected);
  }
  return {item.substr(0, at), item.substr(at + 1)};
}

double number_in(const std::string& text, const std::string& item, const std::string& option) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(x)) {
    throw SetupError(option + " '" + item + "': '" + text + "' is not a finite number");
  }
  return x;
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

/// The damping is one parameter, given as gamma or as e_n: settings naming both forms conflict.
bool uses_restitution(const ModelSetup& s) {
  const bool gamma_named = s.names("gamma");
  const bool en_named = s.names("e_n") || names_in_list(s.free, {"en"});
  if (gamma_named && en_named) {
    throw std::invalid_argument(
        "the damping is one parameter, given either as the dashpot gamma (--gamma, --gamma-bounds, --fit gamma) or "
        "as the restitution e_n (--en, --en-bounds, --fit en); these options name both");
  }
  return en_named;
}

/// One parameter given twice (two values, or two sets of bounds) would keep one silently: refused,
/// naming both origins.
template <typename Given>
void refuse_repeated(const std::vector<Given>& given, const char* verb) {
  for (std::size_t i = 0; i < given.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (given[i].parameter == given[j].parameter) {
        throw SetupError(given[j].origin + " and " + given[i].origin + " both " + verb + " " + given[i].parameter +
                         ": give one");
      }
    }
  }
}

/// Refuses a start value or search bound outside the parameter's physical range, naming both.
void check_physical(const ParameterSpec& spec, const sediment::Parameter& range, const std::string& model) {
  const auto outside = [&](double x) { return !(x >= range.lower && x <= range.upper); };
  if (outside(spec.value) || outside(spec.lower) || outside(spec.upper)) {
    std::ostringstream msg;
    msg << "model '" << model << "': " << spec.name << " (value " << spec.value << ", search bounds [" << spec.lower
        << ", " << spec.upper << "]) must lie within its physical range [" << range.lower << ", " << range.upper
        << "] " << range.unit << " (sedwave models)";
    throw std::invalid_argument(msg.str());
  }
}

/// Builds one candidate; the steps run in the order whose first failure a user should hear of.
class Assembly {
 public:
  Assembly(const ModelSetup& setup, SetupUse use) : s_(setup), use_(use) {}

  Candidate run() {
    c_.model = s_.instance ? s_.instance : make_model(s_);
    c_.label = s_.instance ? s_.instance->name() : s_.model;
    select();
    refuse_repeated(values_, "set");
    refuse_repeated(bounds_, "bound");
    c_.parameters = FitParameters(c_.model->parameters());
    if (use_ == SetupUse::Fit) {
      c_.parameters.set_free_from_list(!s_.free.empty() ? s_.free : sediment::typical_free_parameters(*c_.model),
                                       s_.free.empty() ? "" : s_.free_origin);
    }
    for (const GivenBounds& b : bounds_) {
      ParameterSpec& spec = named(b.parameter, b.lookup.empty() ? b.origin : b.lookup);
      spec.lower = b.lower;
      spec.upper = b.upper;
    }
    for (const GivenValue& v : values_) {
      named(v.parameter, v.lookup.empty() ? v.origin : v.lookup).value = v.value;
      c_.given[v.parameter] = v.origin;
    }
    apply_sites();
    if (use_ == SetupUse::Fit) refuse_bounds_on_fixed();
    for (int i = 0; i < c_.parameters.size(); ++i) {
      check_physical(c_.parameters.spec[static_cast<std::size_t>(i)], c_.model->parameters()[static_cast<std::size_t>(i)],
                     c_.model->name());
    }
    c_.parameters.validate();
    c_.priors = default_priors(c_.parameters);
    apply_site_priors(c_.parameters, site_priors_, c_.priors);
    apply_priors(c_.parameters, prior_items(), s_.priors_source, c_.priors);
    return std::move(c_);
  }

  /// The values and bounds this model takes: with shared settings, those naming a parameter it has.
  void select() {
    const auto kept = [&](const std::string& name) { return !s_.shared || c_.model->has_parameter(name); };
    for (const GivenValue& v : s_.values) {
      if (kept(v.parameter)) values_.push_back(v);
    }
    for (const GivenBounds& b : s_.bounds) {
      if (kept(b.parameter)) bounds_.push_back(b);
    }
  }

 private:
  ParameterSpec& named(const std::string& name, const std::string& option) {
    try {
      return c_.parameters.spec[static_cast<std::size_t>(c_.parameters.index_of(name))];
    } catch (const std::invalid_argument& e) {
      throw SetupError(option + ": " + e.what() + " in model '" + c_.model->name() + "'");
    }
  }

  void apply_sites() {
    const auto apply = [&](Site site) {
      site.skip_missing_parameters = site.skip_missing_parameters || s_.shared;
      try {
        SiteApplied applied = apply_site(site, *c_.model, c_.parameters, c_.given);
        c_.notes.insert(c_.notes.end(), applied.notes.begin(), applied.notes.end());
        site_priors_.insert(site_priors_.end(), applied.priors.begin(), applied.priors.end());
      } catch (const SiteConflict& e) {
        throw SetupError(e.what());
      }
    };
    apply(s_.site);
    if (s_.site_file) apply(read_site_file(*s_.site_file));
  }

  /// Search bounds move only a free parameter: on a fixed one they would be ignored.
  void refuse_bounds_on_fixed() const {
    for (const GivenBounds& b : bounds_) {
      for (const ParameterSpec& spec : c_.parameters.spec) {
        if (spec.name == b.parameter && !spec.free) {
          throw SetupError(b.origin + " bounds " + b.parameter + ", which is fixed (--fit " +
                           (s_.free.empty() ? std::string("default: the model's typical set") : "'" + s_.free + "'") +
                           "): name it in --fit, or drop the bounds");
        }
      }
    }
  }

  /// The prior items this model takes: with shared settings, those naming one of its free parameters.
  std::vector<std::string> prior_items() const {
    if (!s_.shared) return s_.priors;
    std::vector<std::string> kept;
    for (const std::string& item : s_.priors) {
      const std::string name = item.substr(0, item.find('='));
      if (!c_.model->has_parameter(name)) continue;
      if (c_.parameters.spec[static_cast<std::size_t>(c_.parameters.index_of(name))].free) kept.push_back(item);
    }
    return kept;
  }

  const ModelSetup& s_;
  SetupUse use_;
  Candidate c_;
  std::vector<GivenValue> values_;
  std::vector<GivenBounds> bounds_;
  std::vector<SitePrior> site_priors_;
};

}  // namespace

void ModelSetup::add_value(const std::string& item, const std::string& option) {
  const auto [name, text] = name_and_rest(item, option, "VALUE");
  values.push_back({name, number_in(text, item, option), option + " '" + item + "'", option});
}

void ModelSetup::add_bounds(const std::string& item, const std::string& option) {
  const auto [name, text] = name_and_rest(item, option, "LO,HI");
  const auto comma = text.find(',');
  if (comma == std::string::npos) throw SetupError(option + " '" + item + "': expected NAME=LO,HI");
  bounds.push_back({name, number_in(text.substr(0, comma), item, option), number_in(text.substr(comma + 1), item, option),
                    option + " '" + item + "'", option});
}

bool ModelSetup::names(const std::string& parameter) const {
  for (const GivenValue& v : values) {
    if (v.parameter == parameter) return true;
  }
  for (const GivenBounds& b : bounds) {
    if (b.parameter == parameter) return true;
  }
  return names_in_list(free, {parameter.c_str()});
}

std::shared_ptr<const sediment::SedimentModel> make_model(const ModelSetup& setup) {
  const sediment::ModelChoices choices{uses_restitution(setup) ? sediment::DampingForm::Restitution
                                                               : sediment::DampingForm::Gamma,
                                       setup.names("permeability") || setup.names("pore_size")};
  return sediment::make_sediment_model(setup.model, choices);
}

Candidate make_candidate(const ModelSetup& setup, SetupUse use) {
  if (!setup.shared || setup.instance) return Assembly(setup, use).run();
  // The choices a model is made with follow from the names its settings use: shared values for
  // another model's parameters must not choose this one's form.
  const auto probe = make_model(setup);
  ModelSetup own = setup;
  std::erase_if(own.values, [&](const GivenValue& v) { return !probe->has_parameter(v.parameter); });
  std::erase_if(own.bounds, [&](const GivenBounds& b) { return !probe->has_parameter(b.parameter); });
  own.instance = make_model(own);
  Candidate candidate = Assembly(own, use).run();
  candidate.label = setup.model;
  return candidate;
}

Candidate make_candidate(const std::string& spec, const Site& site) {
  ModelSetup setup;
  setup.model = spec;
  setup.site = site;
  setup.shared = true;
  return make_candidate(setup);
}

Candidate make_candidate(std::shared_ptr<const sediment::SedimentModel> model, const Site& site) {
  ModelSetup setup;
  setup.instance = std::move(model);
  setup.site = site;
  setup.shared = true;
  return make_candidate(setup);
}

std::vector<std::string> values_not_given(const Candidate& candidate) {
  std::vector<std::string> missing;
  for (const sediment::Parameter& p : candidate.model->parameters()) {
    if (!p.typical && !candidate.given.contains(p.name)) missing.push_back(p.name);
  }
  return missing;
}

}  // namespace sedwave::inversion
