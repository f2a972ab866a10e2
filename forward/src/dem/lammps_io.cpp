#include "sedwave/forward/dem/lammps_io.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <type_traits>

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

/// White space between the words of a line.
constexpr const char* kSpace = " \t\n\v\f\r";

/// The words of a line, split at white space (as `>>` would, without a stream per line: data files
/// have millions of lines).
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t at = line.find_first_not_of(kSpace); at != std::string::npos;) {
    const std::size_t stop = std::min(line.find_first_of(kSpace, at), line.size());
    out.emplace_back(line, at, stop - at);
    at = line.find_first_not_of(kSpace, stop);
  }
  return out;
}

/// Parses one whole token as a number (from_chars: exact, locale-free), or fails naming the line.
template <typename T, class Reporter>
T parse(const std::string& token, const Reporter& r, const std::string& what) {
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

/// One line of a data file, for errors: "path:12: ...".
struct Where {
  const std::string& path;
  std::int64_t number;
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path + ":" + std::to_string(number) + ": " + what);
  }
};

/// What a data file's header holds, and where its sections start (rank 0 reads it, all use it).
struct DataHeader {
  Box box;
  std::int64_t n_atoms = -1;     ///< -1: the header does not say
  std::uint64_t body = 0;        ///< byte offset of the first section keyword line (the file size if none)
  std::int64_t body_line = 0;    ///< its line number
  std::uint64_t file_size = 0;
};

void read_header_line(const std::string& body, const Where& r, DataHeader& h) {
  const std::vector<std::string> words = split(body);
  if (words.size() == 2 && words[1] == "atoms") {
    h.n_atoms = parse<std::int64_t>(words[0], r, "atom count");
    if (h.n_atoms < 0) r.fail("atom count " + words[0] + ": accepted range [0, inf)");
  }
  for (int a = 0; a < 3; ++a) {
    const std::string lo = std::string(1, char('x' + a)) + "lo";
    if (words.size() == 4 && words[2] == lo) {
      h.box.lo[a] = parse<double>(words[0], r, lo);
      h.box.hi[a] = parse<double>(words[1], r, std::string(1, char('x' + a)) + "hi");
      if (!(h.box.hi[a] > h.box.lo[a]) || !std::isfinite(h.box.hi[a] - h.box.lo[a]))
        r.fail(lo + " " + words[0] + " and " + std::string(1, char('x' + a)) + "hi " + words[1] +
               ": the box must have finite, positive extent");
    }
  }
}

/// A section keyword line ("Atoms # sphere", "Velocities", "Masses", ...): its first word starts
/// with a letter; every other non-blank line starts with a number.
bool is_keyword(const std::vector<std::string>& words) {
  return !words.empty() && std::isalpha(static_cast<unsigned char>(words[0][0]));
}

/// The title and header lines, up to the first section keyword.
DataHeader read_header(const std::string& path) {
  LineReader r(path);
  DataHeader h;
  h.file_size = std::filesystem::file_size(path);
  std::string line;
  std::uint64_t offset = 0;  // of the next line
  const auto advance = [&] { offset += line.size() + (r.last_line_terminated() ? 1 : 0); };
  if (r.next(line)) advance();  // title
  for (std::int64_t number = 2; r.next(line); ++number) {
    const std::string body = strip_comment(line);
    if (is_keyword(split(body))) {
      h.body = offset;
      h.body_line = number;
      return h;
    }
    read_header_line(body, Where{path, number}, h);
    advance();
  }
  h.body = h.file_size;
  return h;
}

/// The sections of a data file that the reader takes apart; others (Masses, ...) are skipped.
enum class Section : int { none = 0, atoms, velocities, other };

Section section_of(const std::string& keyword) {
  return keyword == "Atoms" ? Section::atoms : keyword == "Velocities" ? Section::velocities : Section::other;
}

/// The lines of a file that start in the bytes [begin, end), one by one. A line belongs to the range
/// holding its first byte, so ranges that meet at any byte share out the lines exactly.
class RangeLines {
 public:
  RangeLines(const std::string& path, std::uint64_t begin, std::uint64_t end)
      : in_(path, std::ios::binary), at_(begin), end_(end) {
    if (!in_) throw std::runtime_error(path + ": cannot open");
    in_.seekg(static_cast<std::streamoff>(begin));
  }
  bool next(std::string& line) {
    if (at_ >= end_ || !std::getline(in_, line)) return false;
    at_ += line.size() + (in_.eof() ? 0 : 1);
    return true;
  }

 private:
  std::ifstream in_;
  std::uint64_t at_, end_;
};

/// The first line start at or after byte `at` of a file whose lines start at `first_line`: the byte
/// after the first newline at or after at - 1 (the file size if none).
std::uint64_t line_start_from(const std::string& path, std::uint64_t at, std::uint64_t first_line,
                              std::uint64_t file_size) {
  if (at <= first_line) return first_line;
  if (at >= file_size) return file_size;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  in.seekg(static_cast<std::streamoff>(at - 1));
  in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  return std::min(file_size, at - 1 + static_cast<std::uint64_t>(in.gcount()));
}

/// An Atoms line as read (before it is a Grain): id, type, radius, mass, position, and its line.
struct AtomLine {
  std::int64_t id = 0;
  std::int64_t line = 0;
  Vec3 position;
  double radius = 0.0;
  double mass = 0.0;
  std::int32_t group = 0;
};
/// A Velocities line: the atom's id, its line, and the velocities.
struct VelocityLine {
  std::int64_t id = 0;
  std::int64_t line = 0;
  Vec3 velocity, angular_velocity;
};

/// The first failure of a read (in file order), or none.
struct Failure {
  std::int64_t line = std::numeric_limits<std::int64_t>::max();
  std::string message;
  void offer(std::int64_t at, std::string what) {
    if (at < line) {
      line = at;
      message = std::move(what);
    }
  }
};

AtomLine parse_atom(const std::string& line, const std::vector<std::string>& words, const Where& r) {
  // id type diameter density x y z [ix iy iz]
  if (words.size() != 7 && words.size() != 10)
    r.fail("bad Atoms line (atom_style sphere: id type diameter density x y z expected): " + line);
  AtomLine a;
  a.line = r.number;
  a.id = parse<std::int64_t>(words[0], r, "atom id");
  a.group = parse<std::int32_t>(words[1], r, "atom type");
  if (a.group < 1) r.fail("atom type " + words[1] + ": accepted range [1, 2147483647] (LAMMPS types count from 1)");
  const double diameter = parse<double>(words[2], r, "diameter");
  const double density = parse<double>(words[3], r, "density");
  for (int k = 0; k < 3; ++k) a.position[k] = parse<double>(words[4 + static_cast<std::size_t>(k)], r, "coordinate");
  if (!(diameter > 0.0) || !(density > 0.0) || !std::isfinite(diameter) || !std::isfinite(density))
    r.fail("diameter and density must be positive and finite: " + line);
  if (!std::isfinite(a.position.x) || !std::isfinite(a.position.y) || !std::isfinite(a.position.z))
    r.fail("coordinates must be finite: " + line);
  a.radius = 0.5 * diameter;
  a.mass = grain_mass(density, diameter);
  return a;
}

VelocityLine parse_velocity(const std::string& line, const std::vector<std::string>& words, const Where& r) {
  // id vx vy vz wx wy wz
  if (words.size() != 7) r.fail("bad Velocities line (id vx vy vz wx wy wz expected): " + line);
  VelocityLine v;
  v.line = r.number;
  v.id = parse<std::int64_t>(words[0], r, "atom id");
  for (int k = 0; k < 3; ++k) {
    v.velocity[k] = parse<double>(words[1 + static_cast<std::size_t>(k)], r, "velocity");
    v.angular_velocity[k] = parse<double>(words[4 + static_cast<std::size_t>(k)], r, "angular velocity");
  }
  const Vec3& a = v.velocity;
  const Vec3& w = v.angular_velocity;
  if (!std::isfinite(a.x + a.y + a.z + w.x + w.y + w.z)) r.fail("velocities must be finite: " + line);
  return v;
}

/// One rank's lines of the body, parsed: atoms and velocities sorted by the rank that joins them
/// (id mod ranks), the number of lines, and the first malformed line.
struct ParsedRange {
  std::vector<std::vector<AtomLine>> atoms;
  std::vector<std::vector<VelocityLine>> velocities;
  std::int64_t n_atoms = 0;
  Failure failure;
};

/// The lines of [begin, end), numbered from `first_number`, in `section` at the start.
ParsedRange parse_range(const std::string& path, std::uint64_t begin, std::uint64_t end, std::int64_t first_number,
                        Section section, int ranks) {
  ParsedRange out;
  out.atoms.resize(static_cast<std::size_t>(ranks));
  out.velocities.resize(static_cast<std::size_t>(ranks));
  std::int64_t number = first_number;
  try {
    RangeLines lines(path, begin, end);
    for (std::string line; lines.next(line); ++number) {
      const Where r{path, number};
      const std::string body = strip_comment(line);
      const std::vector<std::string> words = split(body);
      if (words.empty()) continue;
      if (is_keyword(words)) {
        section = section_of(words[0]);
        const std::vector<std::string> style = split(line.substr(std::min(line.size(), body.size() + 1)));
        if (section == Section::atoms && !style.empty() && style[0] != "sphere")
          r.fail("atom_style " + style[0] + " is not supported (atom_style sphere expected)");
      } else if (section == Section::atoms) {
        const AtomLine a = parse_atom(line, words, r);
        out.atoms[parallel::rank_for_key(a.id, ranks)].push_back(a);
        ++out.n_atoms;
      } else if (section == Section::velocities) {
        const VelocityLine v = parse_velocity(line, words, r);
        out.velocities[parallel::rank_for_key(v.id, ranks)].push_back(v);
      }
    }
  } catch (const std::runtime_error& e) {  // the rest of the range cannot matter: this failure comes first
    out.failure.offer(number, e.what());
  }
  return out;
}

/// Counts the lines of [begin, end) and finds the section open at its end (none: no keyword line).
std::pair<std::int64_t, Section> scan_range(const std::string& path, std::uint64_t begin, std::uint64_t end) {
  std::int64_t lines = 0;
  Section last = Section::none;
  RangeLines range(path, begin, end);
  for (std::string line; range.next(line); ++lines) {
    // Only a line whose first word starts with a letter can be a keyword: most are not split.
    const std::size_t first = line.find_first_not_of(kSpace);
    if (first == std::string::npos || !std::isalpha(static_cast<unsigned char>(line[first]))) continue;
    last = section_of(split(strip_comment(line))[0]);
  }
  return {lines, last};
}

/// The grains whose ids this rank joins: each atom with the last velocity line given for it, in file
/// order. A repeated id and a velocity for no atom before it are offered as failures.
std::vector<Grain> join(std::vector<AtomLine> atoms, std::vector<VelocityLine> velocities, const std::string& path,
                        Failure& failure) {
  const auto by_id = [](const AtomLine& a, const AtomLine& b) { return std::tie(a.id, a.line) < std::tie(b.id, b.line); };
  std::sort(atoms.begin(), atoms.end(), by_id);
  const auto where = [&](std::int64_t line) { return path + ":" + std::to_string(line) + ": "; };
  for (std::size_t k = 1; k < atoms.size(); ++k)
    if (atoms[k].id == atoms[k - 1].id)
      failure.offer(atoms[k].line, where(atoms[k].line) + "duplicate atom id " + std::to_string(atoms[k].id));
  // Each atom's velocity line: the last one given for it, as a serial read applies them in turn.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> velocity_of(atoms.size(), kNone);
  std::sort(velocities.begin(), velocities.end(), [](const auto& a, const auto& b) { return a.line < b.line; });
  for (std::size_t k = 0; k < velocities.size(); ++k) {
    const VelocityLine& v = velocities[k];
    const auto it = std::lower_bound(atoms.begin(), atoms.end(), AtomLine{v.id, 0, {}, 0.0, 0.0, 0}, by_id);
    if (it == atoms.end() || it->id != v.id || it->line > v.line) {
      failure.offer(v.line, where(v.line) + "Velocities entry for atom id " + std::to_string(v.id) +
                                ", which is not in the Atoms section");
      continue;
    }
    velocity_of[static_cast<std::size_t>(it - atoms.begin())] = k;
  }
  // The grains, built once, in file order.
  std::vector<std::size_t> order(atoms.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return atoms[a].line < atoms[b].line; });
  std::vector<Grain> grains(atoms.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const AtomLine& a = atoms[order[k]];
    Grain& g = grains[k];
    g.id = a.id;
    g.group = a.group;
    g.radius = a.radius;
    g.mass = a.mass;
    g.position = a.position;
    if (const std::size_t v = velocity_of[order[k]]; v != kNone) {
      g.velocity = velocities[v].velocity;
      g.angular_velocity = velocities[v].angular_velocity;
    }
  }
  return grains;
}

/// Throws the first failure of the file on every rank of `comm` (collective; none: returns).
void agree_on_failure(MPI_Comm comm, const Failure& failure) {
  const std::int64_t first = parallel::min(comm, failure.line);
  if (first == std::numeric_limits<std::int64_t>::max()) return;
  const int n = parallel::size(comm);
  const int teller = parallel::min(comm, failure.line == first ? parallel::rank(comm) : n);
  std::string message = failure.message;
  parallel::broadcast(comm, message, teller);
  throw parallel::AgreedFailure(comm, message);
}

}  // namespace

LammpsData read_lammps_data(MPI_Comm comm, const std::string& path) {
  const int ranks = parallel::size(comm), me = parallel::rank(comm);
  // The header, once: rank 0 reads it and tells every rank (a malformed header fails on all).
  DataHeader header;
  Failure failure;
  if (me == 0) {
    try {
      header = read_header(path);
    } catch (const std::exception& e) {
      failure.offer(0, e.what());
    }
  }
  agree_on_failure(comm, failure);
  static_assert(std::is_trivially_copyable_v<DataHeader>);
  parallel::broadcast(comm, std::as_writable_bytes(std::span(&header, 1)));

  // This rank's byte range of the body, its edges moved to line starts; two cheap passes over it:
  // first the line count and the section open at its end (so that every rank knows its first line's
  // number and section), then the parse.
  const std::uint64_t body_bytes = header.file_size - header.body;
  const auto nominal = [&](int r) {  // body + floor(body_bytes * r / ranks), without overflow
    const auto n = static_cast<std::uint64_t>(ranks), k = static_cast<std::uint64_t>(r);
    return header.body + body_bytes / n * k + body_bytes % n * k / n;
  };
  std::uint64_t begin = 0, end = 0;
  std::pair<std::int64_t, Section> scanned{0, Section::none};
  try {
    begin = line_start_from(path, nominal(me), header.body, header.file_size);
    end = line_start_from(path, nominal(me + 1), header.body, header.file_size);
    scanned = scan_range(path, begin, end);
  } catch (const std::exception& e) {
    failure.offer(0, e.what());
  }
  agree_on_failure(comm, failure);
  const std::int64_t first_line = header.body_line + parallel::exclusive_prefix_sum(comm, scanned.first);
  const std::vector<int> last_sections = parallel::all_gather(comm, static_cast<int>(scanned.second));
  Section section = Section::none;
  for (int r = 0; r < me; ++r)
    if (last_sections[static_cast<std::size_t>(r)] != static_cast<int>(Section::none))
      section = static_cast<Section>(last_sections[static_cast<std::size_t>(r)]);
  ParsedRange parsed = parse_range(path, begin, end, first_line, section, ranks);

  // Each atom and velocity goes to the rank that joins its id: repeated ids meet there.
  LammpsData data;
  data.box = header.box;
  const std::int64_t n_atoms = parallel::sum(comm, parsed.n_atoms);
  std::vector<AtomLine> atoms = parallel::all_to_all(comm, parsed.atoms);
  parsed.atoms = {};
  std::vector<VelocityLine> velocities = parallel::all_to_all(comm, parsed.velocities);
  parsed.velocities = {};
  failure = std::move(parsed.failure);
  data.grains = join(std::move(atoms), std::move(velocities), path, failure);
  agree_on_failure(comm, failure);
  if (header.n_atoms >= 0 && n_atoms != header.n_atoms)
    throw std::runtime_error(path + ": header announces " + std::to_string(header.n_atoms) + " atoms, found " +
                             std::to_string(n_atoms));
  return data;
}

LammpsData read_lammps_data(const std::string& path, const std::function<bool(const Grain&)>& keep) {
  LammpsData data = read_lammps_data(MPI_COMM_SELF, path);
  if (keep) std::erase_if(data.grains, [&](const Grain& g) { return !keep(g); });
  return data;
}

void write_lammps_data(MPI_Comm comm, const std::string& path, const Box& box, std::span<const Grain> grains) {
  int types = 1;
  for (const Grain& g : grains) types = std::max(types, g.group);
  types = parallel::max(comm, types);
  const auto count = parallel::sum(comm, static_cast<std::int64_t>(grains.size()));
  // Two passes over the pieces: the atoms, then their velocities.
  parallel::on_root_with_pieces(comm, grains, 2, [&](auto&& pieces) {
    // Whole or not at all: a kill or a full disk leaves the previous file (io::write_text_atomically).
    io::write_text_atomically(path, [&](std::ostream& out) {
      out << "LAMMPS data file written by sedwave (atom_style sphere)\n\n"
          << count << " atoms\n" << types << " atom types\n\n" << std::setprecision(kFullPrecision);
      for (int a = 0; a < 3; ++a)
        out << box.lo[a] << ' ' << box.hi[a] << ' ' << char('x' + a) << "lo " << char('x' + a) << "hi\n";
      out << "\nAtoms # sphere\n\n";
      pieces([&](std::span<const Grain> piece) {
        for (const Grain& g : piece) {
          const double d = 2.0 * g.radius;
          out << g.id << ' ' << std::max(g.group, 1) << ' ' << d << ' ' << g.mass / grain_mass(1.0, d) << ' '
              << g.position.x << ' ' << g.position.y << ' ' << g.position.z << '\n';
        }
      });
      out << "\nVelocities\n\n";
      pieces([&](std::span<const Grain> piece) {
        for (const Grain& g : piece)
          out << g.id << ' ' << g.velocity.x << ' ' << g.velocity.y << ' ' << g.velocity.z << ' '
              << g.angular_velocity.x << ' ' << g.angular_velocity.y << ' ' << g.angular_velocity.z << '\n';
      });
    });
  });
}

void write_lammps_data(const std::string& path, const Box& box, std::span<const Grain> grains) {
  write_lammps_data(MPI_COMM_SELF, path, box, grains);
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
