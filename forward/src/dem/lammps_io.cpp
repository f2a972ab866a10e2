#include "sedwave/forward/dem/lammps_io.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <unordered_set>

#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/io/atomic_file.hpp"

namespace sedwave::forward::dem {
namespace {

/// Every double written survives a text round trip bit for bit with this many digits.
constexpr int kFullPrecision = std::numeric_limits<double>::max_digits10;

/// Reads a text file line by line and names the file and line in its errors ("path:12: ...").
class LineReader {
 public:
  explicit LineReader(std::string path) : path_(std::move(path)), in_(path_) {
    if (!in_) throw std::runtime_error(path_ + ": cannot open");
  }
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    // A line without its newline can only be the last one, possibly cut short by a killed writer.
    terminated_ = !in_.eof();
    return true;
  }
  /// The next line, which must exist.
  std::string require(const std::string& expected) {
    std::string line;
    if (!next(line)) fail("unexpected end of file, expected " + expected);
    return line;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ":" + std::to_string(number_) + ": " + what);
  }
  [[nodiscard]] bool last_line_terminated() const { return terminated_; }
  /// Byte offset just past the last line read.
  [[nodiscard]] std::uintmax_t offset() { return static_cast<std::uintmax_t>(in_.tellg()); }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::size_t number_ = 0;
  bool terminated_ = true;
};

std::string strip_comment(const std::string& line) {
  const auto hash = line.find('#');
  return hash == std::string::npos ? line : line.substr(0, hash);
}

bool starts_with(const std::string& line, const char* prefix) { return line.rfind(prefix, 0) == 0; }

std::vector<std::string> split(const std::string& line) {
  std::istringstream words(line);
  std::vector<std::string> out;
  for (std::string w; words >> w;) out.push_back(w);
  return out;
}

/// Parses one whole token as a number (from_chars: exact, locale-free), or fails naming the line.
template <typename T>
T parse(const std::string& token, const LineReader& r, const std::string& what) {
  T value{};
  const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);  // from_chars rejects '+'
  const char* end = token.data() + token.size();
  const auto [ptr, error] = std::from_chars(begin, end, value);
  if constexpr (std::is_floating_point_v<T>) {
    // from_chars refuses subnormal numbers (out of range), which a file may hold (e.g. a spin of
    // 1e-320): strtod gives them; a true overflow stays an error.
    if (error == std::errc::result_out_of_range && ptr == end) {
      value = static_cast<T>(std::strtod(token.c_str(), nullptr));
      if (std::isfinite(value)) return value;
    }
  }
  if (error != std::errc{} || ptr != end) r.fail("bad " + what + " '" + token + "'");
  return value;
}

// ---- data files ----------------------------------------------------------------------------------

void read_header_line(const std::string& body, const LineReader& r, std::int64_t& n_atoms, Box& box) {
  const std::vector<std::string> words = split(body);
  if (words.size() == 2 && words[1] == "atoms") {
    n_atoms = parse<std::int64_t>(words[0], r, "atom count");
    if (n_atoms < 0) r.fail("atom count " + words[0] + ": accepted range [0, inf)");
  }
  for (int a = 0; a < 3; ++a) {
    const std::string lo = std::string(1, char('x' + a)) + "lo";
    if (words.size() == 4 && words[2] == lo) {
      box.lo[a] = parse<double>(words[0], r, lo);
      box.hi[a] = parse<double>(words[1], r, std::string(1, char('x' + a)) + "hi");
      if (!(box.hi[a] > box.lo[a]) || !std::isfinite(box.hi[a] - box.lo[a]))
        r.fail(lo + " " + words[0] + " and " + std::string(1, char('x' + a)) + "hi " + words[1] +
               ": the box must have finite, positive extent");
    }
  }
}

}  // namespace

LammpsData read_lammps_data(const std::string& path, const std::function<bool(const Grain&)>& keep) {
  LineReader r(path);
  LammpsData data;
  std::string line;
  r.next(line);  // title
  std::int64_t n_atoms = -1;
  std::string section;
  std::unordered_map<std::int64_t, std::size_t> index;  // kept grains: where they are in data.grains
  std::unordered_set<std::int64_t> ids;                 // every atom of the file, kept or not
  std::int64_t atoms_read = 0;
  while (r.next(line)) {
    const std::string body = strip_comment(line);
    const std::vector<std::string> words = split(body);
    if (words.empty()) continue;
    if (std::isalpha(static_cast<unsigned char>(words[0][0]))) {  // a section keyword
      section = words[0];
      const std::vector<std::string> style = split(line.substr(std::min(line.size(), body.size() + 1)));
      if (section == "Atoms" && !style.empty() && style[0] != "sphere")
        r.fail("atom_style " + style[0] + " is not supported (atom_style sphere expected)");
      continue;
    }
    if (section.empty()) {
      read_header_line(body, r, n_atoms, data.box);
    } else if (section == "Atoms") {
      // id type diameter density x y z [ix iy iz]
      if (words.size() != 7 && words.size() != 10)
        r.fail("bad Atoms line (atom_style sphere: id type diameter density x y z expected): " + line);
      Grain g;
      g.id = parse<std::int64_t>(words[0], r, "atom id");
      g.group = parse<std::int32_t>(words[1], r, "atom type");
      if (g.group < 1) r.fail("atom type " + words[1] + ": accepted range [1, 2147483647] (LAMMPS types count from 1)");
      const double diameter = parse<double>(words[2], r, "diameter");
      const double density = parse<double>(words[3], r, "density");
      for (int a = 0; a < 3; ++a) g.position[a] = parse<double>(words[4 + static_cast<std::size_t>(a)], r, "coordinate");
      if (!(diameter > 0.0) || !(density > 0.0) || !std::isfinite(diameter) || !std::isfinite(density))
        r.fail("diameter and density must be positive and finite: " + line);
      if (!std::isfinite(g.position.x) || !std::isfinite(g.position.y) || !std::isfinite(g.position.z))
        r.fail("coordinates must be finite: " + line);
      if (!ids.insert(g.id).second) r.fail("duplicate atom id " + words[0]);
      g.radius = 0.5 * diameter;
      g.mass = grain_mass(density, diameter);
      ++atoms_read;
      if (keep && !keep(g)) continue;
      index.emplace(g.id, data.grains.size());
      data.grains.push_back(g);
    } else if (section == "Velocities") {
      // id vx vy vz wx wy wz
      if (words.size() != 7) r.fail("bad Velocities line (id vx vy vz wx wy wz expected): " + line);
      const auto id = parse<std::int64_t>(words[0], r, "atom id");
      Vec3 v, w;
      for (int a = 0; a < 3; ++a) {
        v[a] = parse<double>(words[1 + static_cast<std::size_t>(a)], r, "velocity");
        w[a] = parse<double>(words[4 + static_cast<std::size_t>(a)], r, "angular velocity");
      }
      if (!std::isfinite(v.x + v.y + v.z + w.x + w.y + w.z)) r.fail("velocities must be finite: " + line);
      if (!ids.contains(id)) r.fail("Velocities entry for atom id " + words[0] + ", which is not in the Atoms section");
      const auto it = index.find(id);
      if (it == index.end()) continue;  // another rank's grain, or filtered out
      data.grains[it->second].velocity = v;
      data.grains[it->second].angular_velocity = w;
    }
  }
  if (n_atoms >= 0 && atoms_read != n_atoms)
    throw std::runtime_error(path + ": header announces " + std::to_string(n_atoms) + " atoms, found " +
                             std::to_string(atoms_read));
  return data;
}

void write_lammps_data(const std::string& path, const Box& box, std::span<const Grain> grains) {
  // Whole or not at all: a kill or a full disk leaves the previous file (io::write_text_atomically).
  io::write_text_atomically(path, [&](std::ostream& out) {
    int types = 1;
    for (const Grain& g : grains) types = std::max(types, g.group);
    out << "LAMMPS data file written by sedwave (atom_style sphere)\n\n"
        << grains.size() << " atoms\n" << types << " atom types\n\n" << std::setprecision(kFullPrecision);
    for (int a = 0; a < 3; ++a)
      out << box.lo[a] << ' ' << box.hi[a] << ' ' << char('x' + a) << "lo " << char('x' + a) << "hi\n";
    out << "\nAtoms # sphere\n\n";
    for (const Grain& g : grains) {
      const double d = 2.0 * g.radius;
      out << g.id << ' ' << std::max(g.group, 1) << ' ' << d << ' ' << g.mass / grain_mass(1.0, d) << ' '
          << g.position.x << ' ' << g.position.y << ' ' << g.position.z << '\n';
    }
    out << "\nVelocities\n\n";
    for (const Grain& g : grains)
      out << g.id << ' ' << g.velocity.x << ' ' << g.velocity.y << ' ' << g.velocity.z << ' '
          << g.angular_velocity.x << ' ' << g.angular_velocity.y << ' ' << g.angular_velocity.z << '\n';
  });
}

// ---- dumps ---------------------------------------------------------------------------------------

namespace {

/// Reads the next frame; false at the end of the file. A malformed or truncated frame fails,
/// naming its line.
bool read_dump_frame(LineReader& r, DumpFrame& f) {
  std::string line;
  do {
    if (!r.next(line)) return false;
  } while (split(line).empty());
  if (!starts_with(line, "ITEM: TIMESTEP")) r.fail("expected 'ITEM: TIMESTEP', found: " + line);
  f = DumpFrame{};
  f.step = parse<std::int64_t>(r.require("the time step"), r, "time step");
  if (!starts_with(r.require("ITEM: NUMBER OF ATOMS"), "ITEM: NUMBER OF ATOMS"))
    r.fail("expected 'ITEM: NUMBER OF ATOMS'");
  const auto n = parse<std::int64_t>(r.require("the number of atoms"), r, "number of atoms");
  line = r.require("ITEM: BOX BOUNDS");
  if (!starts_with(line, "ITEM: BOX BOUNDS")) r.fail("expected 'ITEM: BOX BOUNDS', found: " + line);
  const std::vector<std::string> flags = split(line.substr(16));
  if (flags.size() != 3) r.fail("only orthogonal boxes are supported: " + line);
  for (std::size_t a = 0; a < 3; ++a) f.box.periodic[a] = flags[a] == "pp";
  for (int a = 0; a < 3; ++a) {
    const std::vector<std::string> bounds = split(r.require("box bounds"));
    if (bounds.size() != 2) r.fail("expected 'lo hi' box bounds");
    f.box.lo[a] = parse<double>(bounds[0], r, "box bound");
    f.box.hi[a] = parse<double>(bounds[1], r, "box bound");
  }
  line = r.require("ITEM: ATOMS");
  if (!starts_with(line, "ITEM: ATOMS")) r.fail("expected 'ITEM: ATOMS', found: " + line);
  const std::vector<std::string> columns = split(line.substr(11));
  constexpr std::size_t kMissing = std::numeric_limits<std::size_t>::max();
  std::size_t col_id = kMissing;
  std::size_t col_x[3] = {kMissing, kMissing, kMissing}, col_v[3] = {kMissing, kMissing, kMissing};
  bool scaled = false;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const std::string& c = columns[k];
    if (c == "id") col_id = k;
    for (std::size_t a = 0; a < 3; ++a) {
      const std::string axis(1, char('x' + a));
      if (c == axis) col_x[a] = k;
      if (c == axis + "s") {
        col_x[a] = k;
        scaled = true;
      }
      if (c == "v" + axis) col_v[a] = k;
    }
  }
  if (col_id == kMissing || col_x[0] == kMissing || col_x[1] == kMissing || col_x[2] == kMissing)
    r.fail("the dump needs id and x y z (or xs ys zs) columns");
  const bool velocities = col_v[0] != kMissing && col_v[1] != kMissing && col_v[2] != kMissing;
  for (std::int64_t k = 0; k < n; ++k) {
    const std::vector<std::string> fields = split(r.require("an atom line"));
    if (fields.size() != columns.size())
      r.fail("expected " + std::to_string(columns.size()) + " columns, found " + std::to_string(fields.size()));
    const auto id = parse<std::int64_t>(fields[col_id], r, "atom id");
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      p[a] = parse<double>(fields[col_x[a]], r, "coordinate");
      if (scaled) p[a] = f.box.lo[a] + p[a] * f.box.length(a);
    }
    f.positions[id] = p;
    if (velocities)
      f.velocities[id] = {parse<double>(fields[col_v[0]], r, "velocity"), parse<double>(fields[col_v[1]], r, "velocity"),
                          parse<double>(fields[col_v[2]], r, "velocity")};
  }
  return true;
}

}  // namespace

DumpFrame read_lammps_dump(const std::string& path, std::optional<std::int64_t> step) {
  LineReader r(path);
  DumpFrame frame, f;
  bool found = false;
  while (read_dump_frame(r, f)) {
    if (!step || *step == f.step) {
      frame = std::move(f);
      found = true;
      if (step) break;
    }
  }
  if (!found) {
    throw std::runtime_error(path + ": " + (step ? "no frame with step " + std::to_string(*step) : "no frame"));
  }
  return frame;
}

std::size_t truncate_lammps_dump(const std::string& path, std::int64_t last_step) {
  std::uintmax_t keep_bytes = 0;
  std::size_t kept = 0;
  {
    LineReader r(path);
    DumpFrame f;
    try {
      while (read_dump_frame(r, f) && f.step <= last_step && r.last_line_terminated()) {
        keep_bytes = r.offset();
        ++kept;
      }
    } catch (const std::runtime_error&) {
      // A frame cut short by a killed writer: everything before it is kept.
    }
  }
  std::filesystem::resize_file(path, keep_bytes);
  return kept;
}

void LammpsDumpWriter::write(const Engine& engine) {
  const Domain& domain = engine.domain();
  const GrainArrays& g = engine.grains();
  // Rank by rank in turn, so no rank ever holds all grains; a rank that cannot write stops all.
  parallel::in_turn(domain.comm(), [&] {
    std::ofstream out(path_, started_ || domain.rank() > 0 ? std::ios::app : std::ios::trunc);
    if (!out) throw std::runtime_error(path_ + ": cannot write");
    out << std::setprecision(kFullPrecision);
    if (domain.rank() == 0) {
      const Box& box = domain.box();
      out << "ITEM: TIMESTEP\n" << engine.step_count() << "\nITEM: NUMBER OF ATOMS\n" << engine.n_global()
          << "\nITEM: BOX BOUNDS";
      for (int a = 0; a < 3; ++a) out << (box.periodic[static_cast<std::size_t>(a)] ? " pp" : " ff");
      out << '\n';
      for (int a = 0; a < 3; ++a) out << box.lo[a] << ' ' << box.hi[a] << '\n';
      out << "ITEM: ATOMS id type radius x y z vx vy vz\n";
    }
    for (std::size_t i = 0; i < g.n_local(); ++i)
      out << g.id[i] << ' ' << g.group[i] << ' ' << g.radius[i] << ' ' << g.position[i].x << ' '
          << g.position[i].y << ' ' << g.position[i].z << ' ' << g.velocity[i].x << ' ' << g.velocity[i].y
          << ' ' << g.velocity[i].z << '\n';
    if (!out.flush()) throw std::runtime_error(path_ + ": cannot write");
  });
  started_ = true;
}

}  // namespace sedwave::forward::dem
