#include "sedwave/sediment/propagation_files.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace sedwave::sediment {

namespace {

/// dB per neper: 20 log10(e), the toolbox's 8.6858896.
constexpr double kDbPerNeper = 8.6858896380650365;
constexpr double kDegree = std::numbers::pi / 180.0;

std::string number(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

/// One line of list-directed input: its fields, with a comment ('!') and everything after a '/'
/// dropped; quoted fields lose their quotes.
struct FortranLine {
  std::vector<std::string> fields;
  std::vector<bool> quoted;
  int number = 0;
};

FortranLine split_fortran_line(const std::string& text, int line_number) {
  FortranLine line;
  line.number = line_number;
  std::string field;
  bool in_field = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'' || c == '"') {
      const std::size_t end = text.find(c, i + 1);
      line.fields.push_back(text.substr(i + 1, end == std::string::npos ? std::string::npos : end - i - 1));
      line.quoted.push_back(true);
      if (end == std::string::npos) break;
      i = end;
      continue;
    }
    if (c == '!' || c == '/') break;
    if (c == ' ' || c == '\t' || c == ',' || c == '\r') {
      if (in_field) {
        line.fields.push_back(field);
        line.quoted.push_back(false);
        field.clear();
        in_field = false;
      }
      continue;
    }
    field += c;
    in_field = true;
  }
  if (in_field) {
    line.fields.push_back(field);
    line.quoted.push_back(false);
  }
  return line;
}

/// Reads the next line with at least one field (list-directed input skips nothing else, but a
/// blank line would hold no value).
class FortranReader {
 public:
  FortranReader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  FortranLine next(const char* what) {
    std::string text;
    while (std::getline(in_, text)) {
      ++line_number_;
      FortranLine line = split_fortran_line(text, line_number_);
      if (!line.fields.empty()) return line;
    }
    fail(line_number_, std::string("ended before ") + what);
  }

  double number(const FortranLine& line, std::size_t index, const char* what, bool optional = false) {
    if (index >= line.fields.size()) {
      if (optional) return 0.0;
      fail(line.number, std::string(what) + " missing");
    }
    const std::string& s = line.fields[index];
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || !std::isfinite(value)) fail(line.number, std::string(what) + " '" + s + "' is not a number");
    return value;
  }

  std::string text(const FortranLine& line, const char* what) {
    if (!line.quoted.front()) fail(line.number, std::string(what) + " must be quoted, found '" + line.fields.front() + "'");
    return line.fields.front();
  }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw std::invalid_argument(name_ + ":" + std::to_string(line) + ": " + message);
  }

 private:
  std::istream& in_;
  std::string name_;
  int line_number_ = 0;
};

}  // namespace

char attenuation_unit_letter(AttenuationUnit unit) {
  switch (unit) {
    case AttenuationUnit::NepersPerMetre: return 'N';
    case AttenuationUnit::DbPerMetre: return 'M';
    case AttenuationUnit::DbPerMetreKhz: return 'F';
    case AttenuationUnit::DbPerWavelength: return 'W';
    case AttenuationUnit::QualityFactor: return 'Q';
  }
  return '?';
}

AttenuationUnit attenuation_unit_from_letter(char letter) {
  switch (letter) {
    case 'N': return AttenuationUnit::NepersPerMetre;
    case 'M': return AttenuationUnit::DbPerMetre;
    case 'F': return AttenuationUnit::DbPerMetreKhz;
    case 'W': return AttenuationUnit::DbPerWavelength;
    case 'Q': return AttenuationUnit::QualityFactor;
    default: break;
  }
  throw std::invalid_argument(std::string("attenuation unit '") + letter +
                              "': N (Np/m), M (dB/m), F (dB/(m kHz)), W (dB/wavelength) or Q (quality factor) "
                              "expected");
}

double attenuation_in_unit(double alpha, double speed, double frequency_hz, AttenuationUnit unit) {
  switch (unit) {
    case AttenuationUnit::NepersPerMetre: return alpha;
    case AttenuationUnit::DbPerMetre: return alpha * kDbPerNeper;
    case AttenuationUnit::DbPerMetreKhz: return alpha * kDbPerNeper * 1000.0 / frequency_hz;
    case AttenuationUnit::DbPerWavelength: return alpha * kDbPerNeper * speed / frequency_hz;
    case AttenuationUnit::QualityFactor:  // alpha = omega / (2 c Q); no loss is written Q = 0
      return alpha == 0.0 ? 0.0 : 2.0 * std::numbers::pi * frequency_hz / (2.0 * speed * alpha);
  }
  return 0.0;
}

double attenuation_from_unit(double value, double speed, double frequency_hz, AttenuationUnit unit) {
  switch (unit) {
    case AttenuationUnit::NepersPerMetre: return value;
    case AttenuationUnit::DbPerMetre: return value / kDbPerNeper;
    case AttenuationUnit::DbPerMetreKhz: return value * frequency_hz / (1000.0 * kDbPerNeper);
    case AttenuationUnit::DbPerWavelength: return value * frequency_hz / (kDbPerNeper * speed);
    case AttenuationUnit::QualityFactor:
      return value == 0.0 ? 0.0 : 2.0 * std::numbers::pi * frequency_hz / (2.0 * speed * value);
  }
  return 0.0;
}

std::vector<ReflectionTableRow> toolbox_reflection_table(std::span<const double> grazing_deg,
                                                         std::span<const std::complex<double>> r) {
  if (grazing_deg.size() != r.size()) throw std::invalid_argument("reflection table: angles and R differ in count");
  std::vector<ReflectionTableRow> rows;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (i > 0 && !(grazing_deg[i] > grazing_deg[i - 1])) {
      throw std::invalid_argument("reflection table: grazing angles must increase");
    }
    double phase = -std::arg(r[i]) / kDegree;
    if (!rows.empty()) {  // unwrap: the nearest branch to the previous angle's phase
      phase += 360.0 * std::round((rows.back().phase_deg - phase) / 360.0);
    }
    rows.push_back({grazing_deg[i], std::abs(r[i]), phase});
  }
  return rows;
}

void write_reflection_table(std::ostream& out, const std::vector<ReflectionTableRow>& rows) {
  out << rows.size() << "\n";
  for (const ReflectionTableRow& row : rows) {
    out << number(row.grazing_deg) << " " << number(row.magnitude) << " " << number(row.phase_deg) << "\n";
  }
}

std::vector<ReflectionTableRow> read_reflection_table(std::istream& in, const std::string& name) {
  FortranReader reader(in, name);
  const FortranLine count_line = reader.next("the number of angles");
  const double count = reader.number(count_line, 0, "number of angles NTHETA");
  if (count < 1.0 || count != std::floor(count)) reader.fail(count_line.number, "NTHETA must be a positive integer");
  std::vector<ReflectionTableRow> rows;
  for (int i = 0; i < static_cast<int>(count); ++i) {
    const FortranLine line = reader.next("all NTHETA angles were read");
    rows.push_back({reader.number(line, 0, "angle [deg]"), reader.number(line, 1, "|R|"),
                    reader.number(line, 2, "phase [deg]")});
  }
  return rows;
}

AttenuationUnit ToolboxEnvironment::attenuation_unit() const {
  if (options.size() < 3) throw std::invalid_argument("environment options '" + options + "' carry no attenuation unit");
  return attenuation_unit_from_letter(options[2]);
}

ToolboxEnvironment toolbox_environment(const std::string& title, double frequency_hz, double water_depth,
                                       const AcousticMedium& halfspace, AttenuationUnit unit) {
  const double cp = halfspace.compressional_speed, cs = halfspace.shear_speed;
  // Built whole: GCC 12 at -O3 warns falsely (-Wrestrict) on assigning short literals to the members.
  return {title,
          frequency_hz,
          1,
          std::string{'C', 'V', attenuation_unit_letter(unit)},  // C-linear sound speed, vacuum above, the unit
          std::string(1, 'A'),                                   // an acousto-elastic half-space below
          {water_depth, cp, cs, halfspace.density / 1000.0,
           attenuation_in_unit(halfspace.compressional_attenuation, cp, frequency_hz, unit),
           cs > 0.0 ? attenuation_in_unit(halfspace.shear_attenuation, cs, frequency_hz, unit) : 0.0}};
}

void write_toolbox_environment(std::ostream& out, const ToolboxEnvironment& env, double water_speed,
                               double water_density) {
  const char unit = env.options.size() >= 3 ? env.options[2] : '?';
  const char* unit_name = unit == 'N' ? "Np/m" : unit == 'M' ? "dB/m" : unit == 'F' ? "dB/(m kHz)"
                          : unit == 'W' ? "dB/wavelength" : unit == 'Q' ? "quality factor Q" : "?";
  const ToolboxHalfspace& h = env.halfspace;
  const std::string rho_w = number(water_density / 1000.0);
  out << "'" << env.title << "'  ! title\n"
      << number(env.frequency_hz) << "  ! frequency [Hz]\n"
      << env.media << "  ! number of media\n"
      << "'" << env.options << "'  ! options: C-linear sound speed, vacuum above, attenuation in " << unit_name
      << "\n"
      << "0 0.0 " << number(h.depth) << "  ! NMESH (0: the program's choice), roughness [m], water depth [m]\n"
      << "0.0 " << number(water_speed) << " 0.0 " << rho_w
      << " 0.0 0.0 /  ! depth [m], c_p, c_s [m/s], density [g/cm^3], alpha_p, alpha_s\n"
      << number(h.depth) << " " << number(water_speed) << " 0.0 " << rho_w << " 0.0 0.0 /\n"
      << "'" << env.bottom_option << "' 0.0  ! bottom: acousto-elastic half-space, roughness [m]\n"
      << number(h.depth) << " " << number(h.compressional_speed) << " " << number(h.shear_speed) << " "
      << number(h.density) << " " << number(h.compressional_attenuation) << " " << number(h.shear_attenuation)
      << " /  ! depth [m], c_p, c_s [m/s], density [g/cm^3], alpha_p, alpha_s [" << unit_name << "]\n";
}

ToolboxEnvironment read_toolbox_environment(std::istream& in, const std::string& name) {
  FortranReader reader(in, name);
  ToolboxEnvironment env;
  env.title = reader.text(reader.next("the title"), "title");
  env.frequency_hz = reader.number(reader.next("the frequency"), 0, "frequency [Hz]");
  const FortranLine media_line = reader.next("the number of media");
  const double media = reader.number(media_line, 0, "number of media NMEDIA");
  if (media < 1.0 || media != std::floor(media)) reader.fail(media_line.number, "NMEDIA must be a positive integer");
  env.media = static_cast<int>(media);
  const FortranLine options_line = reader.next("the options");
  env.options = reader.text(options_line, "options");
  if (env.options.size() < 3) reader.fail(options_line.number, "options '" + env.options + "' name no attenuation unit");
  (void)attenuation_unit_from_letter(env.options[2]);
  if (env.options[0] == 'A' || env.options[0] == 'Q' || env.options[0] == 'H') {
    reader.fail(options_line.number, "an analytic or file sound-speed profile ('" + env.options.substr(0, 1) +
                                         "') is not read here");
  }
  if (env.options.size() > 3 && env.options[3] == 'B') {
    reader.fail(options_line.number, "biological attenuation layers ('B') are not read here");
  }
  if (env.options.size() > 3 && env.options[3] == 'F') (void)reader.next("the Francois-Garrison line");
  if (env.options[1] == 'A') (void)reader.next("the top half-space line");
  for (int m = 0; m < env.media; ++m) {
    const FortranLine mesh = reader.next("a medium's NMESH, SIGMA, Z line");
    const double bottom = reader.number(mesh, 2, "depth of the medium's bottom Z(NSSP) [m]");
    for (;;) {
      const FortranLine point = reader.next("the sound-speed profile reached the medium's bottom");
      const double z = reader.number(point, 0, "sound-speed profile depth [m]");
      if (std::abs(z - bottom) <= 1e-9 * std::max(1.0, std::abs(bottom))) break;
      if (z > bottom) reader.fail(point.number, "profile depth " + number(z) + " m lies below the medium's bottom " +
                                                    number(bottom) + " m");
    }
  }
  const FortranLine bottom_line = reader.next("the bottom option");
  env.bottom_option = reader.text(bottom_line, "bottom option");
  if (env.bottom_option.empty() || env.bottom_option[0] != 'A') {
    reader.fail(bottom_line.number, "bottom option '" + env.bottom_option +
                                        "': only an acousto-elastic half-space ('A') carries a seabed line");
  }
  const FortranLine h = reader.next("the bottom half-space line");
  env.halfspace = {reader.number(h, 0, "half-space depth [m]"),
                   reader.number(h, 1, "half-space c_p [m/s]"),
                   reader.number(h, 2, "half-space c_s [m/s]", true),
                   reader.number(h, 3, "half-space density [g/cm^3]", true),
                   reader.number(h, 4, "half-space alpha_p", true),
                   reader.number(h, 5, "half-space alpha_s", true)};
  return env;
}

}  // namespace sedwave::sediment
