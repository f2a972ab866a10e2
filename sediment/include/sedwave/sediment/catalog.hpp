#pragma once
// Choosing a sediment model by name, as the command line does.
//
//   continuum | lattice | table:FILE.h5[?...]         the dry grain-contact frame (forward/ models)
//   saturated-<any of those>                          the frame in Biot's theory with pore water
//   biot-stoll | edfm | grain-shearing | vgs-lambda   closed forms from the literature
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

/// The parameters a fit frees when the user does not say (`--fit`): those that sandy-site data over
/// 50 Hz - 100 kHz can inform and that the model's family is meant to explain. The grain contact's
/// kappa, d and damping for the dry and the saturated frame; porosity and permeability for EDFM,
/// with the frame's decrement for Biot-Stoll; porosity and the shearing coefficients for GS and VGS.
[[nodiscard]] std::string typical_free_parameters(const SedimentModel& model);

/// True for the dry grain-contact frame's specifications (continuum, lattice, table:...).
[[nodiscard]] bool is_dry_frame(const std::string& spec);

}  // namespace sedwave::sediment
