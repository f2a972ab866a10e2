#pragma once
// The files propagation codes read a seabed from (docs/reflection.md, "Files for propagation codes"):
//
//   BELLHOP / KRAKENC / SCOOTER bottom reflection coefficient file (.brc), the Acoustics Toolbox's
//     "Reflection Coefficient File" (doc/ReflectionCoefficientFile.htm of the Acoustics Toolbox,
//     github.com/oalib-acoustics/Acoustics-Toolbox, 2023-08-16): NTHETA, then one line per angle:
//     grazing angle [deg], |R|, phase [deg]. The toolbox works in e^{+i omega t} (its complex sound
//     speed c + i alpha c^2/omega, misc/AttenMod.f90, and BELLHOP's own half-space coefficient,
//     Bellhop/bellhop.f90 Reflect2D), so its phase is -arg R of reflection.hpp's e^{-i omega t} R;
//     phases are unwrapped along angle, as the toolbox's interpolation assumes.
//   The first six blocks of an Acoustics Toolbox environment file (.env), common to KRAKEN,
//     KRAKENC, SCOOTER, SPARC, BOUNCE and BELLHOP (doc/EnvironmentalFile.html, same version):
//     title, frequency, one isovelocity water medium, the options line whose third letter is the
//     attenuation unit, and the acousto-elastic half-space ('A') line
//       depth [m]  c_p  c_s [m/s]  rho [g/cm^3]  alpha_p  alpha_s /
//     The program-specific blocks that follow (phase-speed limits, ranges, source and receiver
//     depths) are the user's.
#include <complex>
#include <istream>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "sedwave/sediment/reflection.hpp"

namespace sedwave::sediment {

/// The Acoustics Toolbox's attenuation units (options line, third letter; misc/AttenMod.f90 CRCI).
enum class AttenuationUnit {
  NepersPerMetre,     ///< 'N'
  DbPerMetre,         ///< 'M'
  DbPerMetreKhz,      ///< 'F'  dB/(m kHz)
  DbPerWavelength,    ///< 'W'
  QualityFactor,      ///< 'Q'  (0 stands for no loss, as in the toolbox)
};

[[nodiscard]] char attenuation_unit_letter(AttenuationUnit unit);
/// Throws std::invalid_argument for a letter other than N, M, F, W, Q.
[[nodiscard]] AttenuationUnit attenuation_unit_from_letter(char letter);
/// alpha [Np/m] of a wave of phase speed `speed` [m/s] at frequency_hz expressed in `unit`.
[[nodiscard]] double attenuation_in_unit(double alpha_np_per_m, double speed, double frequency_hz,
                                         AttenuationUnit unit);
/// The inverse: a value in `unit` back to Np/m, as the toolbox converts it (CRCI).
[[nodiscard]] double attenuation_from_unit(double value, double speed, double frequency_hz, AttenuationUnit unit);

/// One line of a .brc file.
struct ReflectionTableRow {
  double grazing_deg = 0.0;
  double magnitude = 0.0;
  double phase_deg = 0.0;  ///< the toolbox's phase: -arg R (e^{-i omega t} R), unwrapped
};

/// The rows for grazing angles [deg] (increasing) and R (e^{-i omega t}, reflection.hpp).
[[nodiscard]] std::vector<ReflectionTableRow> toolbox_reflection_table(std::span<const double> grazing_deg,
                                                                       std::span<const std::complex<double>> r);
void write_reflection_table(std::ostream& out, const std::vector<ReflectionTableRow>& rows);
/// Reads a .brc file; throws std::invalid_argument naming `name` and the line for a malformed one.
[[nodiscard]] std::vector<ReflectionTableRow> read_reflection_table(std::istream& in, const std::string& name);

/// The half-space line of an environment file.
struct ToolboxHalfspace {
  double depth = 0.0;               ///< [m]
  double compressional_speed = 0.0; ///< [m/s]
  double shear_speed = 0.0;         ///< [m/s]
  double density = 0.0;            ///< [g/cm^3]
  double compressional_attenuation = 0.0;  ///< in the file's unit
  double shear_attenuation = 0.0;          ///< in the file's unit
};

/// The six common blocks of an environment file, as far as sedwave reads and writes them.
struct ToolboxEnvironment {
  std::string title;
  double frequency_hz = 0.0;
  int media = 0;
  std::string options;         ///< e.g. "CVW"
  std::string bottom_option;   ///< e.g. "A"
  ToolboxHalfspace halfspace;  ///< the bottom half-space ('A')
  [[nodiscard]] AttenuationUnit attenuation_unit() const;
};

/// The environment of water `water_depth` [m] deep over `halfspace` at frequency_hz, attenuations
/// in `unit`.
[[nodiscard]] ToolboxEnvironment toolbox_environment(const std::string& title, double frequency_hz,
                                                     double water_depth, const AcousticMedium& halfspace,
                                                     AttenuationUnit unit);
/// Writes blocks 1-6 with isovelocity water (`water_speed` [m/s], `water_density` [kg/m^3]) and a
/// comment on each line saying what it holds and in which unit.
void write_toolbox_environment(std::ostream& out, const ToolboxEnvironment& env, double water_speed,
                               double water_density);
/// Reads blocks 1-6 (any number of media, their sound-speed profiles skipped; a volume-attenuation
/// line after the options is skipped too) up to the bottom half-space line. Throws
/// std::invalid_argument naming `name`, the line and what was expected.
[[nodiscard]] ToolboxEnvironment read_toolbox_environment(std::istream& in, const std::string& name);

}  // namespace sedwave::sediment
