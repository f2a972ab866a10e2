#include "sedwave/sediment/site.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "sedwave/forward/units.hpp"

namespace sedwave::sediment {
namespace {

enum class Bounds { Closed, Open, LowerOpen };

// Refuses a value outside [lower, upper] (or the open variants), or not finite, naming the quantity,
// its value, the accepted range and the basis of that range.
void require(const char* quantity, double value, double lower, double upper, const char* unit, const char* basis,
             Bounds bounds = Bounds::Closed) {
  const bool lower_ok = bounds == Bounds::Closed ? value >= lower : value > lower;
  const bool upper_ok = bounds == Bounds::Open ? value < upper : value <= upper;
  if (std::isfinite(value) && lower_ok && upper_ok) return;
  std::ostringstream msg;
  msg.precision(10);
  const char* open = bounds == Bounds::Closed ? "[" : "(";
  const char* close = bounds == Bounds::Open ? ")" : "]";
  msg << quantity << " = " << value << (*unit ? " " : "") << unit << " lies outside the accepted range " << open
      << lower << ", " << upper << close << (*unit ? " " : "") << unit << " (" << basis << ")";
  throw std::invalid_argument(msg.str());
}

constexpr double kMinDiameter = 1.0e-8;  // [m], as grain_contact_parameters()'s d
constexpr double kMaxDiameter = 1.0;

void require_diameter(double d) {
  require("grain diameter d", d, kMinDiameter, kMaxDiameter, "m", "10 nm clay to 1 m boulders");
}

void require_porosity(double porosity) {
  require("porosity", porosity, 0.0, 1.0, "", "a volume fraction strictly between 0 and 1", Bounds::Open);
}

void require_densities(double grain_density, double water_density) {
  require("grain density rho_s", grain_density, 1000.0, 8000.0, "kg/m^3", "minerals of sediments; quartz 2650");
  require("water density rho_w", water_density, 900.0, 1300.0, "kg/m^3", "fresh water to brine");
  if (!(grain_density > water_density)) {
    std::ostringstream msg;
    msg << "grain density rho_s = " << grain_density << " kg/m^3 must exceed the water density rho_w = "
        << water_density << " kg/m^3 (grains that float carry no effective stress)";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

// ---- Grain size -----------------------------------------------------------------------------------

double diameter_from_phi(double phi) {
  require("grain size phi", phi, -std::log2(1000.0), std::log2(1.0e5), "",
          "d from 1 m to 10 nm, the grain-contact models' range");
  return 1.0e-3 * std::exp2(-phi);
}

double phi_from_diameter(double diameter) {
  require_diameter(diameter);
  return -std::log2(diameter * 1.0e3);
}

WentworthClass wentworth_class(double diameter) {
  require_diameter(diameter);
  struct Row {
    double lower_mm;
    const char* name;
    const char* major;
  };
  // Lower limits [mm], coarsest first; each class runs from its limit up to the previous one.
  static constexpr std::array<Row, 14> kRows{{
      {256.0, "boulder", "gravel"},
      {64.0, "cobble", "gravel"},
      {4.0, "pebble", "gravel"},
      {2.0, "granule", "gravel"},
      {1.0, "very coarse sand", "sand"},
      {0.5, "coarse sand", "sand"},
      {0.25, "medium sand", "sand"},
      {0.125, "fine sand", "sand"},
      {0.0625, "very fine sand", "sand"},
      {1.0 / 32.0, "coarse silt", "silt"},
      {1.0 / 64.0, "medium silt", "silt"},
      {1.0 / 128.0, "fine silt", "silt"},
      {1.0 / 256.0, "very fine silt", "silt"},
      {0.0, "clay", "clay"},
  }};
  const double mm = diameter * 1.0e3;
  double upper = std::numeric_limits<double>::infinity();
  for (const Row& row : kRows) {
    if (mm >= row.lower_mm) return {row.name, row.major, row.lower_mm, upper};
    upper = row.lower_mm;
  }
  return {"clay", "clay", 0.0, 1.0 / 256.0};  // unreachable: the last lower limit is 0
}

// ---- Porosity and bulk density ----------------------------------------------------------------

double bulk_density(double porosity, double grain_density, double water_density) {
  require_porosity(porosity);
  require_densities(grain_density, water_density);
  return porosity * water_density + (1.0 - porosity) * grain_density;
}

double porosity_from_bulk_density(double bulk, double grain_density, double water_density) {
  require_densities(grain_density, water_density);
  require("bulk density rho_bulk", bulk, water_density, grain_density, "kg/m^3",
          "strictly between the water and the grain density", Bounds::Open);
  return (grain_density - bulk) / (grain_density - water_density);
}

// ---- Effective stress at depth ----------------------------------------------------------------

double effective_vertical_stress(double depth, double porosity, double grain_density, double water_density,
                                 double gravity) {
  require("depth below the seafloor z", depth, 0.0, 1000.0, "m",
          "a column of uniform porosity; deeper, porosity varies with depth");
  require_porosity(porosity);
  require_densities(grain_density, water_density);
  require("gravity g", gravity, 9.76, 9.84, "m/s^2", "Earth's surface, equator to poles");
  return (grain_density - water_density) * (1.0 - porosity) * gravity * depth;
}

double mean_effective_stress(double vertical_stress, double k0) {
  require("vertical effective stress sigma_v'", vertical_stress, 0.0, 1.0e8, "Pa",
          "non-negative, at most 100 MPa");
  require("lateral earth pressure coefficient K0", k0, 0.0, 3.0, "",
          "about 0.4-0.5 in normally consolidated sand (Jaky 1944), above 1 when overconsolidated",
          Bounds::LowerOpen);
  return vertical_stress * (1.0 + 2.0 * k0) / 3.0;
}

double sand_pressure_at_depth(double depth, double porosity, double grain_density, double water_density) {
  return mean_effective_stress(effective_vertical_stress(depth, porosity, grain_density, water_density), kSandK0);
}

// ---- Hertz contact stiffness at pressure --------------------------------------------------------

double contact_force_from_pressure(double pressure, double diameter, double porosity, double coordination) {
  require("effective pressure p", pressure, 0.0, 1.0e8, "Pa", "positive, at most 100 MPa", Bounds::LowerOpen);
  require_diameter(diameter);
  require_porosity(porosity);
  require("coordination number Z", coordination, 4.0, 12.0, "",
          "4: fewest contacts holding a frictional pack; 12: close packing");
  return std::numbers::pi * diameter * diameter * pressure / (coordination * (1.0 - porosity));
}

double hertz_contact_stiffness(const GrainMaterial& material, double diameter, double force) {
  require("Young's modulus E", material.young_modulus, 0.0, 1.0e12, "Pa", "positive, at most 1 TPa",
          Bounds::LowerOpen);
  require("Poisson's ratio nu", material.poisson_ratio, -1.0, 0.5, "", "isotropic elastic solid",
          Bounds::LowerOpen);
  require_diameter(diameter);
  require("contact force F", force, 0.0, 1.0e6, "N", "positive, at most 1 MN", Bounds::LowerOpen);
  const double e_star = forward::hertz_effective_modulus(material.young_modulus, material.poisson_ratio,
                                                         material.young_modulus, material.poisson_ratio);
  const double r_eff = diameter / 4.0;  // two spheres of radius d/2
  return forward::hertz_stiffness(e_star, r_eff, forward::hertz_overlap(e_star, r_eff, force));
}

double hertz_kappa_at_pressure(const GrainMaterial& material, double diameter, double pressure, double porosity,
                               double coordination) {
  return hertz_contact_stiffness(material, diameter,
                                 contact_force_from_pressure(pressure, diameter, porosity, coordination));
}

// ---- Sea water --------------------------------------------------------------------------------

double mackenzie_sound_speed(double temperature, double salinity, double depth) {
  require("temperature T", temperature, 2.0, 30.0, "deg C", "Mackenzie (1981) validity");
  require("salinity S", salinity, 25.0, 40.0, "ppt", "Mackenzie (1981) validity");
  require("depth", depth, 0.0, 8000.0, "m", "Mackenzie (1981) validity");
  const double t = temperature, s = salinity - 35.0, d = depth;
  return 1448.96 + 4.591 * t - 5.304e-2 * t * t + 2.374e-4 * t * t * t + 1.340 * s + 1.630e-2 * d +
         1.675e-7 * d * d - 1.025e-2 * t * s - 7.139e-13 * t * d * d * d;
}

double seawater_density(double temperature, double salinity) {
  require("temperature T", temperature, -2.0, 40.0, "deg C", "EOS-80 one-atmosphere validity");
  require("salinity S", salinity, 0.0, 42.0, "", "EOS-80 one-atmosphere validity (practical salinity)");
  const double t = 1.00024 * temperature;  // ITS-90 to IPTS-68
  const double s = salinity;
  // Standard Mean Ocean Water (Bigg 1967), then the salinity terms of Millero & Poisson (1981).
  const double rho_w = 999.842594 + t * (6.793952e-2 + t * (-9.095290e-3 + t * (1.001685e-4 +
                                                                                 t * (-1.120083e-6 + t * 6.536332e-9))));
  const double a = 8.24493e-1 + t * (-4.0899e-3 + t * (7.6438e-5 + t * (-8.2467e-7 + t * 5.3875e-9)));
  const double b = -5.72466e-3 + t * (1.0227e-4 - t * 1.6546e-6);
  const double c = 4.8314e-4;
  return rho_w + a * s + b * s * std::sqrt(s) + c * s * s;
}

double bulk_modulus(double density, double sound_speed) {
  require("density rho", density, 0.0, 2.0e4, "kg/m^3", "positive, at most 20000", Bounds::LowerOpen);
  require("sound speed c", sound_speed, 0.0, 1.0e4, "m/s", "positive, at most 10 km/s", Bounds::LowerOpen);
  return density * sound_speed * sound_speed;
}

double seawater_bulk_modulus(double temperature, double salinity) {
  const double c = mackenzie_sound_speed(temperature, salinity, 0.0);
  return bulk_modulus(seawater_density(temperature, salinity), c);
}

double seawater_viscosity(double temperature, double salinity) {
  require("temperature T", temperature, 0.0, 180.0, "deg C", "Sharqawy et al. (2010) validity");
  require("salinity S", salinity, 0.0, 150.0, "g/kg", "Sharqawy et al. (2010) validity");
  const double t = temperature;
  const double s = salinity * 1.0e-3;  // kg/kg
  const double mu_w = 4.2844e-5 + 1.0 / (0.157 * (t + 64.993) * (t + 64.993) - 91.296);
  const double a = 1.541 + 1.998e-2 * t - 9.52e-5 * t * t;
  const double b = 7.974 - 7.561e-2 * t + 4.724e-4 * t * t;
  return mu_w * (1.0 + a * s + b * s * s);
}

// ---- Permeability -----------------------------------------------------------------------------

double kozeny_carman_permeability(double diameter, double porosity) {
  require_diameter(diameter);
  require_porosity(porosity);
  return kozeny_carman_formula(diameter, porosity);
}

// ---- Empirical reference curves (Hamilton) ----------------------------------------------------------

namespace {

void require_hamilton_bachman_range(double mz) {
  require("mean grain size Mz", mz, 1.0, 9.0, "phi",
          "the limits of Hamilton & Bachman's (1982) continental-terrace regressions");
}

}  // namespace

double hamilton_bachman_sound_speed(double mz) {
  require_hamilton_bachman_range(mz);
  return 1952.5 - 86.26 * mz + 4.14 * mz * mz;
}

double hamilton_bachman_density(double mz) {
  require_hamilton_bachman_range(mz);
  return 1000.0 * (2.374 - 0.175 * mz + 0.008 * mz * mz);  // the paper's g/cm^3 to kg/m^3
}

double hamilton_attenuation_factor(double mz) {
  require("mean grain size Mz", mz, 0.0, 9.5, "phi", "the limits of Hamilton's (1972) k_p regressions");
  if (mz < 2.6) return 0.4556 + 0.0245 * mz;
  if (mz < 4.5) return 0.1978 + 0.1245 * mz;
  if (mz < 6.0) return 8.0399 - 2.5228 * mz + 0.20098 * mz * mz;
  return 0.9431 - 0.2041 * mz + 0.0117 * mz * mz;
}

}  // namespace sedwave::sediment
