#include "sedwave/sediment/edfm.hpp"

#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

EffectiveDensityFluidModel::EffectiveDensityFluidModel() : parameters_(pore_space_parameters()) {}

std::string EffectiveDensityFluidModel::summary() const {
  return "effective density fluid model: Biot with a rigidity-free frame (Williams, JASA 110, 2276, 2001) "
         "(docs/models/poroelastic.md)";
}

}  // namespace sedwave::sediment
