#include "sedwave/sediment/saturated_granular.hpp"

// With permeability from Kozeny-Carman the model has 11 parameters and never reads entries 11 and
// 12 (permeability_of, wave: a run-time branch on permeability_), but GCC's inliner, seeing one
// function body for both counts, warns of those reads in the 11-entry instantiation.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif

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
      parameters_(saturated_parameters(form, permeability)),
      contact_(form, nullptr),
      derived_(contact_.quantities()) {
  if (!model_) throw std::invalid_argument("SaturatedGranularModel needs a dimensionless model");
  const std::vector<DerivedQuantity>& poroelastic = poroelastic_derived_quantities();
  derived_.insert(derived_.end(), poroelastic.begin(), poroelastic.end());
}

std::string SaturatedGranularModel::typical_free_parameters() const {
  // The contact's three parameters, as for the dry frame: the pore water's part is known.
  return "kappa,d," + parameters_[kDamping].name;
}

std::vector<DerivedValue> SaturatedGranularModel::derived_values(std::span<const double> values,
                                                                 bool derivatives) const {
  const auto derived_of = [&](const auto* x) {
    using T = std::remove_cvref_t<decltype(*x)>;
    return derived<T>(x);
  };
  if (permeability_ == PermeabilityFrom::KozenyCarman) {
    return evaluate_derived_with_jets<kDerivedParameters>(name(), values, derivatives, derived_of);
  }
  return evaluate_derived_with_jets<kAllParameters>(name(), values, derivatives, derived_of);
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

Wave SaturatedGranularModel::evaluate_shear(std::span<const double> values, double frequency_hz,
                                            bool derivatives) const {
  const auto wave_of = [&](const auto* x) {
    using T = std::remove_cvref_t<decltype(*x)>;
    return shear_wave<T>(x, frequency_hz);
  };
  const std::string label = name() + " (shear)";
  if (permeability_ == PermeabilityFrom::KozenyCarman) {
    return evaluate_with_jets<kDerivedParameters>(label, values, frequency_hz, derivatives, wave_of);
  }
  return evaluate_with_jets<kAllParameters>(label, values, frequency_hz, derivatives, wave_of);
}

std::string SaturatedGranularModel::shear_summary() const {
  return "Biot's shear wave of the frame shear modulus mu = M_frame (1 - 2 nu_frame) / (2 (1 - nu_frame)), the "
         "dry frame's P-wave modulus split by the frame Poisson ratio nu_frame (a parameter)";
}

std::optional<double> SaturatedGranularModel::bulk_density(std::span<const double> values) const {
  check_values(values);
  return mixture_density(values[kPorosity], values[kGrainDensity], values[kWaterDensity]);
}

}  // namespace sedwave::sediment
