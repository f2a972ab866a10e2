#pragma once
// Site inputs: the quantities a user measures or looks up for a site (grain size in phi, porosity or
// bulk density, depth below the seafloor, water temperature and salinity) converted to the SI
// parameters the sediment models take (grain diameter d, porosity, contact stiffness kappa, water
// density, bulk modulus and viscosity, permeability).
//
// Every function cites its source and refuses an input outside the range in which that source
// holds with std::invalid_argument naming the quantity, its value and the accepted range. The
// manual page is docs/models/site-inputs.md.
#include <string>

namespace sedwave::sediment {

// ---- Grain size -----------------------------------------------------------------------------------
// Krumbein (1934) phi scale: d = 2^(-phi) mm. Accepted: d in [10 nm, 1 m] (the range of the
// grain-contact models' d), i.e. phi in [-log2(1000), log2(1e5)] = [-9.966, 16.61].

/// Grain diameter [m] of Krumbein grain size phi.
[[nodiscard]] double diameter_from_phi(double phi);
/// Krumbein grain size phi of a grain diameter [m].
[[nodiscard]] double phi_from_diameter(double diameter);

/// A class of the Wentworth (1922) grade scale; silt's subclasses as in the scale's later usage
/// (e.g. Folk 1980). A size on a boundary belongs to the coarser class (limits are lower-inclusive).
struct WentworthClass {
  std::string name;   ///< e.g. "medium sand"
  std::string major;  ///< "clay", "silt", "sand" or "gravel"
  double lower_mm;    ///< smallest diameter of the class [mm] (0 for clay)
  double upper_mm;    ///< diameter at which the next coarser class starts [mm] (infinity for boulder)
};

/// The Wentworth class of a grain diameter [m].
[[nodiscard]] WentworthClass wentworth_class(double diameter);

// ---- Porosity and bulk density ----------------------------------------------------------------
// Mass balance of a water-saturated sediment: rho_bulk = beta rho_w + (1 - beta) rho_s
// (e.g. Hamilton 1980, JASA 68, 1313; Jackson & Richardson 2007, High-Frequency Seafloor
// Acoustics, ch. 5). Accepted: porosity in (0, 1), rho_s in [1000, 8000] kg/m^3,
// rho_w in [900, 1300] kg/m^3 (fresh water to brine), rho_s > rho_w.

/// Bulk (wet) density [kg/m^3] of a saturated sediment of this porosity.
[[nodiscard]] double bulk_density(double porosity, double grain_density, double water_density);
/// Porosity of a saturated sediment of this bulk density [kg/m^3] (strictly between rho_w and rho_s).
[[nodiscard]] double porosity_from_bulk_density(double bulk_density, double grain_density, double water_density);

// ---- Effective stress at depth ----------------------------------------------------------------
/// Standard gravity [m/s^2] (CGPM 1901).
inline constexpr double kStandardGravity = 9.80665;

/// Vertical effective (intergranular) stress [Pa] at depth [m] below the seafloor in a sediment of
/// uniform porosity with hydrostatic pore pressure: the buoyant weight of the grains above,
/// sigma_v' = (rho_s - rho_w)(1 - beta) g z (Terzaghi's effective stress; e.g. Jackson & Richardson
/// 2007, ch. 5). Accepted: z in [0, 1000] m (beyond, porosity varies with depth), g in
/// [9.76, 9.84] m/s^2 (Earth's surface), densities and porosity as for bulk_density.
[[nodiscard]] double effective_vertical_stress(double depth, double porosity, double grain_density,
                                               double water_density, double gravity = kStandardGravity);

/// Mean effective stress [Pa] from the vertical one and the coefficient of lateral earth pressure at
/// rest K0: p' = sigma_v' (1 + 2 K0) / 3 (horizontal stresses K0 sigma_v'). Jaky (1944):
/// K0 = 1 - sin(phi') for normally consolidated sand (about 0.4-0.5). Accepted: K0 in (0, 3].
[[nodiscard]] double mean_effective_stress(double vertical_stress, double k0);

/// K0 of a normally consolidated sand: Jaky (1944), 1 - sin(30 deg).
inline constexpr double kSandK0 = 0.5;
/// Coordination number of a dense random sphere pack (Mavko et al. 2009, section 5.4: Z ~ 9 at
/// porosity 0.36).
inline constexpr double kDensePackCoordination = 9.0;

/// Mean effective stress [Pa] at depth [m] below the seafloor in a normally consolidated sand:
/// mean_effective_stress(effective_vertical_stress(depth, ...), kSandK0).
[[nodiscard]] double sand_pressure_at_depth(double depth, double porosity, double grain_density, double water_density);

// ---- Hertz contact stiffness at pressure --------------------------------------------------------
/// An isotropic grain material.
struct GrainMaterial {
  double young_modulus;  ///< E [Pa]
  double poisson_ratio;  ///< nu [-]
};

/// Quartz from Mavko, Mukerji & Dvorkin, The Rock Physics Handbook (2009), table 7.1: K = 37 GPa,
/// G = 44 GPa, so E = 9KG/(3K+G) = 94.5 GPa and nu = (3K-2G)/(2(3K+G)) = 0.074.
inline constexpr GrainMaterial kQuartz{9.45e10, 0.074};

/// Mean normal force [N] per contact in a random pack of equal spheres of diameter d [m], porosity
/// beta and coordination number Z under isotropic effective pressure p [Pa]:
/// F = 4 pi R^2 p / (Z (1 - beta)) = pi d^2 p / (Z (1 - beta)) (Digby 1981, J. Appl. Mech. 48, 803;
/// Walton 1987; Mavko et al. 2009, section 5.4). Accepted: p in (0, 100 MPa], d in [10 nm, 1 m],
/// porosity in (0, 1), Z in [4, 12] (4: the fewest contacts that hold a frictional pack;
/// 12: close packing). A dense random pack has beta ~ 0.36, Z ~ 9 (Mavko et al. 2009).
[[nodiscard]] double contact_force_from_pressure(double pressure, double diameter, double porosity,
                                                 double coordination);

/// Hertz normal tangent stiffness dF/d delta [N/m] of a contact between two equal spheres of
/// diameter d [m] of `material` carrying the normal force F [N]:
/// kappa = 2 E* sqrt(R_eff delta) = (6 E*^2 R_eff F)^(1/3), E* = E / (2 (1 - nu^2)), R_eff = d/4
/// (Johnson 1985, Contact Mechanics, ch. 4). Uses forward/units.hpp's Hertz functions.
/// Accepted: E in (0, 1e12] Pa, nu in (-1, 0.5], d in [10 nm, 1 m], F in (0, 1e6] N.
[[nodiscard]] double hertz_contact_stiffness(const GrainMaterial& material, double diameter, double force);

/// kappa [N/m] of the grains of a random pack at effective pressure p [Pa]:
/// hertz_contact_stiffness(material, d, contact_force_from_pressure(p, d, beta, Z)).
[[nodiscard]] double hertz_kappa_at_pressure(const GrainMaterial& material, double diameter, double pressure,
                                             double porosity, double coordination);

// ---- Sea water --------------------------------------------------------------------------------
/// Sound speed [m/s] in sea water, Mackenzie (1981), JASA 70, 807, nine-term equation, of
/// temperature [deg C], salinity [ppt] and depth [m]. Accepted (validity as stated with the
/// equation by NPL's technical guide on the speed of sound in sea water): T in [2, 30] deg C,
/// S in [25, 40] ppt, depth in [0, 8000] m.
[[nodiscard]] double mackenzie_sound_speed(double temperature, double salinity, double depth);

/// Density [kg/m^3] of sea water at atmospheric pressure, the one-atmosphere International Equation
/// of State of Seawater 1980 (Millero & Poisson 1981; UNESCO Technical Papers in Marine Science 44,
/// Fofonoff & Millard 1983). Temperature on ITS-90 [deg C] (converted to the equation's IPTS-68
/// by T68 = 1.00024 T90), practical salinity. Accepted: T in [-2, 40] deg C, S in [0, 42].
[[nodiscard]] double seawater_density(double temperature, double salinity);

/// Bulk modulus [Pa] of a fluid from its density [kg/m^3] and sound speed [m/s]: K = rho c^2
/// (the adiabatic modulus, the one a sound wave sees). Accepted: rho in (0, 20000], c in (0, 10000].
[[nodiscard]] double bulk_modulus(double density, double sound_speed);

/// Bulk modulus [Pa] of sea water at atmospheric pressure: seawater_density(T, S) times the square
/// of mackenzie_sound_speed(T, S, 0). Accepted: Mackenzie's range, T in [2, 30] deg C, S in [25, 40].
[[nodiscard]] double seawater_bulk_modulus(double temperature, double salinity);

/// Dynamic viscosity [Pa s] of sea water at atmospheric pressure, Sharqawy, Lienhard & Zubair (2010),
/// Desalination and Water Treatment 16, 354, eqs. 22-23 (accuracy 1.5 %):
/// mu = mu_w (1 + A S + B S^2), S in kg/kg. Temperature [deg C], salinity [g/kg].
/// Accepted (the paper's validity): T in [0, 180] deg C, S in [0, 150] g/kg.
[[nodiscard]] double seawater_viscosity(double temperature, double salinity);

// ---- Permeability -----------------------------------------------------------------------------
/// Kozeny-Carman permeability [m^2] of a pack of grains of diameter d [m] and porosity beta:
/// k = d^2 beta^3 / (180 (1 - beta)^2) (Carman 1937, Trans. Inst. Chem. Eng. 15, 150; Bear 1972,
/// Dynamics of Fluids in Porous Media, section 5.10). Meant for well-sorted sands. Accepted: d in [10 nm, 1 m], porosity in (0, 1).
[[nodiscard]] double kozeny_carman_permeability(double diameter, double porosity);

/// The same formula unchecked, on any scalar type (the saturated model evaluates it on Jets).
template <typename T>
T kozeny_carman_formula(const T& diameter, const T& porosity) {
  const T solid = 1.0 - porosity;
  return diameter * diameter * porosity * porosity * porosity / (180.0 * solid * solid);
}

// ---- Empirical reference curves (Hamilton) ----------------------------------------------------------
// Regressions of measured sediment properties on mean grain size Mz [phi], to compare a model's
// prediction with what sediments of that grain size typically show. They are reference curves, not
// models to fit: their scatter (the standard errors below) is the spread of real sediments.

/// Compressional sound speed [m/s] of continental-terrace (shelf and slope) sediments of mean grain
/// size Mz [phi], E. L. Hamilton and R. T. Bachman, J. Acoust. Soc. Am. 72, 1891-1904 (1982),
/// Appendix (p. 1902), environment (T): V_p = 1952.5 - 86.26 Mz + 4.14 Mz^2, standard error of
/// estimate 29 m/s. Laboratory values at 23 deg C and 1 atm. Accepted: Mz in [1, 9] (the paper's
/// limits for (T)).
[[nodiscard]] double hamilton_bachman_sound_speed(double mean_grain_size_phi);

/// Saturated bulk density [kg/m^3] of continental-terrace sediments of mean grain size Mz [phi],
/// Hamilton & Bachman (1982), Appendix (p. 1902), environment (T):
/// rho = 2.374 - 0.175 Mz + 0.008 Mz^2 [g/cm^3], standard error of estimate 0.11 g/cm^3.
/// Accepted: Mz in [1, 9].
[[nodiscard]] double hamilton_bachman_density(double mean_grain_size_phi);

/// Standard errors of estimate printed with the two regressions above.
inline constexpr double kHamiltonBachmanSoundSpeedError = 29.0;  ///< [m/s]
inline constexpr double kHamiltonBachmanDensityError = 110.0;    ///< [kg/m^3]

/// Hamilton's attenuation factor k_p [dB m^-1 kHz^-1] (alpha [dB/m] = k_p f [kHz]) of a sediment of
/// mean grain size Mz [phi], E. L. Hamilton, Geophysics 37, 620-646 (1972), the four regressions of
/// its Fig. 3 (p. 636):
///   0 <= Mz < 2.6:    k_p = 0.4556 + 0.0245 Mz
///   2.6 <= Mz < 4.5:  k_p = 0.1978 + 0.1245 Mz
///   4.5 <= Mz < 6.0:  k_p = 8.0399 - 2.5228 Mz + 0.20098 Mz^2
///   6.0 <= Mz <= 9.5: k_p = 0.9431 - 0.2041 Mz + 0.0117 Mz^2
/// The paper shares each join between two branches (they differ there by < 0.003); a join belongs
/// here to the branch above it, as in the APL-UW TR 9407 handbook (1994), which reproduces these
/// regressions. Accepted: Mz in [0, 9.5] (the paper's limits).
[[nodiscard]] double hamilton_attenuation_factor(double mean_grain_size_phi);

}  // namespace sedwave::sediment
