#pragma once
// Choosing a sediment model by name, as the command line does: one table of entries, one per model
// (or family of models), that a program may extend with its own (register_model).
//
//   continuum | lattice | table:FILE.h5[?...]         the dry grain-contact frame (forward/ models)
//   saturated-<any of those>                          the frame in Biot's theory with pore water
//   biot-stoll | edfm | grain-shearing | vgs-lambda   closed forms from the literature
//
// A model in the tree is one file (its class), one line in the table (catalog.cpp) and its source
// line in sediment/CMakeLists.txt; a model outside the tree is one register_model call
// (docs/models/adding-a-model.md).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/sediment/grain_contact.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment {

/// Choices a specification leaves open.
struct ModelChoices {
  /// The contact damping of grain-contact models: the dashpot gamma or the restitution e_n.
  DampingForm damping = DampingForm::Gamma;
  /// Saturated models: permeability and pore size as parameters (true) or from d and porosity by
  /// Kozeny-Carman (false).
  bool permeability_given = false;
};

/// One entry of the catalog: a model, or a family of models chosen by a specification's form.
struct CatalogEntry {
  /// The specifications it accepts, one help line each (e.g. "biot-stoll", "table:FILE.h5").
  std::vector<std::string> names;
  /// The model a specification names. Called only for specifications `accepts` takes.
  std::function<std::shared_ptr<const SedimentModel>(const std::string& spec, const ModelChoices& choices)> make;
  /// Whether a specification is this entry's; empty: exactly one of `names`.
  std::function<bool(const std::string& spec)> accepts;
  /// Representative instances for listing parameters (`sedwave models`); empty: make(names[0], {}).
  std::function<std::vector<std::shared_ptr<const SedimentModel>>()> examples;
};

/// Adds a model to the catalog, after the built-in ones: make_sediment_model, sediment_model_names
/// and model_examples then know it, so every command and library study that takes a model by name
/// takes it. Throws std::invalid_argument if one of its names is already taken. Thread-safe.
void register_model(CatalogEntry entry);

/// The short form for a model with one name: register_model({{name}, make}).
void register_model(const std::string& name, std::function<std::shared_ptr<const SedimentModel>()> make);

/// The model a specification names. Throws std::invalid_argument listing the accepted names.
[[nodiscard]] std::shared_ptr<const SedimentModel> make_sediment_model(const std::string& spec,
                                                                       const ModelChoices& choices = {});

/// One line per accepted specification, for help texts.
[[nodiscard]] std::vector<std::string> sediment_model_names();

/// Representative instances of every model family (a table stands for all tables), for listing
/// their parameters (`sedwave models`).
[[nodiscard]] std::vector<std::shared_ptr<const SedimentModel>> model_examples();

/// The file a specification reads (a table), or nothing.
[[nodiscard]] std::optional<std::string> sediment_model_file(const std::string& spec);

/// The parameters a fit frees when the user does not say (`--fit`): the model's own choice
/// (SedimentModel::typical_free_parameters).
[[nodiscard]] inline std::string typical_free_parameters(const SedimentModel& model) {
  return model.typical_free_parameters();
}

}  // namespace sedwave::sediment
