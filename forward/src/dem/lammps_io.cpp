#include "sedwave/forward/dem/lammps_io.hpp"

#include <mpi.h>

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::dem {
namespace {

std::string strip_comment(const std::string& line) {
  const auto hash = line.find('#');
  return hash == std::string::npos ? line : line.substr(0, hash);
}

bool contains(const std::string& line, const char* word) { return line.find(word) != std::string::npos; }

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("LAMMPS file " + path + ": " + what);
}

}  // namespace

LammpsData read_lammps_data(const std::string& path, const std::function<bool(const Grain&)>& keep) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open");
  LammpsData data;
  std::string line;
  std::getline(in, line);  // title
  std::int64_t n_atoms = -1;
  std::string section;
  std::unordered_map<std::int64_t, std::size_t> index;
  std::int64_t atoms_read = 0;
  while (std::getline(in, line)) {
    const std::string body = strip_comment(line);
    std::istringstream words(body);
    std::string first;
    if (!(words >> first)) continue;
    if (std::isalpha(static_cast<unsigned char>(first[0]))) {  // a section keyword
      section = first;
      continue;
    }
    if (section.empty()) {  // header
      if (contains(body, "atoms") && !contains(body, "types")) n_atoms = std::stoll(first);
      for (int a = 0; a < 3; ++a) {
        const std::string lo = std::string(1, char('x' + a)) + "lo";
        if (contains(body, lo.c_str())) {
          std::istringstream bounds(body);
          bounds >> data.box.lo[a] >> data.box.hi[a];
        }
      }
      continue;
    }
    std::istringstream fields(body);
    if (section == "Atoms") {
      Grain g;
      double diameter = 0.0, density = 0.0;
      if (!(fields >> g.id >> g.group >> diameter >> density >> g.position.x >> g.position.y >> g.position.z))
        fail(path, "bad Atoms line (atom_style sphere expected): " + line);
      g.radius = 0.5 * diameter;
      g.mass = grain_mass(density, diameter);
      ++atoms_read;
      if (keep && !keep(g)) continue;
      index[g.id] = data.grains.size();
      data.grains.push_back(g);
    } else if (section == "Velocities") {
      std::int64_t id = 0;
      Vec3 v, w;
      if (!(fields >> id >> v.x >> v.y >> v.z >> w.x >> w.y >> w.z)) fail(path, "bad Velocities line: " + line);
      const auto it = index.find(id);
      if (it == index.end()) continue;
      data.grains[it->second].velocity = v;
      data.grains[it->second].angular_velocity = w;
    }
  }
  if (n_atoms >= 0 && atoms_read != n_atoms)
    fail(path, "header announces " + std::to_string(n_atoms) + " atoms, found " + std::to_string(atoms_read));
  return data;
}

void write_lammps_data(const std::string& path, const Box& box, std::span<const Grain> grains) {
  std::ofstream out(path);
  if (!out) fail(path, "cannot create");
  int types = 1;
  for (const Grain& g : grains) types = std::max(types, g.group);
  out << "LAMMPS data file written by sedwave (atom_style sphere)\n\n"
      << grains.size() << " atoms\n" << types << " atom types\n\n" << std::setprecision(17);
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
}

DumpFrame read_lammps_dump(const std::string& path, std::optional<std::int64_t> step) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open");
  DumpFrame frame;
  bool found = false;
  std::string line;
  while (std::getline(in, line)) {
    if (!contains(line, "ITEM: TIMESTEP")) continue;
    DumpFrame f;
    std::getline(in, line);
    f.step = std::stoll(line);
    std::getline(in, line);  // ITEM: NUMBER OF ATOMS
    std::getline(in, line);
    const std::int64_t n = std::stoll(line);
    std::getline(in, line);  // ITEM: BOX BOUNDS pp pp ff
    for (int a = 0; a < 3; ++a) {
      std::getline(in, line);
      std::istringstream(line) >> f.box.lo[a] >> f.box.hi[a];
    }
    std::getline(in, line);  // ITEM: ATOMS id type x y z ...
    std::istringstream header(line.substr(line.find("ATOMS") + 5));
    std::vector<std::string> columns;
    for (std::string c; header >> c;) columns.push_back(c);
    int col_id = -1, col[3] = {-1, -1, -1};
    bool scaled = false;
    for (int k = 0; k < static_cast<int>(columns.size()); ++k) {
      const std::string& c = columns[static_cast<std::size_t>(k)];
      if (c == "id") col_id = k;
      for (int a = 0; a < 3; ++a) {
        if (c == std::string(1, char('x' + a))) col[a] = k;
        if (c == std::string(1, char('x' + a)) + "s") {
          col[a] = k;
          scaled = true;
        }
      }
    }
    if (col_id < 0 || col[0] < 0 || col[1] < 0 || col[2] < 0) fail(path, "dump needs id and x y z columns");
    std::vector<double> values(columns.size());
    for (std::int64_t k = 0; k < n; ++k) {
      if (!std::getline(in, line)) fail(path, "truncated frame");
      std::istringstream fields(line);
      for (double& v : values) fields >> v;
      Vec3 p{values[static_cast<std::size_t>(col[0])], values[static_cast<std::size_t>(col[1])],
             values[static_cast<std::size_t>(col[2])]};
      if (scaled)
        for (int a = 0; a < 3; ++a) p[a] = f.box.lo[a] + p[a] * f.box.length(a);
      f.positions[static_cast<std::int64_t>(values[static_cast<std::size_t>(col_id)])] = p;
    }
    const bool wanted = !step || *step == f.step;
    if (wanted) {
      frame = std::move(f);
      found = true;
      if (step) break;
    }
  }
  if (!found) fail(path, "no matching frame");
  return frame;
}

void LammpsDumpWriter::write(const Engine& engine) {
  const Domain& domain = engine.domain();
  const GrainArrays& g = engine.grains();
  // Rank by rank in turn (a token passed along), so no rank ever holds all grains.
  int token = 0;
  if (domain.rank() > 0) MPI_Recv(&token, 1, MPI_INT, domain.rank() - 1, 21, domain.comm(), MPI_STATUS_IGNORE);
  {
    std::ofstream out(path_, started_ || domain.rank() > 0 ? std::ios::app : std::ios::trunc);
    if (!out) fail(path_, "cannot write");
    out << std::setprecision(10);
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
  }
  if (domain.rank() + 1 < domain.size()) MPI_Send(&token, 1, MPI_INT, domain.rank() + 1, 21, domain.comm());
  MPI_Barrier(domain.comm());
  started_ = true;
}

}  // namespace sedwave::forward::dem
