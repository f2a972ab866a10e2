#include "sedwave/sediment/catalog.hpp"

#include <stdexcept>

#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/sediment/biot_stoll.hpp"
#include "sedwave/sediment/edfm.hpp"
#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/saturated_granular.hpp"

namespace sedwave::sediment {
namespace {

constexpr std::string_view kSaturated = "saturated-";

std::string accepted() {
  std::string list;
  for (const std::string& name : sediment_model_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

/// forward::make_dispersion_model, its error rephrased with every accepted sediment model.
std::shared_ptr<const forward::DispersionModel> frame_model(const std::string& frame, const std::string& spec) {
  try {
    return forward::make_dispersion_model(frame);
  } catch (const std::invalid_argument& e) {
    if (frame.starts_with("table:")) throw;  // a table's own error (missing file, bad format) says more
    throw std::invalid_argument("unknown model '" + spec + "' (accepted: " + accepted() + ")");
  }
}

}  // namespace

bool is_dry_frame(const std::string& spec) {
  return spec == "continuum" || spec == "lattice" || spec.starts_with("table:");
}

std::shared_ptr<const SedimentModel> make_sediment_model(const std::string& spec, const ModelChoices& choices) {
  if (spec == "biot-stoll") return std::make_shared<const BiotStollModel>();
  if (spec == "edfm") return std::make_shared<const EffectiveDensityFluidModel>();
  if (spec == "grain-shearing") return std::make_shared<const GrainShearingModel>();
  if (spec == "vgs-lambda") return std::make_shared<const ViscousGrainShearingModel>();
  if (spec.starts_with(kSaturated)) {
    const std::string frame = spec.substr(kSaturated.size());
    return std::make_shared<const SaturatedGranularModel>(
        frame_model(frame, spec), choices.damping,
        choices.permeability_given ? PermeabilityFrom::Parameter : PermeabilityFrom::KozenyCarman);
  }
  return std::make_shared<const GrainContactModel>(frame_model(spec, spec), choices.damping);
}

std::vector<std::string> sediment_model_names() {
  std::vector<std::string> names = forward::dispersion_model_names();
  const std::size_t frames = names.size();
  for (std::size_t i = 0; i < frames; ++i) names.push_back(std::string(kSaturated) + names[i]);
  for (const char* name : {"biot-stoll", "edfm", "grain-shearing", "vgs-lambda"}) names.emplace_back(name);
  return names;
}

std::vector<std::shared_ptr<const SedimentModel>> model_examples() {
  // The saturated frame once, in the form that lists permeability and pore_size (which --set accepts).
  return {make_sediment_model("lattice"), make_sediment_model("saturated-lattice", {DampingForm::Gamma, true}),
          make_sediment_model("biot-stoll"),
          make_sediment_model("edfm"), make_sediment_model("grain-shearing"), make_sediment_model("vgs-lambda")};
}

std::string typical_free_parameters(const SedimentModel& model) {
  const std::string name = model.name();
  if (name == "edfm") return "porosity,permeability";
  if (name == "biot-stoll") return "porosity,permeability,delta_b";
  if (name == "grain-shearing") return "porosity,gamma_p,n";
  if (name == "vgs-lambda") return "porosity,gamma_p,tau_p";
  // The grain-contact frames, dry or saturated: the contact's three parameters.
  return "kappa,d," + model.parameters()[GrainContactModel::kDamping].name;
}

std::optional<std::string> sediment_model_file(const std::string& spec) {
  return forward::dispersion_model_file(spec.starts_with(kSaturated) ? spec.substr(kSaturated.size()) : spec);
}

}  // namespace sedwave::sediment
