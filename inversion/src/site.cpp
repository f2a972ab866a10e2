#include "sedwave/inversion/site.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "short_number.hpp"
#include "sedwave/sediment/site.hpp"

namespace sedwave::inversion {
namespace {

/// Where a model lacks a quantity a relation needs: quartz sand in sea water.
constexpr double kDefaultPorosity = 0.4;
constexpr double kDefaultGrainDensity = 2650.0;  // [kg/m^3]
constexpr double kDefaultWaterDensity = 1025.0;  // [kg/m^3]

/// Sets parameters of one model from one site, keeping the notes and priors it makes.
class SiteConversion {
 public:
  SiteConversion(const Site& site, const sediment::SedimentModel& model, FitParameters& parameters, SetBy& set_by)
      : site_(site), model_(model), p_(parameters), set_by_(set_by) {}

  /// The parameter `name` for a value from `origin`, or nullptr where the model lacks it and the
  /// site skips such parameters.
  ParameterSpec* target(const std::string& name, const std::string& origin) {
    ParameterSpec* spec = find(name);
    if (!spec) {
      if (site_.skip_missing_parameters) return nullptr;
      throw SiteConflict(origin + ": model '" + model_.name() + "' has no parameter '" + name + "'");
    }
    if (const auto it = set_by_.find(name); it != set_by_.end()) {
      throw SiteConflict(origin + " and " + it->second + " both set " + name + ": give one");
    }
    set_by_[name] = origin;
    return spec;
  }

  /// A value (`note` says from what, starting with its separator): a free parameter with a prior starts at the prior's median, inside its search bounds.
  void set(ParameterSpec& spec, double value, const std::optional<Prior>& prior, const std::string& origin,
           const std::string& note) {
    if (prior && spec.free) {
      spec.value = std::clamp(value, spec.lower, spec.upper);
      Prior typed = *prior;
      typed.source = site_.source;
      applied_.priors.push_back({spec.name, typed, origin});
      notes(spec.name + ": prior " + typed.describe_shape(spec.unit) + note);
    } else {
      spec.value = value;
      notes(spec.name + " = " + short_number(value) + (spec.unit == "1" ? "" : " " + spec.unit) + note);
    }
  }

  void notes(const std::string& line) {
    applied_.notes.push_back(site_.source == "command line" ? line : line + " (" + site_.source + ")");
  }

  /// The pore water's density [kg/m^3]: the model's, else the site water's, else sea water's.
  double water_density() { return value_or("rho_w", water_density_.value_or(kDefaultWaterDensity)); }

  /// The model's value of `name`, or `fallback` where it has none.
  double value_or(const char* name, double fallback) {
    const ParameterSpec* spec = find(name);
    return spec ? spec->value : fallback;
  }

  ParameterSpec* find(const std::string& name) {
    for (ParameterSpec& s : p_.spec) {
      if (s.name == name) return &s;
    }
    return nullptr;
  }

  void water();
  void grain_size();
  void porosity();
  void stiffness();
  void restitution();

  SiteApplied result() { return std::move(applied_); }

 private:
  const Site& site_;
  const sediment::SedimentModel& model_;
  FitParameters& p_;
  SetBy& set_by_;
  SiteApplied applied_;
  std::optional<double> diameter_;  ///< the site's grain size [m], for Hertz
  std::optional<double> porosity_;  ///< the site's porosity, for Hertz (also where the model has none)
  std::optional<double> water_density_;  ///< the site water's density [kg/m^3] (also where the model has none)
};

void SiteConversion::water() {
  const auto& t = site_.water_temperature;
  const auto& s = site_.salinity;
  if (!t && !s) return;
  if (!t || !s) throw std::invalid_argument((t ? t : s)->origin + ": the water temperature and salinity go together");
  const double rho = sediment::seawater_density(t->value, s->value);
  const double k = sediment::seawater_bulk_modulus(t->value, s->value);
  const double eta = sediment::seawater_viscosity(t->value, s->value);
  bool used = false;
  for (const char* name : {"rho_w", "K_w", "eta"}) {
    if (!find(name)) continue;
    ParameterSpec* spec = target(name, t->origin);
    spec->value = std::string(name) == "rho_w" ? rho : std::string(name) == "K_w" ? k : eta;
    used = true;
  }
  water_density_ = rho;
  // A model without pore water still takes the site water's density into the porosity from a bulk
  // density and into the effective stress at depth.
  const bool used_by_site = site_.bulk_density || site_.depth;
  if (!used && (site_.skip_missing_parameters || used_by_site)) {
    if (used_by_site) notes("sea water density " + short_number(rho) + " kg/m^3 (EOS-80) for the site's conversions");
    return;
  }
  if (!used) throw SiteConflict(t->origin + ": model '" + model_.name() + "' has no pore-water parameters");
  notes("sea water at " + short_number(t->value) + " deg C, " + short_number(s->value) +
        " ppt: rho_w " + short_number(rho) +
        " kg/m^3, K_w " + short_number(k) + " Pa (EOS-80, Mackenzie 1981), eta " + short_number(eta) +
        " Pa s (Sharqawy et al. 2010)");
}

void SiteConversion::grain_size() {
  if (!site_.phi) return;
  ParameterSpec* spec = target("d", site_.phi->origin);
  if (!spec) return;
  const double d = sediment::diameter_from_phi(site_.phi->value);
  std::optional<Prior> prior;
  // sd of ln d = phi_sd ln 2, since d = 2^-phi mm.
  if (site_.phi_sd) {
    prior = Prior{.kind = PriorKind::LogNormal, .a = d, .b = site_.phi_sd->value * std::numbers::ln2};
  }
  diameter_ = d;
  set(*spec, d, prior, site_.phi->origin,
      " from phi " + short_number(site_.phi->value) + " (" + sediment::wentworth_class(d).name + ")");
}

void SiteConversion::porosity() {
  const auto& mean = site_.porosity;
  const auto& bulk = site_.bulk_density;
  if (mean && bulk) {
    throw SiteConflict(mean->origin + " and " + bulk->origin + " both give the porosity: give one");
  }
  if (!mean && !bulk) return;
  const SiteValue& given = mean ? *mean : *bulk;
  // The mass balance rho_bulk = beta rho_w + (1 - beta) rho_s with the model's densities (the site's
  // water, once set, is the model's).
  const double beta = mean ? mean->value
                           : sediment::porosity_from_bulk_density(bulk->value,
                                                                  value_or("rho_s", kDefaultGrainDensity),
                                                                  water_density());
  porosity_ = beta;
  // A frame without a porosity parameter (the dry lattice) still takes it into Hertz at depth (the
  // stiffness's note names it).
  if (!find("porosity") && (site_.depth || site_.effective_pressure)) return;
  ParameterSpec* spec = target("porosity", given.origin);
  if (!spec) return;
  std::optional<Prior> prior;
  if (mean && site_.porosity_sd) prior = Prior{.kind = PriorKind::Normal, .a = beta, .b = site_.porosity_sd->value};
  set(*spec, beta, prior, given.origin,
      mean ? std::string(" (the site's porosity)") : " from bulk density " + short_number(bulk->value) + " kg/m^3");
}

void SiteConversion::stiffness() {
  const auto& depth = site_.depth;
  const auto& pressure_given = site_.effective_pressure;
  if (depth && pressure_given) {
    throw SiteConflict(depth->origin + " and " + pressure_given->origin + " both set the pressure: give one");
  }
  if (!depth && !pressure_given) return;
  const SiteValue& given = depth ? *depth : *pressure_given;
  ParameterSpec* spec = target("kappa", given.origin);
  if (!spec) return;
  if (!set_by_.count("d")) {
    throw std::invalid_argument(given.origin +
                                ": the Hertz stiffness needs the grain size: give it in the site (grain_size.phi, "
                                "--phi) or directly (--d, --set d=VALUE)");
  }
  // The site's own grain size and porosity where it gives them, else the model's (a direct value).
  const double d = diameter_ ? *diameter_ : value_or("d", 0.0);
  const double beta = porosity_ ? *porosity_ : value_or("porosity", kDefaultPorosity);
  const double pressure =
      depth ? sediment::sand_pressure_at_depth(depth->value, beta, value_or("rho_s", kDefaultGrainDensity),
                                               water_density())
            : pressure_given->value;
  const double kappa =
      sediment::hertz_kappa_at_pressure(sediment::kQuartz, d, pressure, beta, sediment::kDensePackCoordination);
  std::optional<Prior> prior;
  if (site_.kappa_sd_ln) prior = Prior{.kind = PriorKind::LogNormal, .a = kappa, .b = site_.kappa_sd_ln->value};
  set(*spec, kappa, prior, given.origin,
      ": Hertz, quartz grains of d = " + short_number(d) + " m at " + short_number(pressure) +
          " Pa mean effective pressure" +
          (depth ? " (" + short_number(depth->value) + " m below the seafloor, K0 0.5)" : std::string()) + ", porosity " +
          short_number(beta) + ", 9 contacts per grain");
}

void SiteConversion::restitution() {
  const auto& lo = site_.restitution_lower;
  const auto& hi = site_.restitution_upper;
  if (!lo && !hi) return;
  if (!lo || !hi) throw std::invalid_argument((lo ? lo : hi)->origin + ": the restitution range needs both ends");
  if (!(hi->value > lo->value)) throw std::invalid_argument(hi->origin + ": must exceed " + lo->origin);
  ParameterSpec* spec = target("e_n", lo->origin);
  if (!spec) return;
  set(*spec, 0.5 * (lo->value + hi->value), Prior{.kind = PriorKind::Uniform, .a = lo->value, .b = hi->value},
      lo->origin,
      " (middle of the site's restitution range " + short_number(lo->value) + " .. " + short_number(hi->value) + ")");
}

}  // namespace

SiteApplied apply_site(const Site& site, const sediment::SedimentModel& model, FitParameters& parameters,
                       SetBy& set_by) {
  SiteConversion conversion(site, model, parameters, set_by);
  // Water first: the porosity from a bulk density and the effective stress at depth use its density.
  conversion.water();
  conversion.grain_size();
  conversion.porosity();
  conversion.stiffness();
  conversion.restitution();
  return conversion.result();
}

void apply_site_priors(const FitParameters& parameters, const std::vector<SitePrior>& site_priors,
                       std::vector<Prior>& priors) {
  for (const SitePrior& s : site_priors) {
    const int i = parameters.index_of(s.parameter);
    const ParameterSpec& spec = parameters.spec[static_cast<std::size_t>(i)];
    if (!spec.free) throw std::invalid_argument(s.origin + ": a prior on " + s.parameter + ", which is fixed");
    Prior p = s.prior;
    p.lower = spec.lower;
    p.upper = spec.upper;
    check_prior(p, spec, s.origin + ": prior on " + s.parameter + ": ");
    priors[static_cast<std::size_t>(i)] = p;
  }
}

}  // namespace sedwave::inversion
