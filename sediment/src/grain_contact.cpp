#include "sedwave/sediment/grain_contact.hpp"

#include <stdexcept>
#include <utility>

namespace sedwave::sediment {

std::vector<Parameter> grain_contact_parameters(DampingForm form) {
  // A grain contact's stiffness, size and damping have defaults only to start a search from: no one
  // value stands for sandy sediments, so a forward run must be given them (`typical` false).
  // Ranges are wide on purpose: they refuse nonsense (a negative stiffness), while
  // inversion/plausibility.hpp flags values that are possible but implausible for a sediment.
  std::vector<Parameter> ps{
      {"kappa", "N/m", 6.0e3, 1.0e-3, 1.0e13, true, "normal contact stiffness (spring constant)", false},
      {"d", "m", 2.0e-4, 1.0e-8, 1.0, true, "grain diameter: 10 nm (clay) to 1 m (boulders)", false},
      {"gamma", "kg/s", 1.0e-2, 1.0e-12, 1.0e8, true, "normal contact dashpot", false},
      {"rho_s", "kg/m^3", 2650.0, 1000.0, 8000.0, true, "grain density (quartz 2650)"},
  };
  if (form == DampingForm::Restitution) {
    // e_n < 1 strictly: e_n = 1 means no dashpot, where attenuation (fitted in log space) vanishes.
    ps[GrainContactModel::kDamping] = {"e_n", "1", 0.5, 1.0e-6, 0.999999, true,
                                       "normal restitution coefficient of a collision of two equal grains", false};
  }
  return ps;
}

double quartz_hertz_kappa(double diameter, double pressure) {
  return hertz_kappa_at_pressure(kQuartz, diameter, pressure, kReferencePorosity, kDensePackCoordination);
}

GrainContactDerived::GrainContactDerived(DampingForm form, const forward::DispersionModel* dry_frame)
    : form_(form), dry_frame_(dry_frame) {
  // Plausible ranges (SI):
  //   c0 1200 .. 2500 m/s: unconsolidated, water-saturated marine sediments (Hamilton 1980, JASA 68,
  //     1313: about 1450-2100 m/s from muds to gravels), widened for gassy muds and coarse gravels.
  //   kappa / kappa_Hertz 0.46 .. 10: the Hertz stiffness of quartz contacts at confining pressures
  //     1 kPa .. 10 MPa relative to its value at 10 kPa; kappa_Hertz grows as P^(1/3), so the range
  //     is (0.1)^(1/3) .. (1000)^(1/3).
  //   gamma_hat 1e-3 .. 1e3: from nearly elastic contacts (e_n = 0.998) to the heavy overdamping
  //     that sediment attenuation needs in the chain model.
  if (dry_frame_) {
    quantities_.push_back(
        {"c0", "m/s", "low-frequency (f -> 0) sound speed of the model", 1200.0, 2500.0,
         "water-saturated marine sediments (Hamilton 1980: 1450-2100 m/s)",
         "too slow for a sediment: frequencies given in kHz but read as Hz (or a sound-speed ratio read as m/s)?",
         "too fast for a sediment: frequencies in Hz read as kHz, a wrong sound-speed unit, or the wrong model"});
  }
  quantities_.push_back({"tau", "s", "relaxation time gamma/kappa of a contact", 0.0, 0.0, "", "", ""});
  quantities_.push_back({"f_star", "Hz",
                         "crossover frequency 1/(2 pi tau) where attenuation bends from f^2 to f^(1/2)", 0.0, 0.0,
                         "", "", ""});
  quantities_.push_back(
      {"gamma_hat", "1", "dimensionless dashpot gamma/sqrt(kappa m)", 1e-3, 1e3,
       "nearly elastic contacts (e_n 0.998) to the overdamping sediment attenuation needs",
       "contacts almost without loss: attenuation in the wrong unit (Np vs dB), or the wrong model",
       "a dashpot beyond any contact: attenuation in the wrong unit, or loss the model puts in the contacts "
       "that belongs elsewhere"});
  quantities_.push_back(
      {"kappa_over_hertz", "1", "kappa over the Hertz stiffness of quartz grains of diameter d at 10 kPa", 0.46, 10.0,
       "Hertz stiffness of quartz contacts at 1 kPa .. 10 MPa, relative to 10 kPa",
       "softer than a Hertz contact at 1 kPa: a unit mix-up, or d and kappa traded along an unseen direction",
       "stiffer than a Hertz contact at 10 MPa: the contacts carry stiffness that belongs elsewhere (in a "
       "water-saturated sediment the pore water's; a dry-frame model must put it in kappa), or d and kappa "
       "traded along an unseen direction"});
}

GrainContactModel::GrainContactModel(std::shared_ptr<const forward::DispersionModel> model, DampingForm form)
    : model_(std::move(model)),
      form_(form),
      parameters_(grain_contact_parameters(form)),
      derived_(form, model_.get()) {
  if (!model_) throw std::invalid_argument("GrainContactModel needs a dimensionless model");
}

std::string GrainContactModel::typical_free_parameters() const {
  // The contact's three parameters; the grain density is known well enough to stay fixed.
  return "kappa,d," + parameters_[kDamping].name;
}

std::optional<DimensionlessWave> GrainContactModel::dimensionless_wave(std::span<const double> values,
                                                                       double frequency_hz) const {
  const FrameWave<double> h =
      frame_wave(*model_, form_, values[kKappa], values[kDiameter], values[kDamping], values[kGrainDensity],
                 frequency_hz);
  return DimensionlessWave{h.omega_hat, h.gamma_hat, h.hat.alpha_hat, h.hat.c_hat};
}

std::string GrainContactModel::summary() const {
  return "dry granular frame, spring-dashpot contacts, dimensionless model '" + model_->name() +
         "' (docs/physics.md, docs/tables.md)";
}

}  // namespace sedwave::sediment
