#pragma once
// What is known of a seabed, typed: grain size, porosity, depth, water, restitution. A site file
// and the command line's site options fill the same Site; one conversion turns it into a model's
// fixed values and, where the site gives an uncertainty, priors (docs/models/site-inputs.md;
// docs/inversion.md, "Site files"). The physical relations live in sediment/site.hpp.
//
//   site value                      sets       as
//   phi [phi units]                 d          d = 2^-phi mm; with phi_sd: log-normal prior, sd of ln d = phi_sd ln 2
//   porosity [1]                    porosity   the value; with porosity_sd: normal prior
//   bulk_density [kg/m^3]           porosity   the mass balance with the model's rho_s and rho_w
//   depth [m] or effective_pressure kappa      Hertz for quartz at the mean effective pressure (K0 0.5, 9 contacts);
//     [Pa]                                     with kappa_sd_ln: log-normal prior about it
//   water_temperature [deg C] and   rho_w, K_w, eta   sea-water values (EOS-80, Mackenzie 1981, Sharqawy et al. 2010)
//     salinity [ppt]
//   restitution_lower, _upper [1]   e_n        uniform prior (the value: their midpoint)
//
// One set of defaults serves both: where the site does not give a quantity a relation needs, the
// model's own value is used (rho_s, rho_w, porosity), and 2650 kg/m^3, 1025 kg/m^3 and 0.4 where the
// model has none. Hertz needs a grain size the user gave (the site's, or a direct value of d): a
// model's default diameter is not a measurement.
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/inversion/parameters.hpp"
#include "sedwave/inversion/priors.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

/// One measured value and where it was given.
struct SiteValue {
  double value = 0.0;
  std::string origin;  ///< for messages: "--phi", or "site.toml:7: key 'grain_size.phi'"
};

struct Site {
  std::optional<SiteValue> phi, phi_sd;                       ///< mean grain size and its sd [phi units]
  std::optional<SiteValue> porosity, porosity_sd;             ///< [1]
  std::optional<SiteValue> bulk_density;                      ///< wet bulk density [kg/m^3]
  std::optional<SiteValue> depth;                             ///< below the seafloor [m]
  std::optional<SiteValue> effective_pressure;                ///< mean effective pressure [Pa]
  std::optional<SiteValue> kappa_sd_ln;                       ///< sd of ln kappa about Hertz [1]
  std::optional<SiteValue> water_temperature, salinity;       ///< [deg C], [ppt]
  std::optional<SiteValue> restitution_lower, restitution_upper;  ///< [1]
  /// Where the site was given ("site file PATH", "command line"): the source of its priors, and
  /// said after each note except for the command line's.
  std::string source = "site";
  /// A site file describes the seabed for any model: a model without a parameter it sets skips it.
  /// The command line's options are meant for the one model: there that is refused.
  bool skip_missing_parameters = false;
};

/// Two sources set one parameter, or a site value names a parameter the model lacks: how the
/// values were combined, not a value, is wrong (the command line reports it as a usage error).
struct SiteConflict : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// A prior the site gives to a free parameter (its support is set when it is applied: priors.hpp).
struct SitePrior {
  std::string parameter;
  Prior prior;
  std::string origin;  ///< the site value it comes from, for messages
};

/// What a site did to a model's parameters.
struct SiteApplied {
  std::vector<SitePrior> priors;   ///< for free parameters with a site uncertainty
  std::vector<std::string> notes;  ///< one line per conversion: what it set, from what, by which relation
};

/// Parameters already set, each with what set it ("--d", "--set 'd=3e-4'", a site value's origin).
using SetBy = std::map<std::string, std::string>;

/// The one conversion: sets the values of `parameters` (a free parameter with a site prior starts at
/// the prior's median, clamped to its search bounds) and returns the priors. In the order water,
/// grain size, porosity, stiffness, so that Hertz sees the values the site set. A site value for a
/// parameter in `set_by` is refused; those it sets are added there (a second site, applied after,
/// sees them as set: its Hertz uses them). Throws
/// SiteConflict naming the value's origin for a value also given directly or a parameter the model
/// lacks (unless the site skips those), std::invalid_argument for Hertz without a grain size.
[[nodiscard]] SiteApplied apply_site(const Site& site, const sediment::SedimentModel& model,
                                     FitParameters& parameters, SetBy& set_by);

/// The site's priors in place of the defaults in `priors` (one per parameter of `parameters`), each
/// on its parameter's search bounds; throws std::invalid_argument where one cannot lie there.
void apply_site_priors(const FitParameters& parameters, const std::vector<SitePrior>& site_priors,
                       std::vector<Prior>& priors);

}  // namespace sedwave::inversion
