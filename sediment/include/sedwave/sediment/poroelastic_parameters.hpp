#pragma once
// The parameters the poroelastic models share (saturated granular, EDFM, Biot-Stoll): names,
// SI units, defaults for quartz sand in sea water, physical ranges and sources, in one place so
// that every model names and bounds them the same way.
#include <vector>

#include "sedwave/sediment/biot.hpp"
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

/// The pore space of a model whose frame is given by moduli (EDFM, Biot-Stoll): its first nine
/// parameters. Such a model derives from PoreSpace for the names of their indices.
struct PoreSpace {
  enum PoreSpaceIndex : int {
    kPorosity = 0,
    kGrainDensity = 1,
    kGrainBulk = 2,
    kWaterDensity = 3,
    kWaterBulk = 4,
    kViscosity = 5,
    kPermeability = 6,
    kTortuosity = 7,
    kPoreSize = 8,
    kPoreSpaceParameters = 9,
  };

  /// porosity, rho_s, K_s, rho_w, K_w, eta, permeability, tortuosity, pore_size, in index order.
  [[nodiscard]] static std::vector<Parameter> pore_space_parameters();

  /// Biot's medium from the pore-space parameters v[0 .. 9) and the frame's complex moduli.
  template <typename T>
  [[nodiscard]] static BiotMedium<T> pore_space_medium(const T* v, const Complex<T>& frame_bulk,
                                                       const Complex<T>& frame_shear) {
    return {frame_bulk,    frame_shear,   v[kPorosity],     v[kGrainDensity], v[kGrainBulk], v[kWaterDensity],
            v[kWaterBulk], v[kViscosity], v[kPermeability], v[kTortuosity],   v[kPoreSize]};
  }
};

}  // namespace sedwave::sediment
