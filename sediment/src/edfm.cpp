#include "sedwave/sediment/edfm.hpp"

#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

EffectiveDensityFluidModel::EffectiveDensityFluidModel()
    : parameters_{porosity_parameter(),
                  {"rho_s", "kg/m^3", 2650.0, 1000.0, 8000.0, true, "grain density (quartz 2650)"},
                  grain_bulk_parameter(),
                  water_density_parameter(),
                  water_bulk_parameter(),
                  viscosity_parameter(),
                  permeability_parameter(),
                  tortuosity_parameter(),
                  pore_size_parameter()} {}

std::string EffectiveDensityFluidModel::summary() const {
  return "effective density fluid model: Biot with a rigidity-free frame (Williams, JASA 110, 2276, 2001) "
         "(docs/models/poroelastic.md)";
}

}  // namespace sedwave::sediment
