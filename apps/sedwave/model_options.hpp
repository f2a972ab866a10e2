#pragma once
// The command-line options that choose a sediment model and set its parameters, shared by
// `sedwave invert` (start values, bounds, which are free) and `sedwave synthesize` (the truth).
#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/inversion/setup.hpp"

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
  std::string site;  ///< a site file (sedwave/inversion/site_file.hpp): priors and values from what is known
};

using ModelUse = inversion::SetupUse;

/// --model, --set, --kappa, --d, --gamma, --en, --density, the site inputs (--phi, --porosity, --bulk-density,
/// --depth, --effective-pressure, --water-temperature, --salinity); for fits also --fit, --bounds,
/// --*-bounds.
void add_model_options(CLI::App& cmd, ModelOptions& options, ModelUse use);

/// The options as a study's setup (sedwave/inversion/setup.hpp), each value with the option it came
/// from: candidate_of turns it into the model with its parameters and priors. Throws UsageError for a malformed --set or --bounds,
/// or --water-temperature without --salinity.
[[nodiscard]] inversion::ModelSetup setup_of(const ModelOptions& options);

/// inversion::make_candidate, with its SetupError (settings that do not fit together) thrown as the
/// command line's UsageError.
[[nodiscard]] inversion::Candidate candidate_of(const inversion::ModelSetup& setup, ModelUse use = ModelUse::Fit);

}  // namespace sedwave::app
