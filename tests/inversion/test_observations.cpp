// Tests of the observation readers: unit conversions against hand-computed values, every class of
// bad input (exception type, line, column, field and reason), and the shipped data files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/inversion/observations.hpp"

namespace sedwave::inversion {
namespace {

namespace fs = std::filesystem;

// Hand-computed with ln(10) = 2.302585092994046: 1 dB = ln(10)/20 Np.
constexpr double kNpPerDb = 0.11512925464970229;
constexpr std::string_view kHeader = "quantity,frequency,frequency_unit,value,value_unit,sigma\n";

/// Relative comparison for converted values (a few ulps of rounding in the conversion chain).
void expect_rel_near(double actual, double expected, double tolerance = 1e-13) {
  EXPECT_NEAR(actual, expected, tolerance * std::abs(expected)) << "expected " << expected;
}

/// Each test gets its own fresh directory under the system temporary directory.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device random;
    const auto base = fs::temp_directory_path();
    do {
      dir_ = base / ("sedwave_test_observations_" + std::to_string(random()) + std::to_string(random()));
    } while (!fs::create_directory(dir_));
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  [[nodiscard]] fs::path write(const std::string& name, std::string_view content) const {
    const auto path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out << content;
    return path;
  }

 private:
  fs::path dir_;
};

/// Runs `read` and returns the InputError it must throw.
template <typename Read>
InputError input_error(Read&& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return {"", 0, 0, "", "none thrown"};
}

void expect_error(const InputError& error, int line, int column, std::string_view field,
                  std::string_view reason) {
  EXPECT_EQ(error.line(), line) << error.what();
  EXPECT_EQ(error.column(), column) << error.what();
  EXPECT_EQ(error.field(), field) << error.what();
  EXPECT_NE(std::string_view(error.what()).find(reason), std::string_view::npos)
      << "message '" << error.what() << "' lacks '" << reason << "'";
}

ReadOptions speeds(std::optional<double> water, std::optional<double> sediment = std::nullopt) {
  ReadOptions options;
  options.water_sound_speed = water;
  options.sediment_sound_speed = sediment;
  return options;
}

Observation observation(Quantity quantity, double frequency_hz, double value) {
  Observation obs;
  obs.quantity = quantity;
  obs.frequency_hz = frequency_hz;
  obs.value = value;
  return obs;
}

// ---- Conversion functions -----------------------------------------------------------------------

TEST(UnitConversion, FrequencyToHz) {
  EXPECT_DOUBLE_EQ(frequency_to_hz(250.0, "Hz"), 250.0);
  EXPECT_DOUBLE_EQ(frequency_to_hz(2.5, "kHz"), 2500.0);
  EXPECT_DOUBLE_EQ(frequency_to_hz(0.002, "MHz"), 2000.0);
  EXPECT_THROW((void)frequency_to_hz(1.0, "khz"), std::invalid_argument);
}

TEST(UnitConversion, AttenuationToNeperPerMetre) {
  EXPECT_DOUBLE_EQ(attenuation_to_np_per_m(0.25, "Np/m", 100.0, std::nullopt), 0.25);
  expect_rel_near(attenuation_to_np_per_m(2.0, "dB/m", 100.0, std::nullopt), 0.23025850929940458);
  // k-value: 0.37 dB/m/kHz at 2 kHz is 0.74 dB/m.
  expect_rel_near(attenuation_to_np_per_m(0.37, "dB/m/kHz", 2000.0, std::nullopt), 0.08519564844077969);
  // 0.5 dB per wavelength at 1 kHz in 1600 m/s sediment (wavelength 1.6 m) is 0.3125 dB/m.
  expect_rel_near(attenuation_to_np_per_m(0.5, "dB/lambda", 1000.0, 1600.0), 0.03597789207803197);
  expect_rel_near(attenuation_to_np_per_m(0.5, "dB/λ", 1000.0, 1600.0), 0.03597789207803197);
  EXPECT_THROW((void)attenuation_to_np_per_m(0.5, "dB/lambda", 1000.0, std::nullopt), std::invalid_argument);
  EXPECT_THROW((void)attenuation_to_np_per_m(1.0, "dB/km", 1000.0, std::nullopt), std::invalid_argument);
}

TEST(UnitConversion, SoundSpeedToMetrePerSecond) {
  EXPECT_DOUBLE_EQ(sound_speed_to_m_per_s(1650.0, "m/s", std::nullopt), 1650.0);
  EXPECT_DOUBLE_EQ(sound_speed_to_m_per_s(1.6, "km/s", std::nullopt), 1600.0);
  expect_rel_near(sound_speed_to_m_per_s(1.061, "ratio", 1500.0), 1591.5);
  EXPECT_THROW((void)sound_speed_to_m_per_s(1.061, "ratio", std::nullopt), std::invalid_argument);
  EXPECT_THROW((void)sound_speed_to_m_per_s(1.0, "ft/s", std::nullopt), std::invalid_argument);
}

TEST(UnitConversion, DecibelPerNeperIsInverseOfConversion) {
  expect_rel_near(kDecibelPerNeper * kNpPerDb, 1.0);
  expect_rel_near(kDecibelPerNeper, 20.0 / std::numbers::ln10);
}

TEST(UnitConversion, UnknownUnitMessageListsAcceptedUnits) {
  try {
    (void)attenuation_to_np_per_m(1.0, "dB/km", 1000.0, std::nullopt);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("dB/m, Np/m, dB/lambda, dB/λ, dB/m/kHz"), std::string::npos);
  }
}

// ---- InputError ---------------------------------------------------------------------------------

TEST(InputErrorMessage, Formats) {
  const InputError full("obs.csv", 3, 2, "frequency", "not a number: 'x'");
  EXPECT_STREQ(full.what(), "obs.csv:3:2: field 'frequency': not a number: 'x'");
  EXPECT_EQ(full.file(), "obs.csv");
  EXPECT_EQ(full.line(), 3);
  EXPECT_EQ(full.column(), 2);
  EXPECT_EQ(full.field(), "frequency");
  EXPECT_STREQ(InputError("obs.csv", 3, 0, "", "duplicated header").what(), "obs.csv:3: duplicated header");
  EXPECT_STREQ(InputError("obs.csv", 3, 0, "quantity", "bad").what(), "obs.csv:3: field 'quantity': bad");
  EXPECT_STREQ(InputError("obs.csv", 0, 0, "", "empty file").what(), "obs.csv: empty file");
}

// ---- sedwave observation CSV: good input --------------------------------------------------------

using ObservationCsv = TempDirTest;

TEST_F(ObservationCsv, ConvertsEveryUnitToSi) {
  const auto path = write("units.csv",
                          "# water_sound_speed_m_per_s: 1500\n"
                          "# sediment_sound_speed_m_per_s: 1600\n"
                          "quantity,frequency,frequency_unit,value,value_unit,sigma\n"
                          "attenuation,1000,Hz,2,dB/m,0.03\n"
                          "attenuation,1,kHz,0.5,dB/lambda,0.02\n"
                          "attenuation,0.002,MHz,0.37,dB/m/kHz,\n"
                          "attenuation,100,Hz,0.25,Np/m,0.01\n"
                          "attenuation,1000,Hz,0.5,dB/λ,\n"
                          "sound_speed,500,Hz,1.6,km/s,0.01\n"
                          "sound_speed,500,Hz,1650,m/s,20\n"
                          "sound_speed_ratio,600,Hz,1.061,ratio,0.009\n");
  const auto set = read_observation_csv(path);
  ASSERT_EQ(set.observations.size(), 8U);
  const auto& obs = set.observations;

  EXPECT_EQ(obs[0].quantity, Quantity::Attenuation);
  EXPECT_DOUBLE_EQ(obs[0].frequency_hz, 1000.0);
  expect_rel_near(obs[0].value, 0.23025850929940458);
  expect_rel_near(*obs[0].sigma, 0.0034538776394910688);  // 0.03 dB/m
  EXPECT_EQ(obs[0].unit, "dB/m");
  EXPECT_EQ(obs[0].line, 4);
  EXPECT_EQ(obs[0].file, path.string());

  EXPECT_DOUBLE_EQ(obs[1].frequency_hz, 1000.0);
  expect_rel_near(obs[1].value, 0.03597789207803197);
  expect_rel_near(*obs[1].sigma, 0.0014391156831212787);  // 0.02 dB/lambda = 0.0125 dB/m
  EXPECT_EQ(obs[1].unit, "dB/lambda");

  EXPECT_DOUBLE_EQ(obs[2].frequency_hz, 2000.0);
  expect_rel_near(obs[2].value, 0.08519564844077969);
  EXPECT_FALSE(obs[2].sigma.has_value());

  EXPECT_DOUBLE_EQ(obs[3].value, 0.25);
  EXPECT_DOUBLE_EQ(*obs[3].sigma, 0.01);

  expect_rel_near(obs[4].value, 0.03597789207803197);
  EXPECT_EQ(obs[4].unit, "dB/λ");

  EXPECT_EQ(obs[5].quantity, Quantity::SoundSpeed);
  EXPECT_DOUBLE_EQ(obs[5].value, 1600.0);
  EXPECT_DOUBLE_EQ(*obs[5].sigma, 10.0);

  EXPECT_DOUBLE_EQ(obs[6].value, 1650.0);
  EXPECT_DOUBLE_EQ(*obs[6].sigma, 20.0);

  EXPECT_EQ(obs[7].quantity, Quantity::SoundSpeed);
  expect_rel_near(obs[7].value, 1591.5);
  expect_rel_near(*obs[7].sigma, 13.5);
  EXPECT_EQ(obs[7].unit, "ratio");
  EXPECT_EQ(obs[7].line, 11);

  EXPECT_EQ(set.water_sound_speed, 1500.0);
}

TEST_F(ObservationCsv, ToleratesCrlfBomSpacesAndBlankLines) {
  const auto path = write("messy.csv",
                          "\xEF\xBB\xBF# title: messy\r\n"
                          "\r\n"
                          "quantity, frequency ,frequency_unit,value,value_unit,sigma  \r\n"
                          "  attenuation , 1e3 , Hz , 2 , dB/m ,   \r\n"
                          "\r\n"
                          "   \t\r\n"
                          "sound_speed,100,Hz,1600,m/s,\r\n");
  const auto set = read_observation_csv(path);
  ASSERT_EQ(set.observations.size(), 2U);
  EXPECT_DOUBLE_EQ(set.observations[0].frequency_hz, 1000.0);
  expect_rel_near(set.observations[0].value, 0.23025850929940458);
  EXPECT_FALSE(set.observations[0].sigma.has_value());
  EXPECT_EQ(set.observations[1].line, 7);
  EXPECT_EQ(set.metadata.at("title"), "messy");
}

TEST_F(ObservationCsv, ReadsMetadataWhereverItAppears) {
  const auto path = write("meta.csv",
                          "# sedwave observation CSV (format: docs/file-formats.md)\n"
                          "# see https://example.org/a:b\n"
                          "# citation: First line of a long citation,\n"
                          "# citation: continued on a second line\n"
                          "# url: https://doi.org/10.1121/1.3089218\n"
                          "# not:metadata without a space after the colon\n"
                          "quantity,frequency,frequency_unit,value,value_unit,sigma\n"
                          "sound_speed_ratio,100,Hz,1.05,ratio,\n"
                          "# water_sound_speed_m_per_s:   1480.5  \n");
  const auto set = read_observation_csv(path);
  ASSERT_EQ(set.observations.size(), 1U);
  expect_rel_near(set.observations[0].value, 1.05 * 1480.5);
  EXPECT_EQ(set.water_sound_speed, 1480.5);
  EXPECT_EQ(set.metadata.at("citation"), "First line of a long citation, continued on a second line");
  EXPECT_EQ(set.metadata.at("url"), "https://doi.org/10.1121/1.3089218");
  EXPECT_EQ(set.metadata.at("water_sound_speed_m_per_s"), "1480.5");
  EXPECT_EQ(set.metadata.size(), 3U);
}

TEST_F(ObservationCsv, CallerSuppliesMissingSpeeds) {
  const auto path = write("speeds.csv",
                          "quantity,frequency,frequency_unit,value,value_unit,sigma\n"
                          "sound_speed_ratio,100,Hz,1.1,ratio,0.01\n"
                          "attenuation,800,Hz,0.4,dB/lambda,\n");
  const auto set = read_observation_csv(path, speeds(1500.0, 1600.0));
  ASSERT_EQ(set.observations.size(), 2U);
  expect_rel_near(set.observations[0].value, 1650.0);
  expect_rel_near(*set.observations[0].sigma, 15.0);
  expect_rel_near(set.observations[1].value, 0.4 * 800.0 / 1600.0 * kNpPerDb);  // 0.2 dB/m
  EXPECT_EQ(set.water_sound_speed, 1500.0);
}

TEST_F(ObservationCsv, FileAndCallerSpeedsMustAgree) {
  const auto path = write("agree.csv",
                          "# water_sound_speed_m_per_s: 1500\n"
                          "quantity,frequency,frequency_unit,value,value_unit,sigma\n"
                          "sound_speed_ratio,100,Hz,1.1,ratio,\n");
  EXPECT_NO_THROW((void)read_observation_csv(path, speeds(1500.0 * (1.0 + 1e-12))));
  const auto error = input_error([&] { (void)read_observation_csv(path, speeds(1480.0)); });
  expect_error(error, 1, 30, "water_sound_speed_m_per_s", "1500 m/s disagrees with 1480 m/s");
}

TEST_F(ObservationCsv, WholeMessageNamesFileLineColumnFieldAndReason) {
  const auto path = write("bad.csv", std::string(kHeader) + "attenuation,abc,Hz,1,dB/m,\n");
  const auto error = input_error([&] { (void)read_observation_csv(path); });
  EXPECT_EQ(std::string(error.what()), path.string() + ":2:2: field 'frequency': not a number: 'abc'");
  EXPECT_EQ(error.file(), path.string());
}

TEST_F(ObservationCsv, MissingFileIsAnInputError) {
  const auto error = input_error([&] { (void)read_observation_csv("/nonexistent/sedwave/none.csv"); });
  expect_error(error, 0, 0, "", "cannot open file");
}

TEST_F(ObservationCsv, TwoColumnDigitizedExportIsRecognisedAndPointsToTheOption) {
  for (const std::string_view content : {"f [kHz],alpha [dB/m]\n0.1,0.0058641\n0.158489,0.0134338\n",
                                         "0.1;0.0058641\n\n0.158489;0.0134338\n"}) {
    const auto path = write("fig3.csv", content);
    const auto error = input_error([&] { (void)read_observation_csv(path); });
    expect_error(error, 0, 0, "",
                 "this looks like a two-column digitised export; read it with --digitized-file " + path.string() +
                     " --digitized QUANTITY:FREQ_UNIT:VALUE_UNIT");
  }
}

TEST_F(ObservationCsv, ThreeNumericColumnsAreNotTakenForADigitizedExport) {
  const auto path = write("three.csv", "0.1,0.0058641,1\n");
  expect_error(input_error([&] { (void)read_observation_csv(path); }), 1, 0, "", "data row before the header line");
}

// ---- sedwave observation CSV: every class of bad input -------------------------------------------

struct BadCase {
  std::string name;
  std::string content;
  int line;
  int column;
  std::string field;
  std::string reason;
};

std::string with_header(std::string_view rows) { return std::string(kHeader) + std::string(rows); }

std::vector<BadCase> bad_cases() {
  return {
      {"NonNumericFrequency", with_header("attenuation,abc,Hz,1,dB/m,\n"), 2, 2, "frequency",
       "not a number: 'abc'"},
      {"TrailingGarbage", with_header("attenuation,100Hz,Hz,1,dB/m,\n"), 2, 2, "frequency", "not a number"},
      {"HexNumber", with_header("attenuation,0x10,Hz,1,dB/m,\n"), 2, 2, "frequency", "not a number"},
      {"OutOfRange", with_header("attenuation,1e999,Hz,1,dB/m,\n"), 2, 2, "frequency", "number out of range"},
      {"MissingFrequency", with_header("attenuation,,Hz,1,dB/m,\n"), 2, 2, "frequency", "missing number"},
      {"NanValue", with_header("attenuation,100,Hz,nan,dB/m,\n"), 2, 4, "value", "not a finite number"},
      {"InfFrequency", with_header("attenuation,inf,Hz,1,dB/m,\n"), 2, 2, "frequency", "not a finite number"},
      {"InfSigma", with_header("attenuation,100,Hz,1,dB/m,-inf\n"), 2, 6, "sigma", "not a finite number"},
      {"NegativeFrequency", with_header("attenuation,-100,Hz,1,dB/m,\n"), 2, 2, "frequency",
       "frequency must be positive"},
      {"ZeroFrequency", with_header("attenuation,0,Hz,1,dB/m,\n"), 2, 2, "frequency",
       "frequency must be positive"},
      {"MissingFrequencyUnit", with_header("attenuation,100,,1,dB/m,\n"), 2, 3, "frequency_unit",
       "missing unit"},
      {"UnknownFrequencyUnit", with_header("attenuation,100,khz,1,dB/m,\n"), 2, 3, "frequency_unit",
       "unknown unit 'khz' (accepted: Hz, kHz, MHz)"},
      {"MissingValueUnit", with_header("attenuation,100,Hz,1,,\n"), 2, 5, "value_unit", "missing unit"},
      {"MissingRatioUnit",
       "# water_sound_speed_m_per_s: 1500\n" + with_header("sound_speed_ratio,100,Hz,1.05,,\n"), 3, 5,
       "value_unit", "missing unit for sound_speed_ratio (accepted: ratio)"},
      {"UnknownAttenuationUnit", with_header("attenuation,100,Hz,1,dB/km,\n"), 2, 5, "value_unit",
       "unknown unit 'dB/km' for attenuation (accepted: dB/m, Np/m, dB/lambda, dB/λ, dB/m/kHz)"},
      {"UnitOfAnotherQuantity", with_header("sound_speed,100,Hz,1.05,ratio,\n"), 2, 5, "value_unit",
       "unknown unit 'ratio' for sound_speed (accepted: m/s, km/s)"},
      {"UnknownQuantity", with_header("density,100,Hz,1,kg/m3,\n"), 2, 1, "quantity",
       "unknown quantity 'density' (accepted: attenuation, sound_speed, sound_speed_ratio, bottom_loss, shear_speed, shear_attenuation, reflection_magnitude)"},
      {"MissingQuantity", with_header(",100,Hz,1,dB/m,\n"), 2, 1, "quantity", "missing quantity"},
      {"ZeroAttenuation", with_header("attenuation,100,Hz,0,dB/m,\n"), 2, 4, "value",
       "attenuation (fitted in log space) must be positive"},
      {"NegativeAttenuation", with_header("attenuation,100,Hz,-0.1,Np/m,\n"), 2, 4, "value",
       "must be positive, got '-0.1'"},
      {"ZeroSoundSpeed", with_header("sound_speed,100,Hz,0,m/s,\n"), 2, 4, "value",
       "sound speed must be positive"},
      {"ZeroSigma", with_header("attenuation,100,Hz,1,dB/m,0\n"), 2, 6, "sigma", "sigma must be positive"},
      {"NegativeSigma", with_header("sound_speed,100,Hz,1600,m/s,-5\n"), 2, 6, "sigma",
       "sigma must be positive"},
      {"NonNumericSigma", with_header("sound_speed,100,Hz,1600,m/s,n/a\n"), 2, 6, "sigma",
       "not a number: 'n/a'"},
      {"TooFewColumns", with_header("attenuation,100,Hz,1,dB/m\n"), 2, 0, "",
       "wrong number of columns: expected 6"},
      {"TooManyColumns", with_header("attenuation,100,Hz,1,dB/m,0.1,extra\n"), 2, 0, "", "found 7"},
      {"RowBeforeHeader", "attenuation,100,Hz,1,dB/m,\n" + with_header(""), 1, 0, "",
       "data row before the header line"},
      {"DuplicatedHeader", with_header("attenuation,100,Hz,1,dB/m,\n") + std::string(kHeader), 3, 0, "",
       "duplicated header (first on line 1)"},
      {"MisspeltHeader", "quantity,freq,frequency_unit,value,value_unit,sigma\nattenuation,100,Hz,1,dB/m,\n",
       1, 2, "frequency", "header column must be 'frequency', found 'freq'"},
      {"CapitalisedHeader", "Quantity,frequency,frequency_unit,value,value_unit,sigma\n", 1, 1, "quantity",
       "header column must be 'quantity'"},
      {"ShortHeader", "quantity,frequency\n", 1, 0, "", "header must have the 6 columns"},
      {"RatioWithoutWaterSpeed",
       with_header("attenuation,100,Hz,1,dB/m,\nsound_speed_ratio,100,Hz,1.05,ratio,\n"), 3, 5, "value_unit",
       "ratio needs a water sound speed"},
      {"WavelengthWithoutSedimentSpeed", with_header("attenuation,100,Hz,0.5,dB/lambda,\n"), 2, 5,
       "value_unit", "dB/lambda needs a sediment sound speed"},
      {"EmptyFile", "", 0, 0, "", "empty file"},
      {"BlankFile", "\n  \r\n\t\n", 0, 0, "", "empty file"},
      {"HeaderOnly", with_header(""), 0, 0, "", "no data rows"},
      {"CommentsOnly", "# title: nothing here\n", 0, 0, "", "no header line"},
      {"WaterSpeedNotANumber",
       "# water_sound_speed_m_per_s: fast\n" + with_header("attenuation,100,Hz,1,dB/m,\n"), 1, 30,
       "water_sound_speed_m_per_s", "not a number: 'fast'"},
      {"SedimentSpeedNegative",
       "# sediment_sound_speed_m_per_s: -1600\n" + with_header("attenuation,100,Hz,1,dB/m,\n"), 1, 33,
       "sediment_sound_speed_m_per_s", "sound speed must be positive"},
      {"WaterSpeedTwice",
       "# water_sound_speed_m_per_s: 1500\n# water_sound_speed_m_per_s: 1500\n" +
           with_header("attenuation,100,Hz,1,dB/m,\n"),
       2, 30, "water_sound_speed_m_per_s", "given twice (first on line 1)"},
      {"CrlfLineNumbers",
       "\r\nquantity,frequency,frequency_unit,value,value_unit,sigma\r\n\r\nattenuation,x,Hz,1,dB/m,\r\n", 4,
       2, "frequency", "not a number: 'x'"},
  };
}

class BadObservationCsv : public TempDirTest, public ::testing::WithParamInterface<BadCase> {};

TEST_P(BadObservationCsv, ThrowsInputErrorAtTheFault) {
  const auto path = write("bad.csv", GetParam().content);
  const auto error = input_error([&] { (void)read_observation_csv(path); });
  expect_error(error, GetParam().line, GetParam().column, GetParam().field, GetParam().reason);
  EXPECT_EQ(error.file(), path.string());
}

INSTANTIATE_TEST_SUITE_P(EveryFault, BadObservationCsv, ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& param) { return param.param.name; });

// ---- WebPlotDigitizer export --------------------------------------------------------------------

using DigitizedCsv = TempDirTest;

const DigitizedColumns kAttenuationKhzDbPerM{"attenuation", "kHz", "dB/m", std::nullopt};

TEST_F(DigitizedCsv, ReadsTwoColumnsWithoutHeader) {
  const auto path = write("wpd.csv", "0.1,0.0058641\n1,0.37\n");
  const auto set = read_digitized_csv(path, kAttenuationKhzDbPerM);
  ASSERT_EQ(set.observations.size(), 2U);
  EXPECT_EQ(set.observations[0].quantity, Quantity::Attenuation);
  EXPECT_DOUBLE_EQ(set.observations[0].frequency_hz, 100.0);
  expect_rel_near(set.observations[0].value, 0.0058641 * kNpPerDb);
  EXPECT_FALSE(set.observations[0].sigma.has_value());
  EXPECT_EQ(set.observations[0].unit, "dB/m");
  EXPECT_EQ(set.observations[1].line, 2);
  EXPECT_DOUBLE_EQ(set.observations[1].frequency_hz, 1000.0);
}

TEST_F(DigitizedCsv, AcceptsOneHeaderLineAndOtherSeparators) {
  const auto header = write("header.csv", "x,y\r\n0.1,0.0058641\r\n");
  EXPECT_EQ(read_digitized_csv(header, kAttenuationKhzDbPerM).observations.size(), 1U);
  const auto dataset = write("dataset.csv", "Dataset 1,,\n0.1,0.0058641\n");
  EXPECT_EQ(read_digitized_csv(dataset, kAttenuationKhzDbPerM).observations.at(0).line, 2);
  const auto semicolon = write("semicolon.csv", "0.1;0.0058641\n0.2; 0.02\n");
  EXPECT_EQ(read_digitized_csv(semicolon, kAttenuationKhzDbPerM).observations.size(), 2U);
  const auto tab = write("tab.csv", "X\tY\n0.1\t0.0058641\n");
  EXPECT_DOUBLE_EQ(read_digitized_csv(tab, kAttenuationKhzDbPerM).observations.at(0).frequency_hz, 100.0);
}

TEST_F(DigitizedCsv, RelativeSigmaAndRatioWithWaterSpeed) {
  const auto path = write("ratio.csv", "50,1.061\n600,1.061\n");
  const DigitizedColumns columns{"sound_speed_ratio", "Hz", "ratio", 0.01};
  const auto set = read_digitized_csv(path, columns, speeds(1500.0));
  ASSERT_EQ(set.observations.size(), 2U);
  EXPECT_EQ(set.observations[0].quantity, Quantity::SoundSpeed);
  expect_rel_near(set.observations[0].value, 1591.5);
  expect_rel_near(*set.observations[0].sigma, 15.915);
  EXPECT_EQ(set.water_sound_speed, 1500.0);
}

TEST_F(DigitizedCsv, BadRowsPointAtLineAndColumn) {
  const auto second_header = write("h2.csv", "Dataset 1,\nX,Y\n0.1,0.2\n");
  expect_error(input_error([&] { (void)read_digitized_csv(second_header, kAttenuationKhzDbPerM); }), 2, 1,
               "frequency", "not a number: 'X'");
  // A first line with a number in it is data, so its bad cell is reported, not skipped as a header.
  const auto bad_first = write("first.csv", "0.1,abc\n0.2,0.3\n");
  expect_error(input_error([&] { (void)read_digitized_csv(bad_first, kAttenuationKhzDbPerM); }), 1, 2,
               "value", "not a number: 'abc'");
  const auto three = write("three.csv", "0.1,0.2\n0.3,0.4,0.5\n");
  expect_error(input_error([&] { (void)read_digitized_csv(three, kAttenuationKhzDbPerM); }), 2, 0, "",
               "wrong number of columns: expected 2");
  const auto negative_x = write("negx.csv", "-0.1,0.2\n");
  expect_error(input_error([&] { (void)read_digitized_csv(negative_x, kAttenuationKhzDbPerM); }), 1, 1,
               "frequency", "frequency must be positive");
  const auto zero_y = write("zeroy.csv", "x,y\n0.1,0\n");
  expect_error(input_error([&] { (void)read_digitized_csv(zero_y, kAttenuationKhzDbPerM); }), 2, 2, "value",
               "attenuation (fitted in log space) must be positive");
  const auto nan_y = write("nany.csv", "0.1,NaN\n");
  expect_error(input_error([&] { (void)read_digitized_csv(nan_y, kAttenuationKhzDbPerM); }), 1, 2, "value",
               "not a finite number");
}

TEST_F(DigitizedCsv, EmptyOrHeaderOnlyFile) {
  const auto empty = write("empty.csv", "");
  expect_error(input_error([&] { (void)read_digitized_csv(empty, kAttenuationKhzDbPerM); }), 0, 0, "",
               "empty file");
  const auto header = write("header.csv", "x,y\n\n");
  expect_error(input_error([&] { (void)read_digitized_csv(header, kAttenuationKhzDbPerM); }), 0, 0, "",
               "no data rows");
}

TEST_F(DigitizedCsv, BadColumnDescriptionNamesTheOption) {
  const auto path = write("ok.csv", "0.1,0.2\n");
  const auto read = [&](const DigitizedColumns& columns, const ReadOptions& options = {}) {
    return input_error([&] { (void)read_digitized_csv(path, columns, options); });
  };
  expect_error(read({"density", "kHz", "dB/m", std::nullopt}), 0, 0, "quantity",
               "unknown quantity 'density'");
  expect_error(read({"attenuation", "hz", "dB/m", std::nullopt}), 0, 0, "frequency_unit",
               "unknown unit 'hz'");
  expect_error(read({"attenuation", "kHz", "m/s", std::nullopt}), 0, 0, "value_unit",
               "unknown unit 'm/s' for attenuation");
  expect_error(read({"sound_speed_ratio", "Hz", "ratio", std::nullopt}), 0, 0, "value_unit",
               "ratio needs a water sound speed");
  expect_error(read({"attenuation", "kHz", "dB/lambda", std::nullopt}), 0, 0, "value_unit",
               "needs a sediment sound speed");
  expect_error(read({"attenuation", "kHz", "dB/m", -0.1}), 0, 0, "relative_sigma", "must be a positive");
  const auto message = std::string(read({"attenuation", "kHz", "dB/m", 0.0}).what());
  EXPECT_EQ(message, path.string() +
                         ": field 'relative_sigma': relative sigma must be a positive finite number, got 0");
}

// ---- ObservationSet::append ---------------------------------------------------------------------

TEST(ObservationSetAppend, ConcatenatesAndMergesMetadata) {
  ObservationSet first;
  first.observations.push_back(observation(Quantity::Attenuation, 100.0, 0.1));
  first.metadata = {{"source", "a"}, {"site", "x"}};
  ObservationSet second;
  second.observations.push_back(observation(Quantity::SoundSpeed, 200.0, 1600.0));
  second.water_sound_speed = 1500.0;
  second.metadata = {{"source", "b"}, {"site", "x"}, {"doi", "10.1/x"}};
  first.append(second);
  ASSERT_EQ(first.observations.size(), 2U);
  EXPECT_EQ(first.observations[1].value, 1600.0);
  EXPECT_EQ(first.water_sound_speed, 1500.0);
  EXPECT_EQ(first.metadata.at("source"), "a; b");
  EXPECT_EQ(first.metadata.at("site"), "x");
  EXPECT_EQ(first.metadata.at("doi"), "10.1/x");
}

TEST(ObservationSetAppend, DisagreeingWaterSpeedsThrowAndLeaveSetUnchanged) {
  ObservationSet first;
  first.water_sound_speed = 1500.0;
  ObservationSet second;
  second.water_sound_speed = 1480.0;
  auto from_second = observation(Quantity::SoundSpeed, 100.0, 1600.0);
  from_second.file = "second.csv";
  second.observations.push_back(from_second);
  const auto error = input_error([&] { first.append(second); });
  EXPECT_EQ(error.file(), "second.csv");
  EXPECT_EQ(error.field(), "water_sound_speed_m_per_s");
  EXPECT_TRUE(first.observations.empty());
  EXPECT_EQ(first.water_sound_speed, 1500.0);
}

// ---- Shipped data -------------------------------------------------------------------------------

const fs::path kFieldData = fs::path(SEDWAVE_SOURCE_DIR) / "data" / "field";
const fs::path kDigitizedData = fs::path(SEDWAVE_SOURCE_DIR) / "data" / "digitized";

/// The file holds 6 significant digits: relative rounding of at most 5e-6 (plus conversion ulps).
constexpr double kSixDigits = 5.0001e-6;

TEST(ShippedData, Zhou2009RegressionMatchesTheFormula) {
  const auto set = read_observation_csv(kFieldData / "zhou2009_regression.csv");
  ASSERT_EQ(set.observations.size(), 19U);
  EXPECT_EQ(set.water_sound_speed, 1500.0);
  EXPECT_EQ(set.metadata.at("doi"), "10.1121/1.3089218");
  EXPECT_NE(set.metadata.at("data_kind").find("NOT measurements"), std::string::npos);
  EXPECT_NE(set.metadata.at("water_sound_speed_note").find("NOMINAL ASSUMPTION"), std::string::npos);

  for (int i = 0; i < 13; ++i) {
    const auto& obs = set.observations[static_cast<std::size_t>(i)];
    SCOPED_TRACE("attenuation row " + std::to_string(i));
    ASSERT_EQ(obs.quantity, Quantity::Attenuation);
    EXPECT_EQ(obs.unit, "dB/m");
    expect_rel_near(obs.frequency_hz, 50.0 * std::pow(20.0, i / 12.0), kSixDigits);
    // alpha [dB/m] = 0.37 (f / 1 kHz)^1.80 at the frequency as written.
    const double alpha_db = obs.value * kDecibelPerNeper;
    const double log_f = std::log(obs.frequency_hz / 1000.0);
    expect_rel_near(alpha_db, 0.37 * std::exp(1.80 * log_f), kSixDigits);
    // sigma = alpha sqrt((0.01/0.37)^2 + (0.02 ln(f/1 kHz))^2).
    ASSERT_TRUE(obs.sigma.has_value());
    const double relative = std::hypot(0.01 / 0.37, 0.02 * log_f);
    expect_rel_near(*obs.sigma * kDecibelPerNeper, alpha_db * relative, kSixDigits);
  }
  EXPECT_DOUBLE_EQ(set.observations.front().frequency_hz, 50.0);
  EXPECT_DOUBLE_EQ(set.observations[12].frequency_hz, 1000.0);

  for (int i = 0; i < 6; ++i) {
    const auto& obs = set.observations[static_cast<std::size_t>(13 + i)];
    SCOPED_TRACE("ratio row " + std::to_string(i));
    ASSERT_EQ(obs.quantity, Quantity::SoundSpeed);
    EXPECT_EQ(obs.unit, "ratio");
    expect_rel_near(obs.frequency_hz, 50.0 * std::pow(12.0, i / 5.0), kSixDigits);
    expect_rel_near(obs.value, 1.061 * 1500.0);
    expect_rel_near(*obs.sigma, 0.009 * 1500.0);
  }
  EXPECT_DOUBLE_EQ(set.observations.back().frequency_hz, 600.0);
}

TEST(ShippedData, WebPlotDigitizerExampleMatchesTheRegression) {
  const auto set = read_digitized_csv(kDigitizedData / "example_webplotdigitizer.csv", kAttenuationKhzDbPerM);
  ASSERT_EQ(set.observations.size(), 6U);
  for (const auto& obs : set.observations) {
    expect_rel_near(obs.value * kDecibelPerNeper, 0.37 * std::pow(obs.frequency_hz / 1000.0, 1.8),
                    kSixDigits);
  }
  EXPECT_DOUBLE_EQ(set.observations.front().frequency_hz, 100.0);
  EXPECT_DOUBLE_EQ(set.observations.back().frequency_hz, 1000.0);
}

}  // namespace
}  // namespace sedwave::inversion
