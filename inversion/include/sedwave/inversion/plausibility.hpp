#pragma once
// Is a fitted result physically plausible? Every value sedwave reports is checked against the
// ranges a seabed sediment can have; one outside them is flagged with its likely cause (a unit
// mix-up, the wrong model, a search bound) instead of being printed as an answer.
//
// Ranges (SI):
//   grain diameter d          1 um (clay) .. 64 mm (pebble gravel): the Wentworth scale's clay to
//                             gravel classes.
//   low-frequency speed c0    1200 .. 2500 m/s: unconsolidated, water-saturated marine sediments
//                             (Hamilton 1980, JASA 68, 1313: about 1450-2100 m/s from muds to
//                             gravels), widened for gassy muds and coarse gravels.
//   kappa / kappa_Hertz       0.46 .. 10: the Hertz stiffness of a contact between two equal quartz
//                             grains of diameter d at confining pressures 1 kPa .. 10 MPa, relative
//                             to its value at 10 kPa (about 1 m below the seafloor); kappa_Hertz
//                             grows as P^(1/3), so the range is (0.1)^(1/3) .. (1000)^(1/3).
//   gamma_hat                 1e-3 .. 1e3: from nearly elastic contacts (e_n = 0.998) to the heavy
//                             overdamping that sediment attenuation needs in the chain model.
//   e_n                       (0, 1].
//   sound_speed               100 .. 2e4 m/s at any frequency (synthetic data): no sediment is slower
//                             than a gassy mud or faster than the minerals it is made of; a
//                             dispersive model may exceed c0's range at high frequency, not this.
//   porosity                  0.25 .. 0.9: marine sediments (Hamilton 1980, JASA 68, 1313: sands
//                             0.37-0.47, silts and clays up to 0.85); and for sand-sized grains
//                             (d >= 62.5 um, Wentworth) at most 0.6, since a sand that loose does
//                             not support itself.
#include <string>
#include <vector>

namespace sedwave::inversion {

/// Effective pressure at which kappa is compared with Hertz: about 1 m below the seafloor in sand
/// ((rho_bulk - rho_water) g z = (2000 - 1025) 9.81 1 = 9.6 kPa).
inline constexpr double kReferencePressure = 1.0e4;  ///< [Pa]
/// Porosity of the reference pack: a medium sand (Hamilton 1980: sands 0.37-0.47).
inline constexpr double kReferencePorosity = 0.38;

/// Hertz contact stiffness [N/m] of the quartz grains (sediment::kQuartz) of diameter d [m] of a
/// dense random pack (porosity kReferencePorosity, coordination sediment::kDensePackCoordination)
/// at effective pressure P [Pa]: the same relation as the site inputs' kappa prior
/// (sediment::hertz_kappa_at_pressure), so kappa_over_hertz and a site's kappa prior agree.
[[nodiscard]] double quartz_hertz_kappa(double diameter, double pressure = kReferencePressure);

/// A reported quantity's accepted range.
struct PlausibleRange {
  double lower;
  double upper;
  const char* basis;       ///< where the range comes from
  const char* below_cause;  ///< likely cause of a value below it
  const char* above_cause;  ///< likely cause of a value above it
};

/// The range of a reported quantity by name (d, c0, kappa_over_hertz, gamma_hat, e_n, porosity,
/// sound_speed), or nullptr.
[[nodiscard]] const PlausibleRange* plausible_range(const std::string& quantity);

/// Largest porosity of a sand (d >= 62.5 um) that the joint check accepts.
inline constexpr double kLoosestSandPorosity = 0.6;
inline constexpr double kSandDiameter = 62.5e-6;  ///< [m], Wentworth's silt-sand boundary

/// One flagged result.
struct PlausibilityFlag {
  std::string quantity;
  std::string message;  ///< what is wrong, the accepted range and the likely cause
};

}  // namespace sedwave::inversion
