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

/// The quantities every model of grains, pore water and Biot's flow derives (in this order):
///   wood_speed      sqrt(K_Wood / rho) [m/s], the speed of the grains and water as a suspension
///                   with no frame (Wood, A Textbook of Sound (1930; 2nd ed. 1941)); the fast wave's
///                   low-frequency limit when the frame is soft (EDFM exactly);
///   biot_frequency  f_c = eta beta / (2 pi rho_w k) [Hz] (biot_characteristic_frequency).
[[nodiscard]] const std::vector<DerivedQuantity>& poroelastic_derived_quantities();

/// The values of poroelastic_derived_quantities() from porosity, rho_s, K_s, rho_w, K_w, eta, k.
template <typename T>
std::vector<T> poroelastic_derived(const T& porosity, const T& grain_density, const T& grain_bulk,
                                   const T& water_density, const T& water_bulk, const T& viscosity,
                                   const T& permeability) {
  return {wood_speed(porosity, grain_density, grain_bulk, water_density, water_bulk),
          biot_characteristic_frequency(viscosity, porosity, water_density, permeability)};
}

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

  /// poroelastic_derived() of the pore-space parameters.
  template <typename T>
  [[nodiscard]] static std::vector<T> pore_space_derived(const T* v) {
    return poroelastic_derived(v[kPorosity], v[kGrainDensity], v[kGrainBulk], v[kWaterDensity], v[kWaterBulk],
                               v[kViscosity], v[kPermeability]);
  }
};

}  // namespace sedwave::sediment
