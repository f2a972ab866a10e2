#pragma once
// Is a fitted result physically plausible? Every value sedwave reports is checked against the
// ranges a seabed sediment can have; one outside them is flagged with its likely cause (a unit
// mix-up, the wrong model, a search bound) instead of being printed as an answer.
//
// A model's derived quantities (c0, kappa/kappa_Hertz, gamma_hat, Wood's speed ...) carry their own
// ranges (sediment::DerivedQuantity, e.g. sediment/src/grain_contact.cpp). The parameters' ranges (SI):
//   grain diameter d          1 um (clay) .. 64 mm (pebble gravel): the Wentworth scale's clay to
//                             gravel classes.
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

#include "sedwave/sediment/grain_contact.hpp"

namespace sedwave::inversion {

/// The grain contact's reference for kappa_over_hertz (sediment/grain_contact.hpp).
using sediment::kReferencePressure;
using sediment::kReferencePorosity;
using sediment::quartz_hertz_kappa;

/// A reported quantity's accepted range.
struct PlausibleRange {
  double lower;
  double upper;
  const char* basis;       ///< where the range comes from
  const char* below_cause;  ///< likely cause of a value below it
  const char* above_cause;  ///< likely cause of a value above it
};

/// The range of a parameter or the sound speed by name (d, e_n, porosity, sound_speed), or nullptr.
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
