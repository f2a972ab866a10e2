#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

// Ranges refuse what is not a sediment's pore fluid or frame; inversion/plausibility.hpp judges
// what is possible but unusual. Fluid density and bulk modulus reach far down so that the
// vacuum-in-the-pores limit (a dry frame) stays inside the accepted range.

const std::vector<DerivedQuantity>& poroelastic_derived_quantities() {
  // wood_speed: Wood's speed of quartz grains in sea water is about 1480-1880 m/s for porosities
  // 0.9-0.25; the range is that of marine sediments (Hamilton 1980, JASA 68, 1313), as for c0.
  // biot_frequency: eta beta / (2 pi rho_w k) for water from gravel (k ~ 1e-7 m^2, beta 0.3: 0.5 Hz)
  // to clay (k ~ 1e-18 m^2, beta 0.8: 1.3e11 Hz).
  static const std::vector<DerivedQuantity> kQuantities{
      {"wood_speed", "m/s",
       "Wood's speed sqrt(K_Wood/rho) of grains and water as a suspension (Wood 1930): the low-frequency speed "
       "without a frame",
       1200.0, 2500.0, "grains and water of marine sediments (Hamilton 1980: 1450-2100 m/s)",
       "slower than any sediment's mixture: the water or grain moduli in the wrong unit, or a porosity beyond any "
       "sediment",
       "faster than any sediment's mixture: the water or grain moduli in the wrong unit"},
      {"biot_frequency", "Hz",
       "Biot's characteristic frequency eta beta/(2 pi rho_w k) (Biot 1956): below it the pore water moves "
       "with the frame",
       0.1, 2.0e11, "permeabilities from gravel (1e-7 m^2) to clay (1e-18 m^2)",
       "a permeability above any gravel's: the fit raised k to move the viscous loss below the data",
       "a permeability below any clay's: the fit lowered k to move the viscous loss above the data"},
  };
  return kQuantities;
}

Parameter porosity_parameter() {
  return {"porosity", "1", 0.40, 0.01, 0.99, false,
          "pore volume fraction; well-sorted sands 0.35-0.45"};
}

Parameter grain_bulk_parameter() {
  return {"K_s", "Pa", 3.6e10, 1.0e8, 1.0e12, true,
          "grain bulk modulus; quartz 36-37 GPa (Mavko, Mukerji & Dvorkin, The Rock Physics Handbook)"};
}

Parameter water_density_parameter() {
  return {"rho_w", "kg/m^3", 1025.0, 1.0e-3, 2000.0, true, "pore water density; sea water 1025"};
}

Parameter water_bulk_parameter() {
  return {"K_w", "Pa", 2.31e9, 1.0e3, 1.0e11, true,
          "pore water bulk modulus; sea water rho c^2 = 1025 kg/m^3 x (1500 m/s)^2"};
}

Parameter viscosity_parameter() {
  return {"eta", "Pa s", 1.0e-3, 1.0e-7, 1.0e4, true,
          "pore water dynamic viscosity; water at 20 C 1.0e-3 (sea water 1.07e-3)"};
}

Parameter permeability_parameter() {
  return {"permeability", "m^2", 4.0e-11, 1.0e-20, 1.0e-5, true,
          "intrinsic permeability; default = Kozeny-Carman d^2 beta^3 / (180 (1 - beta)^2) at d = 0.2 mm, "
          "beta = 0.4"};
}

Parameter tortuosity_parameter() {
  return {"tortuosity", "1", 1.75, 1.0, 10.0, false,
          "tortuosity alpha_inf (Stoll's structure factor), >= 1; default = 1 + (1/beta - 1)/2 for spheres at "
          "beta = 0.4 (Berryman, Appl. Phys. Lett. 37, 382, 1980)"};
}

Parameter pore_size_parameter() {
  return {"pore_size", "m", 4.4e-5, 1.0e-9, 0.1, true,
          "pore-size parameter a of Biot's F(kappa); default = d beta / (3 (1 - beta)) at d = 0.2 mm, "
          "beta = 0.4 (Hovem & Ingram 1979)"};
}

Parameter frame_poisson_parameter() {
  return {"frame_poisson", "1", 0.15, 1.0e-3, 0.49, false,
          "Poisson ratio of the drained frame; between the Hertz-Mindlin no-slip sphere pack (0.008 for "
          "quartz) and the frictionless Walton pack (0.25) (Mavko et al., The Rock Physics Handbook)"};
}

std::vector<Parameter> PoreSpace::pore_space_parameters() {
  return {porosity_parameter(),
          {"rho_s", "kg/m^3", 2650.0, 1000.0, 8000.0, true, "grain density (quartz 2650)"},
          grain_bulk_parameter(),
          water_density_parameter(),
          water_bulk_parameter(),
          viscosity_parameter(),
          permeability_parameter(),
          tortuosity_parameter(),
          pore_size_parameter()};
}

}  // namespace sedwave::sediment
