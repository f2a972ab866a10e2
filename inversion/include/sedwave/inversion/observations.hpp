#pragma once
// Field observations: attenuation and sound speed against frequency, read from files.
//
// Two formats (documented in docs/file-formats.md):
//  * the sedwave observation CSV: '#' metadata lines ("# key: value"), one header line
//      quantity,frequency,frequency_unit,value,value_unit,sigma[,grazing_angle_deg]
//    (the last column only where a row is a bottom loss or |R|) and one observation per row, each with its own units;
//  * the two-column "x,y" CSV that WebPlotDigitizer exports, with quantity and units given by the
//    caller (command-line options), since the file itself carries none.
// Everything is converted to SI on reading: frequency in Hz, attenuation in Np/m, sound speed in m/s,
// grazing angle in rad; bottom loss stays in dB, |R| as it is.
// Bad input throws InputError naming file, line, column and the reason; nothing is skipped.
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sedwave::inversion {

/// What an observation measures. Sound-speed ratios are converted to SoundSpeed with the water
/// sound speed on reading (the original unit is kept in Observation::unit for display). BottomLoss
/// is the plane-wave bottom loss -20 log10 |R| [dB] at a grazing angle (docs/reflection.md);
/// ReflectionMagnitude |R| itself [1]; ShearSpeed and ShearAttenuation those of the shear wave of a
/// model that has one.
enum class Quantity { Attenuation, SoundSpeed, BottomLoss, ShearSpeed, ShearAttenuation, ReflectionMagnitude };

/// Whether a quantity is of the plane-wave reflection coefficient (it has a grazing angle).
[[nodiscard]] inline bool is_reflection(Quantity q) {
  return q == Quantity::BottomLoss || q == Quantity::ReflectionMagnitude;
}

/// Whether a quantity is an attenuation (fitted in log space), of either wave.
[[nodiscard]] inline bool is_attenuation(Quantity q) {
  return q == Quantity::Attenuation || q == Quantity::ShearAttenuation;
}
/// Whether a quantity is of the shear wave.
[[nodiscard]] inline bool is_shear(Quantity q) { return q == Quantity::ShearSpeed || q == Quantity::ShearAttenuation; }

/// The observation file's name of a quantity ("attenuation", "sound_speed", "bottom_loss", ...).
[[nodiscard]] const char* quantity_name(Quantity q);

/// The unit a quantity's values are held in: Np/m, m/s, dB (bottom loss) or 1 (|R|).
[[nodiscard]] const char* quantity_unit(Quantity q);

/// One measured value, in SI.
struct Observation {
  Quantity quantity = Quantity::Attenuation;
  double frequency_hz = 0.0;    ///< [Hz]
  double value = 0.0;           ///< attenuation [Np/m], speed [m/s], bottom loss [dB] or |R| [1]
  std::optional<double> sigma;  ///< 1-sigma uncertainty in the same SI unit, if the file gave one
  std::string unit;             ///< the value unit as written in the file (e.g. "dB/m", "ratio")
  std::string file;             ///< where it came from, for messages
  int line = 0;
  double grazing_angle = 0.0;   ///< [rad] from the horizontal, is_reflection() rows only
};

/// The observations of one or more files plus the metadata they declared.
struct ObservationSet {
  std::vector<Observation> observations;
  /// Water sound speed [m/s] (from "# water_sound_speed_m_per_s:" or the caller); needed for ratios.
  std::optional<double> water_sound_speed;
  /// All "# key: value" metadata lines, by key (a key repeated within one file is joined with a
  /// space; append() joins differing values of later files with "; ").
  std::map<std::string, std::string> metadata;

  /// Adds the observations and metadata of `other`. Throws InputError (naming other's first file)
  /// and changes nothing if both sets have water sound speeds that differ by more than 1e-9
  /// relative, since their ratios were converted with different speeds.
  void append(const ObservationSet& other);
};

/// The reference sound speeds a file or an option may declare [m/s] (water for ratios and reflection,
/// sediment for dB/wavelength): from gassy mud to the grains' minerals.
inline constexpr double kLowestDeclaredSpeed = 100.0;
inline constexpr double kHighestDeclaredSpeed = 10000.0;
/// The densities of the water above a seabed a file or an option may declare [kg/m^3]: from warm
/// fresh water to dense brine.
inline constexpr double kLowestWaterDensity = 950.0;
inline constexpr double kHighestWaterDensity = 1300.0;

/// The density [kg/m^3] of the water above the seabed that a data set declares
/// ("# water_density_kg_per_m3: ..."), else sea water's 1025 kg/m^3. Throws std::invalid_argument
/// for a value that is not one number in [kLowestWaterDensity, kHighestWaterDensity].
[[nodiscard]] double water_density_of(const ObservationSet& data);


/// Error in an input file: "FILE:LINE:COLUMN: field 'NAME': REASON". ":COLUMN" is omitted when column
/// is 0 (whole-row errors), " field 'NAME'" when field is empty, and ":LINE" (with the column) when
/// line is 0 (whole-file errors: cannot open, empty file, no data rows, and digitized-column options).
/// Lines are 1-based; for data rows the column is the 1-based field number (quantity = 1), for
/// "# key: value" metadata lines the 1-based character position where the value starts.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, int column, std::string field, const std::string& reason);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }
  [[nodiscard]] int column() const { return column_; }
  [[nodiscard]] const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string field_;
};

/// Options that complete what a file does not say.
struct ReadOptions {
  /// Water sound speed [m/s] used for sound-speed ratios when the file gives none (a value in the
  /// file wins; give both and they must agree to 1e-9 relative, else InputError).
  std::optional<double> water_sound_speed;
  /// Sediment sound speed [m/s] used to convert dB/wavelength when the file gives none
  /// ("# sediment_sound_speed_m_per_s:"; same agreement rule as the water sound speed).
  std::optional<double> sediment_sound_speed;
};

/// Reads a sedwave observation CSV.
ObservationSet read_observation_csv(const std::filesystem::path& file, const ReadOptions& options = {});

/// Quantity and units of a WebPlotDigitizer two-column export (x = frequency, y = value).
struct DigitizedColumns {
  std::string quantity;        ///< "attenuation", "sound_speed" or "sound_speed_ratio"
  std::string frequency_unit;  ///< "Hz", "kHz" or "MHz"
  std::string value_unit;      ///< any value unit the observation CSV accepts for that quantity
  std::optional<double> relative_sigma;  ///< 1-sigma relative uncertainty for every point, if known
};

/// Reads a WebPlotDigitizer "x,y" CSV export: two numeric columns separated by ',', ';' or a tab,
/// optionally preceded by one header line in which no cell is a number. Only `options` supply the
/// water/sediment sound speeds (the file cannot declare them).
ObservationSet read_digitized_csv(const std::filesystem::path& file, const DigitizedColumns& columns,
                                  const ReadOptions& options = {});

/// Unit conversions to SI, exposed for the CLI and tests. Throw std::invalid_argument naming the
/// unit and the accepted ones if the unit is unknown.
double frequency_to_hz(double value, const std::string& unit);
/// Attenuation in `unit` at frequency f [Hz] to Np/m. dB/lambda needs the sediment sound speed.
double attenuation_to_np_per_m(double value, const std::string& unit, double frequency_hz,
                               std::optional<double> sediment_sound_speed);
/// Sound speed in `unit` ("m/s", "km/s" or "ratio" with the water sound speed) to m/s.
double sound_speed_to_m_per_s(double value, const std::string& unit, std::optional<double> water_sound_speed);

/// Np/m -> dB/m (20 log10 e = 8.6859 dB per neper), for reports and plots.
inline constexpr double kDecibelPerNeper = 8.685889638065035;

}  // namespace sedwave::inversion
