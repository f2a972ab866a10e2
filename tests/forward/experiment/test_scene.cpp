// Scene files: the shipped example parses to the thesis's numbers, and every mistake names the
// file, the line and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <variant>
#include <string>
#include <vector>

#include "sedwave/forward/experiment/scene.hpp"

namespace sedwave::forward::experiment {
namespace {

using namespace channel;  // a scene holds the channel's settings

TEST(Scene, ShippedExampleParses) {
  const ChannelScene s = read_scene(std::string(SEDWAVE_SOURCE_DIR) + "/data/scenes/thesis_w3.toml");
  EXPECT_EQ(s.geometry.n_grains, 1000);
  EXPECT_DOUBLE_EQ(s.geometry.width, 3.0);
  EXPECT_DOUBLE_EQ(s.geometry.sizes.min, 0.8);
  // kn from E = 1000, nu = 2/7 by LAMMPS's formula 4G / (3 (1 - nu)), G = E / (2 (1 + nu)).
  EXPECT_NEAR(std::get<dem::ContactModel<dem::HookeNormal>>(dem::make_contact_model(s.contact)).normal.kn, 4.0 * (1000.0 / (2.0 * (1.0 + 2.0 / 7.0))) / (3.0 * (1.0 - 2.0 / 7.0)), 1e-9);
  EXPECT_DOUBLE_EQ(s.preparation.pressure, 10.0);
  EXPECT_EQ(s.drive.far_end, FarEnd::absorbing);
  EXPECT_DOUBLE_EQ(s.drive.layer_thickness, 1.0);
  EXPECT_FALSE(s.text.empty());
}

TEST(Scene, ShippedLinearExampleParses) {
  const ChannelScene s = read_scene(std::string(SEDWAVE_SOURCE_DIR) + "/data/scenes/linear_w3.toml");
  EXPECT_EQ(s.engine, EngineKind::linear);
  EXPECT_EQ(s.linear.ensemble, 3);
  EXPECT_DOUBLE_EQ(s.linear.refuse_state_changes, 0.1);
  EXPECT_EQ(read_scene(std::string(SEDWAVE_SOURCE_DIR) + "/data/scenes/thesis_w3.toml").engine,
            EngineKind::time_domain);
}

TEST(Scene, EveryEngineNameNamesItsOwnEngine) {
  const std::vector<std::string>& names = engine_names();
  ASSERT_EQ(names.size(), 3u);
  for (std::size_t k = 0; k < names.size(); ++k) EXPECT_EQ(engine_named(names[k]), static_cast<EngineKind>(k));
  EXPECT_EQ(engine_named("long_wavelength"), EngineKind::long_wavelength);
  EXPECT_THROW((void)engine_named("longwavelength"), std::invalid_argument);
  // A scene names an engine that drives its packing; the long-wavelength limit is for tables.
  EXPECT_THROW((void)parse_scene("engine = \"long_wavelength\"\n", "x.toml"), SceneError);
}

TEST(Scene, ContactSelectsEveryKindOfPart) {
  const ChannelScene s = parse_scene("[contact]\nlaw = \"hertz\"\nyoungs_modulus = 1000\ntangential = \"coulomb_tanh\"\n"
                                     "friction = 0.3\ntanh_velocity_scale = 10\nrolling = \"constant_torque\"\n"
                                     "rolling_friction = 0.05\n",
                                     "x.toml");
  EXPECT_EQ(dem::describe(s.contact), "hertz+coulomb_tanh+rolling");
  EXPECT_EQ(s.contact.find("rolling_friction"), 0.05);
}

TEST(Scene, RestitutionInDriveMapsToGammaHat) {
  const ChannelScene s = parse_scene("[contact]\nkn = 726\n[drive]\nrestitution = 0.5\n", "x.toml");
  EXPECT_NEAR(s.drive.gamma_hat, 0.3046976322369708, 1e-12);
}

struct BadScene {
  std::string text;
  std::string expected;  // substring of the message
};
// ctest's names show the expected message, not the struct's bytes (which hold pointers).
void PrintTo(const BadScene& s, std::ostream* os) { *os << s.expected; }

class BadScenes : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadScenes, NameFileLineAndKey) {
  try {
    (void)parse_scene(GetParam().text, "bad.toml");
    FAIL() << "no error for:\n" << GetParam().text;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(GetParam().expected), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Mistakes, BadScenes,
    ::testing::Values(BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 10\nwidht = 3\n", "bad.toml:5: key 'geometry.widht': unknown key"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nomega_hat = \"fast\"\n", "bad.toml:4: key 'drive.omega_hat': must be a number"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nomega_hat = -1\n", "bad.toml:4: key 'drive.omega_hat' = -1: accepted range (0, inf)"},
                      BadScene{"[contact]\nkn = 726\n[drive]\naxis = \"y\"\n", "bad.toml:4: key 'drive.axis': must be one of x, z"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 1.5\n", "bad.toml:4: key 'geometry.grains': must be an integer"},
                      BadScene{"[contact]\nkn = 726\n[geometry.sizes]\nmean = 1\nsdd = 0.1\n", "key 'geometry.sizes.sdd': unknown key"},
                      BadScene{"[contact]\nkn = 726\nyoungs_modulus = 1000\n", "bad.toml:1: [contact]: give exactly one of 'kn' or 'youngs_modulus'"},
                      BadScene{"[contact]\nkn = 726\n[drive]\ngamma_hat = 0.1\nrestitution = 0.9\n", "bad.toml:3: [drive]: give 'gamma_hat' or 'restitution', not both"},
                      BadScene{"[contact]\nkn = [726\n", "bad.toml"},
                      BadScene{"[contakt]\nkn = 726\n", "bad.toml:1: key 'contakt': unknown key"},
                      BadScene{"engine = \"fast\"\n[contact]\nkn = 726\n", "bad.toml:1: key 'engine': must be one of linear, time_domain"},
                      BadScene{"engine = \"linear\"\n[contact]\nkn = 726\n[linear]\nensemble = 0\n", "bad.toml:5: key 'linear.ensemble' = 0: accepted range [1, 10000] packings"},
                      BadScene{"engine = \"linear\"\n[contact]\nkn = 726\n[drive]\nfar_end = \"frozen\"\n", "bad.toml:4: [drive]: far_end: the linear engine"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\nomega_hat = 0.5\n", "bad.toml:3: [drive]: a pulse spans omega_hat_min..omega_hat_max"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\nomega_hat_min = 1\nomega_hat_max = 0.5\n", "[drive]: omega_hat_max must exceed omega_hat_min"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\nfar_end = \"frozen\"\n", "[drive]: far_end: a pulse needs far_end = \"absorbing\""},
                      BadScene{"engine = \"linear\"\n[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\n", "[drive]: signal: the linear engine solves each frequency"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"sweep\"\n", "bad.toml:4: key 'drive.signal': must be one of chirp, pulse, sinusoid"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\nsweep_periods = 5\n", "bad.toml:5: key 'drive.sweep_periods': is for signal = \"chirp\""},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsignal = \"chirp\"\nsweep_periods = 0\n", "bad.toml:5: key 'drive.sweep_periods' = 0: accepted range [1, 1000000] periods of omega_hat_min"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nfar_wall = \"free\"\n", "bad.toml:4: key 'drive.far_wall': must be one of frozen, loaded"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nfar_wall_mass = 3\n", "bad.toml:3: [drive]: far_wall_mass is for far_wall = \"loaded\""},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 1000\n[geometry.periodic_cell]\ngrains = 300\n",
                               "bad.toml:6: key 'geometry.periodic_cell.grains': the channel's 1000 grains must be a whole number of cells of 300"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 900\n[geometry.periodic_cell]\ngrains = 300\nwall_thickness = 1\n",
                               "bad.toml:7: key 'geometry.periodic_cell.wall_thickness': walls thinner than the largest grain"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 900\n[geometry.periodic_cell]\ngrains = 300\n[preparation]\ncompression = \"wall\"\n",
                               "bad.toml:8: key 'preparation.compression': a periodic cell ([geometry.periodic_cell]) is compressed affinely"},
                      BadScene{"[contact]\nkn = 726\ntanh_velocity_scale = 10\n", "bad.toml:3: key 'contact.tanh_velocity_scale': unknown key"},
                      BadScene{"[contact]\nkn = 726\ntangential = \"sticky\"\n", "bad.toml:3: key 'contact.tangential': must be one of coulomb_tanh, mindlin, none, spring_history"},
                      BadScene{"[contact]\nkn = 726\nfriction = -0.5\n", "bad.toml:3: key 'contact.friction' = -0.5: accepted range [0, inf)"},
                      BadScene{"[contact]\nyoungs_modulus = 1000\npoisson_ratio = 1\n", "bad.toml:3: key 'contact.poisson_ratio' = 1: accepted range (-1, 0.5]"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 4294967496\n", "bad.toml:4: key 'geometry.grains' = 4294967496: accepted range [1, 100000000] grains"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\nseed = -1\n", "bad.toml:4: key 'geometry.seed' = -1: accepted range [0, "},
                      BadScene{"[contact]\nkn = 726\n[geometry]\nwidth = 1.1\n", "bad.toml:4: key 'geometry.width': must be at least the largest grain diameter"},
                      BadScene{"[contact]\nkn = 726\n[geometry.sizes]\nmin = 1.1\n", "bad.toml:4: key 'geometry.sizes.min': must not exceed mean"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nperiods = -2\n", "bad.toml:4: key 'drive.periods' = -2: accepted range [0, 1000000] periods"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nabsorbing_fraction = 1.5\n", "bad.toml:4: key 'drive.absorbing_fraction' = 1.5: accepted range (0, 0.9]"},
                      BadScene{"[contact]\nkn = 726\n[drive]\nsamples_per_period = 0\n", "bad.toml:4: key 'drive.samples_per_period' = 0: accepted range [4, 1000000]"},
                      BadScene{"[contact]\nkn = 726\n[drive]\ntime_step_fraction = 50\n", "bad.toml:4: key 'drive.time_step_fraction' = 50: accepted range (0, 0.1]"},
                      BadScene{"[contact]\nkn = 726\n[drive]\ngamma_hat = -0.1\n", "bad.toml:4: key 'drive.gamma_hat' = -0.1: accepted range [0, inf)"},
                      BadScene{"[contact]\nkn = 726\n[drive.measurement]\nskip_layers = -1\n", "bad.toml:4: key 'drive.measurement.skip_layers' = -1: accepted range [0, 1000000] layers"},
                      BadScene{"[contact]\nkn = 726\n[drive.measurement]\nsettle_periods = -3\n", "bad.toml:4: key 'drive.measurement.settle_periods' = -3: accepted range [0, 1000000] periods"},
                      BadScene{"[contact]\nkn = 726\n[geometry]\ngrains = 900\n[geometry.periodic_cell]\ngrains = 300\ncopies = 3\n",
                               "bad.toml:7: key 'geometry.periodic_cell.copies': unknown key"}));

TEST(Scene, FitDepthZeroMeansNoLimit) {
  const ChannelScene scene = parse_scene("[contact]\nkn = 726\n[drive.measurement]\nmax_fit_depth = 0\n", "zero.toml");
  EXPECT_EQ(scene.drive.max_fit_depth, 0.0);
}

TEST(Scene, ChirpDriveReadsItsSweep) {
  const ChannelScene s = parse_scene(
      "[contact]\nkn = 726\n[drive]\nsignal = \"chirp\"\nomega_hat_min = 0.1\nomega_hat_max = 1\nsweep_periods = 12\n",
      "x.toml");
  ASSERT_TRUE(s.drive.pulse.has_value());
  EXPECT_EQ(s.drive.pulse->shape, BroadbandShape::log_chirp);
  EXPECT_EQ(s.drive.pulse->sweep_periods, 12.0);
  const ChannelScene p = parse_scene("[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\n", "x.toml");
  EXPECT_EQ(p.drive.pulse->shape, BroadbandShape::gaussian_pulse);
}

TEST(Scene, CompressionProtocolsAreNamed) {
  EXPECT_EQ(parse_scene("[contact]\nkn = 726\n[preparation]\ncompression = \"pressure\"\n", "x.toml").preparation.compression,
            Compression::pressure);
  EXPECT_EQ(parse_scene("[contact]\nkn = 726\n", "x.toml").preparation.compression, Compression::wall);
}

TEST(Scene, FitDepthLimitsTheFittedLayers) {
  const ChannelScene s =
      parse_scene("[contact]\nkn = 726\n[drive.measurement]\nmax_fit_depth = 22\n", "x.toml");
  EXPECT_EQ(s.drive.max_fit_depth, 22.0);
  EXPECT_EQ(parse_scene("[contact]\nkn = 726\n", "x.toml").drive.max_fit_depth, 0.0);
  EXPECT_TRUE(parse_scene("[contact]\nkn = 726\n[drive.measurement]\ngrain_probes = true\n", "x.toml").drive.grain_probes);
}

TEST(Scene, PeriodicCellTilesTheChannelAndCompressesAffinely) {
  const ChannelScene s = parse_scene(
      "[contact]\nkn = 726\n[geometry]\ngrains = 30000\n[geometry.periodic_cell]\ngrains = 10000\nwall_thickness = 2\n",
      "x.toml");
  ASSERT_TRUE(s.tiling.has_value());
  EXPECT_EQ(s.tiling->cell_grains, 10000);
  EXPECT_EQ(s.tiling->wall_thickness, 2.0);
  EXPECT_EQ(s.preparation.compression, Compression::affine);
  EXPECT_FALSE(parse_scene("[contact]\nkn = 726\n", "x.toml").tiling.has_value());
}

TEST(Scene, LoadedFarWallReadsItsMass) {
  const ChannelScene s =
      parse_scene("[contact]\nkn = 726\n[drive]\nfar_wall = \"loaded\"\nfar_wall_mass = 3.5\n", "x.toml");
  EXPECT_EQ(s.drive.far_wall, FarWall::loaded);
  EXPECT_EQ(s.drive.far_wall_mass, 3.5);
  EXPECT_EQ(parse_scene("[contact]\nkn = 726\n", "x.toml").drive.far_wall, FarWall::frozen);
}

TEST(Scene, PulseDriveReadsItsBand) {
  const ChannelScene s = parse_scene(
      "[contact]\nkn = 726\n[drive]\nsignal = \"pulse\"\nomega_hat_min = 0.1\nomega_hat_max = 1\nfrequencies = 3\n", "x.toml");
  ASSERT_TRUE(s.drive.pulse.has_value());
  const std::vector<double> w = s.drive.pulse->omega_hats();
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[0], 0.1, 1e-15);
  EXPECT_NEAR(w[1], std::sqrt(0.1), 1e-15);
  EXPECT_NEAR(w[2], 1.0, 1e-15);
  EXPECT_FALSE(parse_scene("[contact]\nkn = 726\n", "x.toml").drive.pulse.has_value());
}

}  // namespace
}  // namespace sedwave::forward::experiment
