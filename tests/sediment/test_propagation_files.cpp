// The files propagation codes read: the Acoustics Toolbox's own example environment file parses; an
// exported environment's attenuation in each unit is the model's at that frequency by the toolbox's
// own conversions (misc/AttenMod.f90, CRCI, written out here); the .brc phase has BELLHOP's sign
// (its own half-space coefficient, Bellhop/bellhop.f90 Reflect2D, beyond the critical angle); both
// files survive a round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/propagation_files.hpp"
#include "sedwave/sediment/reflection.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::sediment {
namespace {


TEST(ToolboxEnvironment, TheToolboxsPekerisExampleParses) {
  std::ifstream in(std::string(SEDWAVE_SOURCE_DIR) + "/tests/sediment/data/pekeris.env");
  ASSERT_TRUE(in.good());
  const ToolboxEnvironment env = read_toolbox_environment(in, "pekeris.env");
  EXPECT_EQ(env.title, "Pekeris waveguide");
  EXPECT_EQ(env.frequency_hz, 250.0);
  EXPECT_EQ(env.media, 1);
  EXPECT_EQ(env.options, "CVW");
  EXPECT_EQ(env.attenuation_unit(), AttenuationUnit::DbPerWavelength);
  EXPECT_EQ(env.bottom_option, "A");
  EXPECT_EQ(env.halfspace.depth, 100.0);
  EXPECT_EQ(env.halfspace.compressional_speed, 1800.0);
  EXPECT_EQ(env.halfspace.shear_speed, 0.0);
  EXPECT_EQ(env.halfspace.density, 1.8);
  EXPECT_EQ(env.halfspace.compressional_attenuation, 0.5);
  EXPECT_EQ(env.halfspace.shear_attenuation, 0.0);
}

/// The toolbox's conversion of a value in its unit to Np/m (misc/AttenMod.f90, CRCI), written out
/// independently of propagation_files.cpp.
double toolbox_nepers(double value, char unit, double c, double f) {
  switch (unit) {
    case 'N': return value;
    case 'M': return value / 8.6858896;
    case 'F': return value * f / 8685.8896;
    case 'W': return value * f / (8.6858896 * c);
    case 'Q': return 2.0 * std::numbers::pi * f / (2.0 * c * value);
    default: return -1.0;
  }
}

TEST(ToolboxEnvironment, AttenuationInEachUnitIsTheModels) {
  const auto gs = std::make_shared<GrainShearingModel>();
  const double f = 5e3;
  const AcousticMedium m = medium_of({gs, gs->default_values(), 0.0}, f, false, "half-space");
  ASSERT_GT(m.shear_speed, 0.0);
  for (const char letter : {'N', 'M', 'F', 'W', 'Q'}) {
    const AttenuationUnit unit = attenuation_unit_from_letter(letter);
    std::stringstream file;
    write_toolbox_environment(file, toolbox_environment("GS seabed", f, 100.0, m, unit), 1500.0, 1025.0);
    const ToolboxEnvironment env = read_toolbox_environment(file, "written.env");
    EXPECT_EQ(env.options[2], letter);
    const ToolboxHalfspace& h = env.halfspace;
    // The toolbox's 8.6858896 has 8 digits: agreement to 1e-8.
    EXPECT_NEAR(toolbox_nepers(h.compressional_attenuation, letter, h.compressional_speed, f) / m.compressional_attenuation,
                1.0, 1e-8) << letter;
    EXPECT_NEAR(toolbox_nepers(h.shear_attenuation, letter, h.shear_speed, f) / m.shear_attenuation, 1.0, 1e-8)
        << letter;
    EXPECT_NEAR(h.compressional_speed / m.compressional_speed, 1.0, 1e-9);
    EXPECT_NEAR(h.shear_speed / m.shear_speed, 1.0, 1e-9);
    EXPECT_NEAR(h.density * 1000.0 / m.density, 1.0, 1e-9);
    EXPECT_EQ(h.depth, 100.0);
    EXPECT_NEAR(attenuation_from_unit(h.compressional_attenuation, h.compressional_speed, f, unit) /
                    m.compressional_attenuation, 1.0, 1e-9);
  }
}

TEST(ToolboxEnvironment, MalformedFilesAreRefusedWithTheirLine) {
  std::stringstream file("'title'\n250.0\n1\n'CVX'\n");
  try {
    (void)read_toolbox_environment(file, "bad.env");
    FAIL() << "an unknown attenuation unit was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("attenuation unit 'X'"), std::string::npos) << e.what();
  }
  std::stringstream truncated("'title'\n250.0\n1\n'CVW'\n10 0.0 100.0\n0.0 1500.0 /\n");
  try {
    (void)read_toolbox_environment(truncated, "short.env");
    FAIL() << "a truncated file was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("short.env:6"), std::string::npos) << e.what();
  }
}

/// BELLHOP's own coefficient for a fluid half-space (Bellhop/bellhop.f90, Reflect2D, case 'A'),
/// in its convention: kx, kz the water's wavenumbers along and normal to the bottom,
///   kzP = sqrt(kx^2 - (omega/c_P)^2) (its branch: not on the negative imaginary axis),
///   Refl = -(rho_w kzP - i kz rho_b) / (rho_w kzP + i kz rho_b).
std::complex<double> bellhop_halfspace(double c_b, double rho_b, double theta, double f) {
  const double omega = 2.0 * std::numbers::pi * f;
  const double kx = omega * std::cos(theta) / 1500.0, kz = omega * std::sin(theta) / 1500.0;
  std::complex<double> kzp = std::sqrt(std::complex<double>(kx * kx - (omega / c_b) * (omega / c_b), 0.0));
  if (kzp.real() == 0.0 && kzp.imag() < 0.0) kzp = -kzp;
  const std::complex<double> i(0.0, 1.0);
  return -(1000.0 * kzp - i * kz * rho_b) / (1000.0 * kzp + i * kz * rho_b);
}

TEST(ReflectionTable, HasBellhopsPhaseBeyondTheCriticalAngle) {
  const AcousticMedium sand{1700.0, 0.0, 0.0, 0.0, 1900.0};
  const LayeredHalfspace seabed{{1500.0, 0.0, 0.0, 0.0, 1000.0}, {}, sand};
  std::vector<double> degrees, radians;
  for (double d = 1.0; d <= 90.0; d += 1.0) {
    degrees.push_back(d);
    radians.push_back(d * std::numbers::pi / 180.0);
  }
  const std::vector<ReflectionTableRow> rows =
      toolbox_reflection_table(degrees, reflection_coefficients(seabed, radians, 1e3));
  const double critical_deg = std::acos(1500.0 / 1700.0) * 180.0 / std::numbers::pi;
  int total_reflection_rows = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::complex<double> bellhop = bellhop_halfspace(1700.0, 1900.0, radians[k], 1e3);
    EXPECT_NEAR(rows[k].magnitude, std::abs(bellhop), 1e-13) << degrees[k];
    const double wrapped = std::remainder(rows[k].phase_deg - std::arg(bellhop) * 180.0 / std::numbers::pi, 360.0);
    EXPECT_NEAR(wrapped, 0.0, 1e-10) << degrees[k];
    if (degrees[k] < critical_deg) {
      ++total_reflection_rows;
      EXPECT_GT(std::abs(std::remainder(rows[k].phase_deg, 180.0)), 1.0) << "a phase change, not 0 or 180";
    }
  }
  EXPECT_GT(total_reflection_rows, 20);
  // Unwrapped: neighbouring angles' phases differ by less than 180 degrees.
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_LT(std::abs(rows[k].phase_deg - rows[k - 1].phase_deg), 180.0);
}

TEST(ReflectionTable, SurvivesARoundTrip) {
  const std::vector<ReflectionTableRow> rows{{0.0, 1.0, 180.0}, {45.0, 0.95, 175.0}, {90.0, 0.9, 170.0}};
  std::stringstream file;
  write_reflection_table(file, rows);
  const std::vector<ReflectionTableRow> back = read_reflection_table(file, "round.brc");
  ASSERT_EQ(back.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(back[k].grazing_deg, rows[k].grazing_deg);
    EXPECT_EQ(back[k].magnitude, rows[k].magnitude);
    EXPECT_EQ(back[k].phase_deg, rows[k].phase_deg);
  }
  std::stringstream short_file("3\n0 1 180\n");
  EXPECT_THROW((void)read_reflection_table(short_file, "short.brc"), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::sediment
