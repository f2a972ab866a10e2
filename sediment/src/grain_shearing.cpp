#include "sedwave/sediment/grain_shearing.hpp"

#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

std::vector<Parameter> mixture_parameters(const MixtureDefaults& d, const std::string& source) {
  // Ranges refuse nonsense (a porosity of 1 is water, not a sediment), not the implausible.
  return {
      {"porosity", "1", d.porosity, 0.05, 0.99, false, "porosity N, volume fraction of water (" + source + ")"},
      {"rho_s", "kg/m^3", d.grain_density, 1000.0, 8000.0, true, "grain density (" + source + ")"},
      {"rho_w", "kg/m^3", d.water_density, 900.0, 1300.0, false, "pore-water density (" + source + ")"},
      {"K_s", "Pa", d.grain_bulk_modulus, 1.0e9, 1.0e12, true, "bulk modulus of the grain material (" + source + ")"},
      {"K_w", "Pa", d.water_bulk_modulus, 1.0e9, 4.0e9, true, "bulk modulus of the pore water (" + source + ")"},
  };
}

namespace {

/// gamma_p, gamma_s, n: the grain-shearing parameters shared by GS and VGS(λ).
void append_shearing_parameters(std::vector<Parameter>& ps, double gamma_p, double gamma_s, double n,
                                const std::string& source) {
  ps.push_back({"gamma_p", "Pa", gamma_p, 1.0, 1.0e12, true,
                "compressional grain-shearing rigidity coefficient, at T = 1 s (" + source + ")"});
  ps.push_back({"gamma_s", "Pa", gamma_s, 1.0, 1.0e12, true,
                "shear grain-shearing rigidity coefficient, at T = 1 s; enters the compressional wave "
                "only as gamma_p + 4/3 gamma_s (" + source + ")"});
  // 0 < n < 1: n = 0 is a lossless elastic frame, n = 1 a Newtonian viscous one.
  ps.push_back({"n", "1", n, 1.0e-3, 0.99, false, "strain-hardening index (" + source + ")"});
}

}  // namespace

// Buckingham (2005): the reference sediment (porosity 0.377, grain size 1 mm, 0.3 m below the
// seabed) of its comparison with the Hamilton and Richardson sediment data.
DerivedQuantity GrainShearingParameters::wood_speed_quantity() {
  // The poroelastic models' Wood speed, with its plausible range; here it is the wave's f -> 0 limit.
  DerivedQuantity q = poroelastic_derived_quantities().front();
  q.meaning = "Wood's speed c_0 of grains and water as a suspension: the f -> 0 limit of the grain-shearing wave "
              "(Buckingham 2000)";
  return q;
}

GrainShearingModel::GrainShearingModel() : derived_{wood_speed_quantity()} {
  const std::string source = "Buckingham 2005 reference sediment";
  parameters_ = mixture_parameters({0.377, 2730.0, 1005.0, 3.6e10, 2.374e9}, source);
  append_shearing_parameters(parameters_, 3.888e8, 4.588e7, 0.0851, source);
}

std::string GrainShearingModel::summary() const {
  return "grain-shearing (GS) compressional wave, Wood's mixture stiffened by (i omega T)^n intergranular "
         "shearing (Buckingham, JASA 108, 2796 (2000); 117, 137 (2005); docs/models/grain-shearing.md)";
}

// Buckingham (2010), the SAX99 medium sand.
ViscousGrainShearingModel::ViscousGrainShearingModel()
    : derived_{wood_speed_quantity(),
               {"viscous_frequency", "Hz",
                "transition frequency 1/(2 pi tau_p) of VGS(lambda): viscous (alpha ~ f^2) below, GS above "
                "(Buckingham 2007, 2010)",
                0.0, 0.0, "", "", ""},
               {"tau_s", "s",
                "shear viscous time constant, from tau_p: both waves turn viscous at one wavelength "
                "(Buckingham 2010)",
                0.0, 0.0, "", "", ""}} {
  const std::string source = "Buckingham 2010, SAX99 sand";
  parameters_ = mixture_parameters({0.385, 2690.0, 1023.0, 3.2e10, 2.395e9}, source);
  append_shearing_parameters(parameters_, 3.796e8, 1.711e7, 0.0617, source);
  parameters_.push_back({"tau_p", "s", 1.2e-4, 1.0e-9, 1.0e3, true,
                         "compressional viscous time constant; transition frequency 1/(2 pi tau_p) (" + source + ")"});
}

std::string GrainShearingModel::shear_summary() const {
  return "k_s = (omega / sqrt(gamma_s/rho_0)) (i omega T)^(-n/2) (Buckingham 2000, 2005)";
}

std::string ViscousGrainShearingModel::shear_summary() const {
  return "k_s = (omega / sqrt(gamma_s/rho_0)) [(i omega T)^n (1 + 1/(i omega tau_s))^(n-1)]^(-1/2), tau_s from "
         "tau_p by equal transition wavelengths (Buckingham 2010)";
}

std::string ViscousGrainShearingModel::summary() const {
  return "viscous grain-shearing VGS(lambda) compressional wave, grain shearing turning viscous below "
         "1/(2 pi tau_p) (Buckingham, JASA 122, 1486 (2007); 127, 2099 (2010); docs/models/grain-shearing.md)";
}

}  // namespace sedwave::sediment
