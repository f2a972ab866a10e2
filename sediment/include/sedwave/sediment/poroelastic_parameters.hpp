#pragma once
// The parameters the poroelastic models share (saturated granular, EDFM, Biot-Stoll): names,
// SI units, defaults for quartz sand in sea water, physical ranges and sources, in one place so
// that every model names and bounds them the same way.
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment {

/// beta [1]: pore volume fraction.
[[nodiscard]] Parameter porosity_parameter();
/// K_s [Pa]: bulk modulus of the grain material.
[[nodiscard]] Parameter grain_bulk_parameter();
/// rho_w [kg/m^3]: pore water density.
[[nodiscard]] Parameter water_density_parameter();
/// K_w [Pa]: pore water bulk modulus.
[[nodiscard]] Parameter water_bulk_parameter();
/// eta [Pa s]: pore water dynamic viscosity.
[[nodiscard]] Parameter viscosity_parameter();
/// k [m^2]: intrinsic permeability.
[[nodiscard]] Parameter permeability_parameter();
/// alpha_inf [1]: tortuosity (Stoll's structure factor).
[[nodiscard]] Parameter tortuosity_parameter();
/// a [m]: pore-size parameter of Biot's viscous correction.
[[nodiscard]] Parameter pore_size_parameter();
/// nu_frame [1]: Poisson ratio of the drained frame.
[[nodiscard]] Parameter frame_poisson_parameter();

}  // namespace sedwave::sediment
