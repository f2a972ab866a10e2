#pragma once
// The command-line options that choose a sediment model and set its parameters, shared by
// `sedwave invert` (start values, bounds, which are free) and `sedwave synthesize` (the truth).
#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/inversion/parameters.hpp"
#include "sedwave/inversion/site.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::app {

struct ModelOptions {
  std::string model = "lattice";
  std::string fit;  ///< empty: kappa,d,gamma for models with grain contacts; required for the others
  std::optional<double> kappa, diameter, gamma, restitution, density;
  std::vector<double> kappa_bounds, diameter_bounds, gamma_bounds, restitution_bounds;
  std::vector<std::string> set_values;  ///< NAME=VALUE
  std::vector<std::string> set_bounds;  ///< NAME=LO,HI
  /// What users measure at a site, converted to parameters (docs/models/site-inputs.md).
  std::optional<double> phi, porosity, bulk_density, depth, effective_pressure, water_temperature, salinity;
  std::string site;  ///< a site file (site_file.hpp): priors and values from what is known
};

enum class ModelUse { Fit, Truth };

/// --model, --set, --kappa, --d, --gamma, --en, --density, the site inputs (--phi, --porosity, --bulk-density,
/// --depth, --effective-pressure, --water-temperature, --salinity); for fits also --fit, --bounds,
/// --*-bounds.
void add_model_options(CLI::App& cmd, ModelOptions& options, ModelUse use);

/// The model the options name (damping form and permeability mode follow from the options).
[[nodiscard]] std::shared_ptr<const sediment::SedimentModel> make_model(const ModelOptions& options);

/// The model's parameters with the options applied; `site_notes` (if given) receives one line per
/// site input converted (what it set, from what, by which relation), `site_priors` the site file's
/// priors for the free parameters. The site options and the site file fill one typed Site each, and
/// one conversion applies both (sedwave/inversion/site.hpp). Throws UsageError for a name the
/// model does not have, a malformed --set/--bounds or a parameter set twice (directly and from a site
/// input), std::invalid_argument for a value or bound outside the parameter's physical range.
[[nodiscard]] inversion::FitParameters make_parameters(const ModelOptions& options,
                                                       const sediment::SedimentModel& model, ModelUse use,
                                                       std::vector<std::string>* site_notes = nullptr,
                                                       std::vector<inversion::SitePrior>* site_priors = nullptr);

}  // namespace sedwave::app
