#include "sedwave/inversion/observations.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <span>
#include <string_view>
#include <system_error>
#include <utility>

namespace sedwave::inversion {
namespace {

// ---- Units --------------------------------------------------------------------------------------

/// 1 dB = ln(10)/20 Np, since attenuation in dB is 20 log10 of an amplitude ratio and in Np is ln.
constexpr double kNeperPerDecibel = std::numbers::ln10 / 20.0;

struct FrequencyUnit {
  std::string_view name;
  double to_hz;
};
constexpr std::array<FrequencyUnit, 3> kFrequencyUnits{{{"Hz", 1.0}, {"kHz", 1e3}, {"MHz", 1e6}}};

constexpr std::array<std::string_view, 3> kFrequencyUnitNames{"Hz", "kHz", "MHz"};
constexpr std::array<std::string_view, 5> kAttenuationUnits{"dB/m", "Np/m", "dB/lambda", "dB/λ", "dB/m/kHz"};
constexpr std::array<std::string_view, 2> kSoundSpeedUnits{"m/s", "km/s"};
constexpr std::array<std::string_view, 1> kRatioUnits{"ratio"};
constexpr std::array<std::string_view, 1> kBottomLossUnits{"dB"};
constexpr std::array<std::string_view, 1> kReflectionUnits{"1"};
// dB/lambda would need the shear speed, which no file declares.
constexpr std::array<std::string_view, 3> kShearAttenuationUnits{"dB/m", "Np/m", "dB/m/kHz"};

/// A quantity name of the file formats, what it becomes, and the value units it accepts.
struct QuantitySpec {
  std::string_view name;
  Quantity quantity;
  std::span<const std::string_view> units;
};
constexpr std::array<QuantitySpec, 7> kQuantities{{
    {"attenuation", Quantity::Attenuation, kAttenuationUnits},
    {"sound_speed", Quantity::SoundSpeed, kSoundSpeedUnits},
    {"sound_speed_ratio", Quantity::SoundSpeed, kRatioUnits},
    {"bottom_loss", Quantity::BottomLoss, kBottomLossUnits},
    {"shear_speed", Quantity::ShearSpeed, kSoundSpeedUnits},
    {"shear_attenuation", Quantity::ShearAttenuation, kShearAttenuationUnits},
    {"reflection_magnitude", Quantity::ReflectionMagnitude, kReflectionUnits},
}};

/// The header; its last column is optional (only bottom-loss rows need an angle).
constexpr std::array<std::string_view, 7> kHeader{"quantity", "frequency",  "frequency_unit",   "value",
                                                  "value_unit", "sigma", "grazing_angle_deg"};
constexpr std::size_t kShortHeader = 6;
constexpr std::string_view kHeaderText = "quantity,frequency,frequency_unit,value,value_unit,sigma";
constexpr std::string_view kAngleHeaderText = "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg";

constexpr std::string_view kWaterSpeedKey = "water_sound_speed_m_per_s";
constexpr std::string_view kSedimentSpeedKey = "sediment_sound_speed_m_per_s";

std::string join(std::span<const std::string_view> names) {
  std::string out;
  for (const auto name : names) {
    out += out.empty() ? "" : ", ";
    out += name;
  }
  return out;
}

std::string quantity_names() {
  std::array<std::string_view, kQuantities.size()> names{};
  std::ranges::transform(kQuantities, names.begin(), &QuantitySpec::name);
  return join(names);
}

const FrequencyUnit* find_frequency_unit(std::string_view name) {
  const auto it = std::ranges::find(kFrequencyUnits, name, &FrequencyUnit::name);
  return it == kFrequencyUnits.end() ? nullptr : &*it;
}

const QuantitySpec* find_quantity(std::string_view name) {
  const auto it = std::ranges::find(kQuantities, name, &QuantitySpec::name);
  return it == kQuantities.end() ? nullptr : &*it;
}

bool accepts_unit(const QuantitySpec& spec, std::string_view unit) {
  return std::ranges::find(spec.units, unit) != spec.units.end();
}

bool is_per_wavelength(std::string_view unit) { return unit == "dB/lambda" || unit == "dB/λ"; }

/// Relative agreement used when the same speed is given twice (file and caller, or two files).
bool agree(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

std::string format_number(double x) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return {buffer.data(), result.ptr};
}

// ---- Text ---------------------------------------------------------------------------------------

std::string_view trim(std::string_view text) {
  constexpr std::string_view kSpace = " \t\r\n\f\v";
  const auto first = text.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(kSpace) - first + 1);
}

/// Splits at any of `separators`, trimming each field. No quoting: neither format needs it.
std::vector<std::string_view> split(std::string_view line, std::string_view separators) {
  std::vector<std::string_view> fields;
  for (;;) {
    const auto end = line.find_first_of(separators);
    fields.push_back(trim(line.substr(0, end)));
    if (end == std::string_view::npos) return fields;
    line.remove_prefix(end + 1);
  }
}

std::vector<std::string> read_lines(const std::filesystem::path& path, const std::string& name) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name, 0, 0, "", "cannot open file");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF files from Windows tools
    lines.push_back(std::move(line));
  }
  if (in.bad()) throw InputError(name, 0, 0, "", "read error");
  // Spreadsheet programs often prefix a UTF-8 byte-order mark; it is not part of the first field.
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (!lines.empty() && lines.front().starts_with(kBom)) lines.front().erase(0, kBom.size());
  return lines;
}

bool is_blank(std::string_view line) { return trim(line).empty(); }
bool is_comment(std::string_view line) { return trim(line).starts_with('#'); }

// ---- Error locations and strict numbers ---------------------------------------------------------

/// One line of an input file; every error raised while reading it points here.
class LineRef {
 public:
  LineRef(const std::string& file, int line) : file_(&file), line_(line) {}
  [[nodiscard]] int line() const { return line_; }
  [[nodiscard]] const std::string& file() const { return *file_; }
  [[noreturn]] void fail(int column, std::string_view field, const std::string& reason) const {
    throw InputError(*file_, line_, column, std::string(field), reason);
  }

 private:
  const std::string* file_;
  int line_;
};

/// The text of one field with its 1-based column and its name, for messages.
struct Field {
  std::string_view text;
  int column;
  std::string_view name;
};

/// Parses the whole field as a finite double (std::from_chars: no locale, no partial parse).
double parse_number(const LineRef& at, const Field& field) {
  const auto text = trim(field.text);
  if (text.empty()) at.fail(field.column, field.name, "missing number");
  const auto fail = [&](std::string_view reason) {
    at.fail(field.column, field.name, std::string(reason) + ": '" + std::string(text) + "'");
  };
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range) fail("number out of range");
  if (error != std::errc{} || end != text.data() + text.size()) fail("not a number");
  if (!std::isfinite(value)) fail("not a finite number (NaN/inf)");
  return value;
}

/// Parses a number that must be > 0; `what` names it in the message.
double parse_positive(const LineRef& at, const Field& field, std::string_view what) {
  const double value = parse_number(at, field);
  if (value <= 0.0) {
    at.fail(field.column, field.name,
            std::string(what) + " must be positive, got '" + std::string(trim(field.text)) + "'");
  }
  return value;
}

bool is_number(std::string_view text) {
  text = trim(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc{} && end == text.data() + text.size();
}

// ---- Metadata and reference speeds --------------------------------------------------------------

/// Water and sediment sound speeds [m/s] that complete the unit conversions of one file.
struct ReferenceSpeeds {
  std::optional<double> water;
  std::optional<double> sediment;
};

struct MetadataLine {
  std::string_view key;
  std::string_view value;
  int value_column;  ///< 1-based character column where the value starts
};

bool is_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
         c == '.';
}

/// "# key: value" with a key of [A-Za-z0-9_.-] and the colon followed by a space or the end of the
/// line; any other '#' line is a plain comment (so "# see https://..." is not a key "see https").
std::optional<MetadataLine> parse_metadata(std::string_view line) {
  const auto hash = line.find('#');
  const auto key_begin = line.find_first_not_of(" \t", hash + 1);
  const auto colon = line.find(':', key_begin);
  if (key_begin == std::string_view::npos || colon == std::string_view::npos) return std::nullopt;
  const auto key = line.substr(key_begin, colon - key_begin);
  if (key.empty() || !std::ranges::all_of(key, is_key_char)) return std::nullopt;
  if (colon + 1 < line.size() && line[colon + 1] != ' ' && line[colon + 1] != '\t') return std::nullopt;
  const auto rest = line.substr(colon + 1);
  const auto value = trim(rest);
  const auto offset = value.empty() ? rest.size() : rest.find_first_not_of(" \t");
  return MetadataLine{key, value, static_cast<int>(colon + 1 + offset + 1)};
}

/// A numeric metadata key of one file, with the line that set it.
struct DeclaredSpeed {
  std::optional<double> value;
  int line = 0;
  int column = 0;
};

/// Records one numeric metadata line; a key given twice in one file is an error.
void declare_speed(DeclaredSpeed& declared, const LineRef& at, const MetadataLine& meta) {
  if (declared.value) {
    at.fail(meta.value_column, meta.key, "given twice (first on line " + std::to_string(declared.line) + ")");
  }
  const Field field{meta.value, meta.value_column, meta.key};
  declared = {parse_positive(at, field, "sound speed"), at.line(), meta.value_column};
  if (!(*declared.value >= kLowestDeclaredSpeed && *declared.value <= kHighestDeclaredSpeed)) {
    at.fail(meta.value_column, meta.key,
            "sound speed " + std::string(trim(meta.value)) + " m/s is outside [" + format_number(kLowestDeclaredSpeed) +
                ", " + format_number(kHighestDeclaredSpeed) + "] m/s");
  }
}

/// The water density a file declares: one number in the water's range, checked where it is written.
void check_water_density(const LineRef& at, const MetadataLine& meta) {
  const double rho = parse_positive(at, {meta.value, meta.value_column, meta.key}, "density");
  if (!(rho >= kLowestWaterDensity && rho <= kHighestWaterDensity)) {
    at.fail(meta.value_column, meta.key,
            "water density " + std::string(trim(meta.value)) + " kg/m^3 is outside [" +
                format_number(kLowestWaterDensity) + ", " + format_number(kHighestWaterDensity) + "] kg/m^3");
  }
}

/// The file's value wins; if the caller gave one too they must agree, so a typo cannot silently
/// pick one of two different speeds.
std::optional<double> resolve_speed(const std::string& file, std::string_view key,
                                    const DeclaredSpeed& declared, std::optional<double> from_caller) {
  if (!declared.value) return from_caller;
  if (from_caller && !agree(*declared.value, *from_caller)) {
    throw InputError(file, declared.line, declared.column, std::string(key),
                     format_number(*declared.value) + " m/s disagrees with " + format_number(*from_caller) +
                         " m/s given as an option");
  }
  return declared.value;
}

/// Pass 1 over a sedwave CSV: all metadata, wherever it appears, so that a speed declared after a
/// row still applies to it. Text keys repeated in one file are joined with a space (long values
/// may be wrapped over several lines).
ReferenceSpeeds read_metadata(const std::string& file, const std::vector<std::string>& lines,
                              const ReadOptions& options, ObservationSet& set) {
  DeclaredSpeed water;
  DeclaredSpeed sediment;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!is_comment(lines[i])) continue;
    const auto meta = parse_metadata(lines[i]);
    if (!meta) continue;
    const LineRef at(file, static_cast<int>(i + 1));
    if (meta->key == kWaterSpeedKey) declare_speed(water, at, *meta);
    if (meta->key == kSedimentSpeedKey) declare_speed(sediment, at, *meta);
    if (meta->key == "water_density_kg_per_m3") check_water_density(at, *meta);
    auto& text = set.metadata[std::string(meta->key)];
    text += text.empty() ? "" : " ";
    text += meta->value;
  }
  return {resolve_speed(file, kWaterSpeedKey, water, options.water_sound_speed),
          resolve_speed(file, kSedimentSpeedKey, sediment, options.sediment_sound_speed)};
}

/// Where a missing speed can come from, for the message: a digitized file cannot declare one.
enum class SpeedSource { FileOrOption, OptionOnly };

/// Reason why `unit` cannot be converted with the speeds at hand, or empty if it can.
std::string missing_speed(std::string_view unit, const ReferenceSpeeds& speeds, SpeedSource source) {
  const auto hint = [source](std::string_view key) {
    return source == SpeedSource::OptionOnly
               ? std::string(" (a digitized file cannot declare one: give it as a command-line option)")
               : " ('# " + std::string(key) + ": ...' in the file, or a command-line option)";
  };
  if (is_per_wavelength(unit) && !speeds.sediment) {
    return std::string(unit) + " needs a sediment sound speed" + hint(kSedimentSpeedKey);
  }
  if (unit == "ratio" && !speeds.water) return "ratio needs a water sound speed" + hint(kWaterSpeedKey);
  if ((unit == "dB" || unit == "1") && !speeds.water) {
    return "reflection data need a water sound speed" + hint(kWaterSpeedKey);
  }
  return {};
}

// ---- Observations -------------------------------------------------------------------------------

/// Converts a value (or its sigma: every accepted unit is a pure scale factor) to SI.
double value_to_si(const QuantitySpec& spec, double value, std::string_view unit, double frequency_hz,
                   const ReferenceSpeeds& speeds) {
  const std::string unit_text(unit);
  if (is_reflection(spec.quantity)) return value;  // dB or |R|, the unit it is fitted in
  return is_attenuation(spec.quantity)
             ? attenuation_to_np_per_m(value, unit_text, frequency_hz, speeds.sediment)
             : sound_speed_to_m_per_s(value, unit_text, speeds.water);
}

/// What a value must satisfy, named for the message: attenuation is fitted in log space.
std::string_view positive_what(const QuantitySpec& spec) {
  if (spec.quantity == Quantity::Attenuation) return "attenuation (fitted in log space)";
  if (spec.quantity == Quantity::ShearAttenuation) return "shear attenuation (fitted in log space)";
  if (spec.quantity == Quantity::ShearSpeed) return "shear speed";
  return spec.name == "sound_speed" ? "sound speed" : "sound-speed ratio";
}

/// The parts of one row that are common to both formats, already checked to be usable.
struct RowValues {
  const QuantitySpec* spec;
  double frequency_hz;
  double value;                 ///< in `unit`
  std::optional<double> sigma;  ///< in `unit`
  std::string_view unit;
};

Observation make_observation(const LineRef& at, const RowValues& row, const ReferenceSpeeds& speeds) {
  Observation obs;
  obs.quantity = row.spec->quantity;
  obs.frequency_hz = row.frequency_hz;
  obs.value = value_to_si(*row.spec, row.value, row.unit, row.frequency_hz, speeds);
  if (row.sigma) obs.sigma = value_to_si(*row.spec, *row.sigma, row.unit, row.frequency_hz, speeds);
  obs.unit = std::string(row.unit);
  obs.file = at.file();
  obs.line = at.line();
  return obs;
}

// ---- sedwave observation CSV --------------------------------------------------------------------

const QuantitySpec& parse_quantity(const LineRef& at, const Field& field) {
  if (field.text.empty()) {
    at.fail(field.column, field.name, "missing quantity (accepted: " + quantity_names() + ")");
  }
  const auto* spec = find_quantity(field.text);
  if (!spec) {
    at.fail(field.column, field.name,
            "unknown quantity '" + std::string(field.text) + "' (accepted: " + quantity_names() + ")");
  }
  return *spec;
}

double parse_frequency_unit(const LineRef& at, const Field& field) {
  if (field.text.empty()) {
    at.fail(field.column, field.name, "missing unit (accepted: " + join(kFrequencyUnitNames) + ")");
  }
  const auto* unit = find_frequency_unit(field.text);
  if (!unit) {
    at.fail(field.column, field.name,
            "unknown unit '" + std::string(field.text) + "' (accepted: " + join(kFrequencyUnitNames) + ")");
  }
  return unit->to_hz;
}

void check_value_unit(const LineRef& at, const Field& field, const QuantitySpec& spec,
                      const ReferenceSpeeds& speeds, SpeedSource source) {
  const auto accepted = " for " + std::string(spec.name) + " (accepted: " + join(spec.units) + ")";
  if (field.text.empty()) at.fail(field.column, field.name, "missing unit" + accepted);
  if (!accepts_unit(spec, field.text)) {
    at.fail(field.column, field.name, "unknown unit '" + std::string(field.text) + "'" + accepted);
  }
  if (const auto reason = missing_speed(field.text, speeds, source); !reason.empty()) {
    at.fail(field.column, field.name, reason);
  }
}

/// A bottom-loss or |R| row: a loss or an |R| >= 0, a sigma in its unit (a relative default means
/// nothing for a value that may be 0), and a grazing angle in (0, 90] degrees. A passive seabed
/// reflects no more than it receives (loss >= 0 dB, |R| <= 1), but a measurement near total
/// reflection may pass that bound by its noise: a loss below 0 dB is refused only beyond three sigmas.
Observation parse_bottom_loss_row(const LineRef& at, const std::function<Field(int)>& field, const QuantitySpec& spec,
                                  double frequency_hz, const ReferenceSpeeds& speeds) {
  const double value = parse_number(at, field(4));
  if (spec.quantity == Quantity::ReflectionMagnitude && value < 0.0) {
    at.fail(4, "value", "|R| must be >= 0, got '" + std::string(field(4).text) + "'");
  }
  check_value_unit(at, field(5), spec, speeds, SpeedSource::FileOrOption);
  if (field(6).text.empty()) at.fail(6, "sigma", "a reflection row needs its 1-sigma uncertainty in its own unit");
  const double sigma = parse_positive(at, field(6), "sigma");
  if (spec.quantity == Quantity::BottomLoss && value < -3.0 * sigma) {
    at.fail(4, "value", "bottom loss " + std::string(field(4).text) + " dB is below 0 dB (|R| > 1) by more than three "
                        "of its sigmas: a passive seabed reflects no more than it receives");
  }
  if (field(7).text.empty()) {
    at.fail(7, "grazing_angle_deg", "a reflection row needs its grazing angle in degrees (header '" +
                                        std::string(kAngleHeaderText) + "')");
  }
  const double angle = parse_number(at, field(7));
  if (!(angle > 0.0 && angle <= 90.0)) {
    at.fail(7, "grazing_angle_deg", "grazing angle must be in (0, 90] degrees, got '" + std::string(field(7).text) + "'");
  }
  Observation obs = make_observation(at, {&spec, frequency_hz, value, sigma, field(5).text}, speeds);
  obs.grazing_angle = angle * std::numbers::pi / 180.0;
  return obs;
}

Observation parse_csv_row(const LineRef& at, const std::vector<std::string_view>& cells,
                          const ReferenceSpeeds& speeds) {
  const auto field = [&cells](int column) {
    const auto i = static_cast<std::size_t>(column - 1);
    return Field{i < cells.size() ? cells[i] : std::string_view{}, column, kHeader[i]};
  };
  const auto& spec = parse_quantity(at, field(1));
  if (is_reflection(spec.quantity)) {
    const double frequency = parse_positive(at, field(2), "frequency");
    return parse_bottom_loss_row(at, field, spec, frequency * parse_frequency_unit(at, field(3)), speeds);
  }
  if (!field(7).text.empty()) at.fail(7, "grazing_angle_deg", "only a reflection row (bottom loss, |R|) has a grazing angle");
  const double frequency = parse_positive(at, field(2), "frequency");
  const double to_hz = parse_frequency_unit(at, field(3));
  const double value = parse_positive(at, field(4), positive_what(spec));
  check_value_unit(at, field(5), spec, speeds, SpeedSource::FileOrOption);
  std::optional<double> sigma;
  if (!field(6).text.empty()) sigma = parse_positive(at, field(6), "sigma");
  return make_observation(at, {&spec, frequency * to_hz, value, sigma, field(5).text}, speeds);
}

void check_header(const LineRef& at, const std::vector<std::string_view>& cells) {
  if (cells.size() != kShortHeader && cells.size() != kHeader.size()) {
    at.fail(0, "",
            "header must have the 6 columns '" + std::string(kHeaderText) + "' or the 7 columns '" +
                std::string(kAngleHeaderText) + "', found " + std::to_string(cells.size()));
  }
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] != kHeader[i]) {
      at.fail(
          static_cast<int>(i + 1), kHeader[i],
          "header column must be '" + std::string(kHeader[i]) + "', found '" + std::string(cells[i]) + "'");
    }
  }
}

/// A header is recognised by its first cell, case-insensitively, so that a misspelt header is
/// reported as such rather than as a data row before the header.
bool looks_like_header(const std::vector<std::string_view>& cells) {
  return std::ranges::equal(cells.front(), kHeader.front(),
                            [](char a, char b) { return (a | 0x20) == b; });  // ASCII lower-case
}

/// Pass 2: the header and the data rows.
void read_rows(const std::string& file, const std::vector<std::string>& lines, const ReferenceSpeeds& speeds,
               ObservationSet& set) {
  int header_line = 0;
  std::size_t columns = kShortHeader;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (is_blank(lines[i]) || is_comment(lines[i])) continue;
    const LineRef at(file, static_cast<int>(i + 1));
    const auto cells = split(lines[i], ",");
    if (looks_like_header(cells)) {
      if (header_line != 0) {
        at.fail(0, "", "duplicated header (first on line " + std::to_string(header_line) + ")");
      }
      check_header(at, cells);
      header_line = at.line();
      columns = cells.size();
      continue;
    }
    if (header_line == 0) {
      at.fail(0, "", "data row before the header line '" + std::string(kHeaderText) + "'");
    }
    if (cells.size() != columns) {
      at.fail(0, "",
              "wrong number of columns: expected " + std::to_string(columns) + " (" +
                  std::string(columns == kShortHeader ? kHeaderText : kAngleHeaderText) + "), found " +
                  std::to_string(cells.size()));
    }
    set.observations.push_back(parse_csv_row(at, cells, speeds));
  }
  if (header_line == 0) throw InputError(file, 0, 0, "", "no header line '" + std::string(kHeaderText) + "'");
}

void require_content(const std::string& file, const std::vector<std::string>& lines) {
  if (std::ranges::all_of(lines, is_blank)) throw InputError(file, 0, 0, "", "empty file");
}

void require_rows(const std::string& file, const ObservationSet& set) {
  if (set.observations.empty()) throw InputError(file, 0, 0, "", "no data rows");
}

// ---- WebPlotDigitizer export --------------------------------------------------------------------

/// The caller's description of a digitised file, checked once before any row is read.
struct DigitizedSpec {
  const QuantitySpec* quantity;
  double to_hz;
};

DigitizedSpec check_columns(const std::string& file, const DigitizedColumns& columns,
                            const ReferenceSpeeds& speeds) {
  const LineRef at(file, 0);
  const auto& quantity = parse_quantity(at, {columns.quantity, 0, "quantity"});
  if (is_reflection(quantity.quantity)) {
    at.fail(0, "quantity", "a digitized file has no angle column: give reflection data in a sedwave observation CSV");
  }
  const double to_hz = parse_frequency_unit(at, {columns.frequency_unit, 0, "frequency_unit"});
  check_value_unit(at, {columns.value_unit, 0, "value_unit"}, quantity, speeds, SpeedSource::OptionOnly);
  if (columns.relative_sigma && !(std::isfinite(*columns.relative_sigma) && *columns.relative_sigma > 0.0)) {
    at.fail(0, "relative_sigma",
            "relative sigma must be a positive finite number, got " + format_number(*columns.relative_sigma));
  }
  return {&quantity, to_hz};
}

constexpr std::string_view kDigitizedSeparators = ",;\t";

/// One data line of a digitised export: its 1-based line number and its cells.
struct DigitizedLine {
  int line;
  std::vector<std::string_view> cells;
};

/// The data lines of a digitised export. WebPlotDigitizer may write one header line (axis or
/// dataset names): a first line in which no cell is a number. A line with some numeric cells is
/// data, so bad data is never skipped.
std::vector<DigitizedLine> digitized_data_lines(const std::vector<std::string>& lines) {
  std::vector<DigitizedLine> data;
  bool first = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (is_blank(lines[i])) continue;
    auto cells = split(lines[i], kDigitizedSeparators);
    const bool header = first && std::ranges::none_of(cells, is_number);
    first = false;
    if (!header) data.push_back({static_cast<int>(i + 1), std::move(cells)});
  }
  return data;
}

/// A file of x,y number pairs is a digitised export given where an observation CSV belongs: say
/// how to read it instead of reporting its first row as a row before the header.
void reject_digitized_export(const std::string& file, const std::vector<std::string>& lines) {
  const auto data = digitized_data_lines(lines);
  const bool two_numbers = std::ranges::all_of(data, [](const DigitizedLine& d) {
    return d.cells.size() == 2 && std::ranges::all_of(d.cells, is_number);
  });
  if (!data.empty() && two_numbers) {
    throw InputError(file, 0, 0, "",
                     "this looks like a two-column digitised export; read it with --digitized-file " + file +
                         " --digitized QUANTITY:FREQ_UNIT:VALUE_UNIT (docs/file-formats.md)");
  }
}

Observation parse_digitized_row(const LineRef& at, const std::vector<std::string_view>& cells,
                                const DigitizedSpec& spec, const DigitizedColumns& columns,
                                const ReferenceSpeeds& speeds) {
  if (cells.size() != 2) {
    at.fail(0, "",
            "wrong number of columns: expected 2 (x = frequency, y = value), found " +
                std::to_string(cells.size()));
  }
  const double frequency = parse_positive(at, {cells[0], 1, "frequency"}, "frequency");
  const double value = parse_positive(at, {cells[1], 2, "value"}, positive_what(*spec.quantity));
  std::optional<double> sigma;
  if (columns.relative_sigma) sigma = *columns.relative_sigma * value;
  return make_observation(at, {spec.quantity, frequency * spec.to_hz, value, sigma, columns.value_unit},
                          speeds);
}

std::string error_message(const std::string& file, int line, int column, const std::string& field,
                          const std::string& reason) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "..." + std::to_string().
  std::string message = file;
  if (line > 0) message.append(":").append(std::to_string(line));
  if (line > 0 && column > 0) message.append(":").append(std::to_string(column));
  message.append(": ");
  if (!field.empty()) message.append("field '").append(field).append("': ");
  return message.append(reason);
}

}  // namespace

// ---- Public interface ---------------------------------------------------------------------------

InputError::InputError(std::string file, int line, int column, std::string field, const std::string& reason)
    : std::runtime_error(error_message(file, line, column, field, reason)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      field_(std::move(field)) {}

void ObservationSet::append(const ObservationSet& other) {
  // Checked before anything changes, so a failed append leaves this set as it was.
  if (water_sound_speed && other.water_sound_speed && !agree(*water_sound_speed, *other.water_sound_speed)) {
    const std::string file = other.observations.empty() ? std::string{} : other.observations.front().file;
    throw InputError(file, 0, 0, std::string(kWaterSpeedKey),
                     format_number(*other.water_sound_speed) + " m/s disagrees with " +
                         format_number(*water_sound_speed) + " m/s of the files read before");
  }
  if (!water_sound_speed) water_sound_speed = other.water_sound_speed;
  observations.insert(observations.end(), other.observations.begin(), other.observations.end());
  for (const auto& [key, value] : other.metadata) {
    auto& mine = metadata[key];
    if (mine.empty()) {
      mine = value;
    } else if (mine != value) {
      mine += "; " + value;
    }
  }
}

ObservationSet read_observation_csv(const std::filesystem::path& file, const ReadOptions& options) {
  const std::string name = file.string();
  const auto lines = read_lines(file, name);
  require_content(name, lines);
  reject_digitized_export(name, lines);
  ObservationSet set;
  const auto speeds = read_metadata(name, lines, options, set);
  set.water_sound_speed = speeds.water;
  read_rows(name, lines, speeds, set);
  require_rows(name, set);
  return set;
}

ObservationSet read_digitized_csv(const std::filesystem::path& file, const DigitizedColumns& columns,
                                  const ReadOptions& options) {
  const std::string name = file.string();
  const auto lines = read_lines(file, name);
  const ReferenceSpeeds speeds{options.water_sound_speed, options.sediment_sound_speed};
  const auto spec = check_columns(name, columns, speeds);
  require_content(name, lines);
  ObservationSet set;
  set.water_sound_speed = speeds.water;
  for (const DigitizedLine& d : digitized_data_lines(lines)) {
    set.observations.push_back(parse_digitized_row(LineRef(name, d.line), d.cells, spec, columns, speeds));
  }
  require_rows(name, set);
  return set;
}

double frequency_to_hz(double value, const std::string& unit) {
  const auto* found = find_frequency_unit(unit);
  if (!found) {
    throw std::invalid_argument("unknown frequency unit '" + unit +
                                "' (accepted: " + join(kFrequencyUnitNames) + ")");
  }
  return value * found->to_hz;
}

double attenuation_to_np_per_m(double value, const std::string& unit, double frequency_hz,
                               std::optional<double> sediment_sound_speed) {
  if (unit == "Np/m") return value;
  if (unit == "dB/m") return value * kNeperPerDecibel;
  // The k-value convention: alpha [dB/m] = k f [kHz].
  if (unit == "dB/m/kHz") return value * (frequency_hz / 1e3) * kNeperPerDecibel;
  if (is_per_wavelength(unit)) {
    if (!sediment_sound_speed || !(*sediment_sound_speed > 0.0)) {
      throw std::invalid_argument(unit + " needs a positive sediment sound speed");
    }
    // One wavelength is c/f metres, so "per wavelength" is "per metre" times f/c.
    return value * (frequency_hz / *sediment_sound_speed) * kNeperPerDecibel;
  }
  throw std::invalid_argument("unknown attenuation unit '" + unit +
                              "' (accepted: " + join(kAttenuationUnits) + ")");
}

double sound_speed_to_m_per_s(double value, const std::string& unit,
                              std::optional<double> water_sound_speed) {
  if (unit == "m/s") return value;
  if (unit == "km/s") return value * 1e3;
  if (unit == "ratio") {
    if (!water_sound_speed || !(*water_sound_speed > 0.0)) {
      throw std::invalid_argument("ratio needs a positive water sound speed");
    }
    return value * *water_sound_speed;
  }
  throw std::invalid_argument("unknown sound-speed unit '" + unit + "' (accepted: m/s, km/s, ratio)");
}

const char* quantity_name(Quantity q) {
  // The first name of each quantity in the table: sound_speed before sound_speed_ratio.
  return std::ranges::find(kQuantities, q, &QuantitySpec::quantity)->name.data();
}

const char* quantity_unit(Quantity q) {
  if (q == Quantity::BottomLoss) return "dB";
  if (q == Quantity::ReflectionMagnitude) return "1";
  return is_attenuation(q) ? "Np/m" : "m/s";
}

double water_density_of(const ObservationSet& data) {
  const auto it = data.metadata.find("water_density_kg_per_m3");
  if (it == data.metadata.end()) return 1025.0;
  double rho = 0.0;
  const std::string& text = it->second;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), rho);
  if (error != std::errc{} || end != text.data() + text.size() || !(rho >= kLowestWaterDensity) ||
      !(rho <= kHighestWaterDensity)) {
    throw std::invalid_argument("metadata 'water_density_kg_per_m3' = '" + text + "' is not one number in [" +
                                format_number(kLowestWaterDensity) + ", " + format_number(kHighestWaterDensity) +
                                "] kg/m^3");
  }
  return rho;
}

}  // namespace sedwave::inversion
