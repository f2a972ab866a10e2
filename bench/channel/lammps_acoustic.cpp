// sedwave's driven channel against LAMMPS on the same packing and drive (issue: "an independent
// check against LAMMPS on the same compressed packing and drive"). Two steps, run by
// bench/channel/lammps_acoustic.sh:
//
//   bench_lammps_acoustic script  PACKING.h5 --omega-hat W --gamma-hat G [--amplitude A] --dir DIR
//     drives the packing with sedwave's DEM (frozen far end), prints its alpha_hat and c_hat, and
//     writes DIR/packing.data and DIR/in.acoustic: the same grains, contact law, time step, wall
//     motion, run length and sampling for LAMMPS, which dumps the flow grains' z every sample.
//   bench_lammps_acoustic measure PACKING.h5 --omega-hat W --gamma-hat G [--amplitude A] --dir DIR
//     averages LAMMPS's dump DIR/dump.z over the same layers and measures it with the same windows,
//     lock-ins and fit (measure_layer_records), and prints the largest difference between the two
//     engines' layer displacements in units of the drive amplitude.
//
// The contact law is frictionless Hooke kn with a constant normal dashpot gamma = gamma_hat
// sqrt(kn m) on every pair: LAMMPS pair granular "hooke kn gamma damping velocity" (gran/hooke
// would scale the dashpot with each pair's effective mass). Units: those of the packing file.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "../linear/bench_contact.hpp"
#include "../one_process_mpi.hpp"

namespace {

using namespace sedwave::forward;

struct Options {
  std::string mode, packing, dir;
  channel::DriveSettings drive;
  double kn = 726.0;
};

Options parse(int argc, char** argv) {
  Options o;
  o.drive.far_end = channel::FarEnd::frozen;  // LAMMPS has no graded drag; windows end before echoes
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--omega-hat") o.drive.omega_hat = std::stod(next());
    else if (a == "--gamma-hat") o.drive.gamma_hat = std::stod(next());
    else if (a == "--amplitude") o.drive.amplitude = std::stod(next());
    else if (a == "--kn") o.kn = std::stod(next());
    else if (a == "--dir") o.dir = next();
    else if (o.mode.empty()) o.mode = a;
    else o.packing = a;
  }
  if ((o.mode != "script" && o.mode != "measure") || o.packing.empty() || o.dir.empty()) {
    throw std::invalid_argument("usage: bench_lammps_acoustic script|measure PACKING.h5 --omega-hat W --gamma-hat G "
                                "[--amplitude A] [--kn KN] --dir DIR");
  }
  return o;
}

void print_result(const char* engine, const channel::AcousticResult& r) {
  std::printf("%-8s omega_hat %-6g gamma_hat %-6g alpha_hat %.8f +- %.5f c_hat %.8f +- %.5f layers %d %s\n", engine,
              r.omega_hat, r.gamma_hat, r.fit.alpha, r.fit.sigma_alpha, r.fit.c, r.fit.sigma_c, r.layers_used,
              r.problem.c_str());
}

/// The sampling sedwave's run used, written beside the LAMMPS input so `measure` needs no rerun.
struct Protocol {
  double time_step = 0.0;    ///< [packing time units]
  long long steps = 0;
  long long steps_per_sample = 0;
};

void write_protocol(const std::string& path, const Protocol& p) {
  std::ofstream out(path);
  out.precision(17);
  out << "# time_step [packing time units], steps, steps_per_sample\n" << p.time_step << ' ' << p.steps << ' '
      << p.steps_per_sample << '\n';
  if (!out) throw std::runtime_error(path + ": cannot write");
}

Protocol read_protocol(const std::string& path) {
  std::ifstream in(path);
  std::string comment;
  std::getline(in, comment);
  Protocol p;
  if (!(in >> p.time_step >> p.steps >> p.steps_per_sample)) throw std::runtime_error(path + ":2: bad protocol line");
  return p;
}

void write_lammps_input(const std::string& path, const Options& o, const channel::PackingUnits& u, const Protocol& p) {
  const double gamma = o.drive.gamma_hat * u.damping_scale;
  const double period = 2.0 * std::numbers::pi * u.time() / o.drive.omega_hat;
  std::ofstream in(path);
  in.precision(17);
  in << "# sedwave bench/channel/lammps_acoustic.cpp: the driven channel of sedwave's run, for LAMMPS\n"
     << "units lj\natom_style sphere\natom_modify map array\nboundary p p f\ncomm_modify vel yes\n"
     << "read_data packing.data\n"
     << "group flow type " << channel::kFlowGroup + 1 << "\n"
     << "group lower type " << channel::kLowerWallGroup + 1 << "\n"
     << "group upper type " << channel::kUpperWallGroup + 1 << "\n"
     << "pair_style granular\n"
     << "pair_coeff * * hooke " << o.kn << ' ' << gamma
     << " damping velocity tangential linear_nohistory 0.0 0.0\n"
     << "neighbor 0.2 bin\nneigh_modify delay 0 every 1 check yes exclude group lower upper\n"
     << "fix integrate flow nve/sphere\n"
     << "fix drive lower move wiggle 0.0 0.0 " << o.drive.amplitude * u.diameter << ' ' << period << "\n"
     << "timestep " << p.time_step << "\n"
     << "dump layers flow custom " << p.steps_per_sample << " dump.z id z\n"
     << "dump_modify layers sort id format line \"%d %.17g\"\n"
     << "thermo " << p.steps << "\n"
     << "run " << p.steps << "\n";
  if (!in) throw std::runtime_error(path + ": cannot write");
}

/// sedwave's layer records [layer][sample], kept so `measure` can compare the two trajectories.
void write_records(const std::string& path, const std::vector<std::vector<double>>& records) {
  std::ofstream out(path);
  out.precision(17);
  out << "# layer-averaged z displacement [d]: one line per layer, one column per sample\n";
  for (const auto& layer : records) {
    for (const double u : layer) out << u << ' ';
    out << '\n';
  }
  if (!out) throw std::runtime_error(path + ": cannot write");
}

/// Largest |sedwave - LAMMPS| over layers and samples, in units of the drive amplitude.
double largest_difference(const std::string& path, const std::vector<std::vector<double>>& lammps, double amplitude) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  double worst = 0.0;
  for (const auto& layer : lammps) {
    if (!std::getline(in, line)) throw std::runtime_error(path + ": fewer layers than the LAMMPS dump");
    std::istringstream values(line);
    for (const double u : layer) {
      double ours = 0.0;
      if (!(values >> ours)) throw std::runtime_error(path + ": fewer samples than the LAMMPS dump");
      worst = std::max(worst, std::abs(ours - u));
    }
  }
  return worst / amplitude;
}

/// Layer-averaged z displacement per dump frame, layers as in run_acoustic (LayerGrid from the
/// driven wall's surface, reference = the packing's own positions).
std::vector<std::vector<double>> layer_records(const std::string& dump, const channel::PreparedChannel& packing,
                                               const channel::LayerGrid& grid, double diameter) {
  std::unordered_map<std::int64_t, std::pair<int, double>> member;
  std::vector<int> count(static_cast<std::size_t>(grid.count), 0);
  for (const dem::Grain& g : packing.grains) {
    if (g.group != channel::kFlowGroup) continue;
    const int layer = grid.index(g.position.z);
    member[g.id] = {layer, g.position.z};
    ++count[static_cast<std::size_t>(layer)];
  }
  std::vector<std::vector<double>> records(static_cast<std::size_t>(grid.count));
  std::ifstream in(dump);
  if (!in) throw std::runtime_error(dump + ": cannot open");
  std::string line;
  long long line_number = 0;
  auto next_line = [&]() {
    if (!std::getline(in, line)) return false;
    ++line_number;
    return true;
  };
  while (next_line()) {
    if (line.rfind("ITEM: NUMBER OF ATOMS", 0) != 0) continue;
    next_line();
    const long long atoms = std::stoll(line);
    while (next_line() && line.rfind("ITEM: ATOMS", 0) != 0) {
    }
    std::vector<double> sum(records.size(), 0.0);
    for (long long k = 0; k < atoms; ++k) {
      if (!next_line()) throw std::runtime_error(dump + ":" + std::to_string(line_number) + ": frame cut short");
      std::istringstream fields(line);
      std::int64_t id = 0;
      double z = 0.0;
      if (!(fields >> id >> z)) throw std::runtime_error(dump + ":" + std::to_string(line_number) + ": bad atom line");
      const auto it = member.find(id);
      if (it == member.end()) throw std::runtime_error(dump + ":" + std::to_string(line_number) + ": unknown id");
      sum[static_cast<std::size_t>(it->second.first)] += z - it->second.second;
    }
    for (std::size_t k = 0; k < records.size(); ++k) {
      records[k].push_back(count[k] > 0 ? sum[k] / count[k] / diameter : 0.0);
    }
  }
  if (records.front().size() < 2) throw std::runtime_error(dump + ": fewer than two frames");
  return records;
}

}  // namespace

int main(int argc, char** argv) {
  const sedwave::bench::OneProcessMpi mpi(argc, argv, "bench_lammps_acoustic");
  if (!mpi.alone()) return 2;
  int status = 0;
  try {
    const Options o = parse(argc, argv);
    const dem::ContactSpec contact = sedwave::bench::bench_contact(o.kn, 0.0);
    const channel::PreparedChannel packing = experiment::read_packing(o.packing);
    const channel::PackingUnits u = channel::packing_units(MPI_COMM_WORLD, packing, contact);
    if (o.mode == "script") {
      const channel::AcousticResult r = channel::run_acoustic(MPI_COMM_WORLD, packing, contact, o.drive);
      print_result("sedwave", r);
      Protocol p;
      p.time_step = r.time_step * u.time();
      p.steps = r.steps;
      p.steps_per_sample = std::llround(r.sample_dt / r.time_step);
      experiment::write_packing_lammps_data(o.dir + "/packing.data", packing);
      write_lammps_input(o.dir + "/in.acoustic", o, u, p);
      write_protocol(o.dir + "/protocol.txt", p);
      write_records(o.dir + "/sedwave_layers.txt", r.displacement);
    } else {
      const Protocol p = read_protocol(o.dir + "/protocol.txt");
      channel::AcousticResult r;
      r.omega_hat = o.drive.omega_hat;
      r.gamma_hat = o.drive.gamma_hat;
      r.amplitude = o.drive.amplitude;
      const channel::LayerGrid grid(u, o.drive.layer_thickness);
      r.displacement = layer_records(o.dir + "/dump.z", packing, grid, u.diameter);
      r.layer_z = grid.centres();
      r.sample_dt = static_cast<double>(p.steps_per_sample) * p.time_step / u.time();
      channel::measure_layer_records(r, o.drive, u);
      print_result("LAMMPS", r);
      std::printf("largest layer displacement difference / A: %.3g\n",
                  largest_difference(o.dir + "/sedwave_layers.txt", r.displacement, o.drive.amplitude));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_lammps_acoustic: %s\n", e.what());
    status = 1;
  }
  return status;
}
