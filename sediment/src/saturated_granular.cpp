#include "sedwave/sediment/saturated_granular.hpp"

#include <stdexcept>
#include <utility>

#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

namespace {

std::vector<Parameter> saturated_parameters(DampingForm form, PermeabilityFrom permeability) {
  std::vector<Parameter> ps = grain_contact_parameters(form);
  ps.push_back(porosity_parameter());
  ps.push_back(grain_bulk_parameter());
  ps.push_back(water_density_parameter());
  ps.push_back(water_bulk_parameter());
  ps.push_back(viscosity_parameter());
  ps.push_back(tortuosity_parameter());
  ps.push_back(frame_poisson_parameter());
  if (permeability == PermeabilityFrom::Parameter) {
    ps.push_back(permeability_parameter());
    ps.push_back(pore_size_parameter());
  }
  return ps;
}

}  // namespace

SaturatedGranularModel::SaturatedGranularModel(std::shared_ptr<const forward::DispersionModel> model,
                                               DampingForm form, PermeabilityFrom permeability)
    : model_(std::move(model)),
      form_(form),
      permeability_(permeability),
      parameters_(saturated_parameters(form, permeability)) {
  if (!model_) throw std::invalid_argument("SaturatedGranularModel needs a dimensionless model");
}

std::string SaturatedGranularModel::summary() const {
  const std::string source = permeability_ == PermeabilityFrom::KozenyCarman
                                 ? "permeability and pore size from d and porosity (Kozeny-Carman)"
                                 : "permeability and pore size as parameters";
  return "granular frame '" + model_->name() + "' saturated with water by Biot-Stoll theory (Biot 1956; Stoll 1989); " +
         source + " (docs/models/poroelastic.md)";
}

Wave SaturatedGranularModel::evaluate(std::span<const double> values, double frequency_hz, bool derivatives) const {
  const auto wave_of = [&](const auto* x) {
    using T = std::remove_cvref_t<decltype(*x)>;
    return wave<T>(x, frequency_hz);
  };
  if (permeability_ == PermeabilityFrom::KozenyCarman) {
    return evaluate_with_jets<kDerivedParameters>(name(), values, frequency_hz, derivatives, wave_of);
  }
  return evaluate_with_jets<kAllParameters>(name(), values, frequency_hz, derivatives, wave_of);
}

}  // namespace sedwave::sediment
