#pragma once
// Setting up a study: what a user says about one model — which model, which parameters are free,
// values and search bounds, what is known of the site, priors — turned into a model ready to fit,
// sample and rank (a Candidate). Every command (`invert`, `compare`, `synthesize`), the Python
// module and a program of one's own go through this one conversion, so a setting means the same
// everywhere and is refused with the same words.
//
//   ModelSetup setup;
//   setup.model = "biot-stoll";
//   setup.free = "porosity,d";
//   setup.site_file = "data/sites/medium_sand.toml";
//   setup.add_value("rho_s=2650", "--set");          // or setup.values.push_back({"rho_s", 2650, "rho_s"})
//   const Candidate candidate = make_candidate(setup);
//
// Each given value keeps where it was given (an option, an argument, a file's line), and a message
// about it names that origin.
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/inversion/parameters.hpp"
#include "sedwave/inversion/priors.hpp"
#include "sedwave/inversion/site.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

/// A mistake in how the settings were put together — a name the model does not have, one parameter
/// given twice, a malformed NAME=VALUE item, bounds on a fixed parameter — rather than a value out
/// of range (std::invalid_argument). The command line reports it as a usage error.
struct SetupError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// A parameter's value as given.
struct GivenValue {
  std::string parameter;
  double value = 0.0;
  std::string origin;  ///< names it in a message about this value: "--kappa", "--set 'd=3e-4'"
  std::string lookup;  ///< names it in a message about its name; empty: `origin`
};

/// A parameter's search bounds as given [its SI unit].
struct GivenBounds {
  std::string parameter;
  double lower = 0.0;
  double upper = 0.0;
  std::string origin;  ///< "--kappa-bounds", "--bounds 'kappa=1e4,1e8'"
  std::string lookup;  ///< as GivenValue::lookup
};

/// What a setup is for: a fit (the free set matters) or a forward run from known values (all
/// parameters fixed, and those without a typical value must be given).
enum class SetupUse { Fit, Truth };

/// Everything said about one model of a study.
struct ModelSetup {
  std::string model = "lattice";  ///< a catalog specification (sediment/catalog.hpp)
  /// A model object to use instead of `model` (e.g. one of the caller's own); labelled by its name.
  std::shared_ptr<const sediment::SedimentModel> instance;
  std::string free;  ///< comma-separated free parameters; empty: the model's typical set
  std::string free_origin;  ///< names `free` in messages ("--fit 'lattice=kappa,d'"); empty: "--fit 'LIST'"
  std::vector<GivenValue> values;
  std::vector<GivenBounds> bounds;
  /// Measured site values given one by one (origins such as "--phi"): each must name a parameter of
  /// the model unless `shared`.
  Site site;
  std::optional<std::filesystem::path> site_file;  ///< read by read_site_file, applied after `site`
  std::vector<std::string> priors;                 ///< "NAME=KIND:A,B" (priors.hpp)
  std::string priors_source = "command line";      ///< recorded with each of those priors
  /// Settings meant for several models at once (a comparison): a value or prior naming a parameter
  /// this model lacks, or a prior on one it keeps fixed, is skipped instead of refused.
  bool shared = false;

  /// Adds "NAME=VALUE" as given by `option` (e.g. "--set"); throws SetupError naming the option
  /// and the item for a malformed item or a value that is not a finite number.
  void add_value(const std::string& item, const std::string& option);
  /// Adds "NAME=LO,HI" as given by `option` (e.g. "--bounds"), with the same errors.
  void add_bounds(const std::string& item, const std::string& option);
  /// Whether any setting names `parameter` (a value, bounds, or the free list).
  [[nodiscard]] bool names(const std::string& parameter) const;
};

/// One model of a study, ready to fit.
struct Candidate {
  std::string label;  ///< names it in messages and files: the spec it was made from (e.g. "biot-stoll")
  std::shared_ptr<const sediment::SedimentModel> model;
  FitParameters parameters;        ///< free ones marked; values and search bounds set
  std::vector<Prior> priors;       ///< one per parameter of `parameters` (those of the free ones are used)
  std::vector<std::string> notes;  ///< one line per site value converted: what it set, from what, by which relation
  SetBy given;                     ///< the parameters a setting gave a value, each with its origin
};

/// The model a setup names, with the choices its settings imply (the damping as gamma or e_n;
/// permeability given or from Kozeny-Carman). Throws std::invalid_argument for an unknown model or
/// settings naming both damping forms.
[[nodiscard]] std::shared_ptr<const sediment::SedimentModel> make_model(const ModelSetup& setup);

/// The setup turned into a candidate: the model, its free set (for SetupUse::Fit), the given values
/// and bounds, the site's values (the direct ones, then the file's), its priors (log-uniform over the
/// search bounds, then the site's, then `priors`). Throws SetupError for settings that do not fit
/// together (see SetupError) and std::invalid_argument for a value or bound outside a parameter's
/// physical range, and whatever read_site_file throws.
[[nodiscard]] Candidate make_candidate(const ModelSetup& setup, SetupUse use = SetupUse::Fit);

/// The model `spec` names with its typical free set and a site's values and priors (a site value for
/// a parameter the model lacks is skipped): make_candidate of that setup.
[[nodiscard]] Candidate make_candidate(const std::string& spec, const Site& site = {});
/// The same for a model object the caller made (labelled by its name).
[[nodiscard]] Candidate make_candidate(std::shared_ptr<const sediment::SedimentModel> model, const Site& site = {});

/// The parameters of `candidate` that have no typical value (sediment::Parameter::typical) and that
/// no setting gave: a forward run from known values needs them.
[[nodiscard]] std::vector<std::string> values_not_given(const Candidate& candidate);

}  // namespace sedwave::inversion
