#include "sedwave/sediment/grain_contact.hpp"

#include <stdexcept>
#include <utility>

namespace sedwave::sediment {

std::vector<Parameter> grain_contact_parameters(DampingForm form) {
  // Ranges are wide on purpose: they refuse nonsense (a negative stiffness), while
  // inversion/plausibility.hpp flags values that are possible but implausible for a sediment.
  std::vector<Parameter> ps{
      {"kappa", "N/m", 6.0e3, 1.0e-3, 1.0e13, true, "normal contact stiffness (spring constant)"},
      {"d", "m", 2.0e-4, 1.0e-8, 1.0, true, "grain diameter: 10 nm (clay) to 1 m (boulders)"},
      {"gamma", "kg/s", 1.0e-2, 1.0e-12, 1.0e8, true, "normal contact dashpot"},
      {"rho_s", "kg/m^3", 2650.0, 1000.0, 8000.0, true, "grain density (quartz 2650)"},
  };
  if (form == DampingForm::Restitution) {
    // e_n < 1 strictly: e_n = 1 means no dashpot, where attenuation (fitted in log space) vanishes.
    ps[GrainContactModel::kDamping] = {"e_n", "1", 0.5, 1.0e-6, 0.999999, true,
                                       "normal restitution coefficient of a collision of two equal grains"};
  }
  return ps;
}

GrainContactModel::GrainContactModel(std::shared_ptr<const forward::DispersionModel> model, DampingForm form)
    : model_(std::move(model)), form_(form), parameters_(grain_contact_parameters(form)) {
  if (!model_) throw std::invalid_argument("GrainContactModel needs a dimensionless model");
}

std::string GrainContactModel::summary() const {
  return "dry granular frame, spring-dashpot contacts, dimensionless model '" + model_->name() +
         "' (docs/physics.md, docs/tables.md)";
}

}  // namespace sedwave::sediment
