// Test driver for the task farm: fills a table from a grid file with the lattice theory instead of
// the DEM (milliseconds per point), so the farm's distribution, writing and resuming can be checked
// under mpirun in seconds. Also compares two tables.
//
//   farm_driver GRID.toml OUT.h5 [--point-ms MS] [--die-after K]
//   farm_driver --compare A.h5 B.h5
//
// --point-ms makes each point take MS milliseconds, so several ranks really share the work.
// --die-after K: world rank 0 kills its process (std::_Exit, no clean-up, like SIGKILL for the
// file) when asked for its (K+1)-th point, so mpirun takes down the whole run mid-table.
// Meanwhile the other ranks take 10x as long per point: otherwise a rank 0 starved by a busy machine
// could let them finish the whole table before its (K+1)-th point, and the run would not die.
// Points with omega_hat > 1.5 are reported unresolved and those with omega_hat >= 1.9 throw, so
// every status and the reasons travel through the farm too.
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>

#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/task_farm.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace table = sedwave::forward::table;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Everything but wall times must agree bit for bit.
int compare(const std::string& a_path, const std::string& b_path) {
  const table::DispersionTable a = table::read_table(a_path);
  const table::DispersionTable b = table::read_table(b_path);
  if (!(a.grid() == b.grid())) {
    std::cerr << "grids differ\n";
    return 1;
  }
  if (a.metadata().scene_toml != b.metadata().scene_toml || a.metadata().engine != b.metadata().engine) {
    std::cerr << "scene or engine differ\n";
    return 1;
  }
  int differences = 0;
  for (std::size_t g = 0; g < a.n_gamma(); ++g) {
    for (std::size_t w = 0; w < a.n_omega(); ++w) {
      const table::PointResult& p = a.at(g, w);
      const table::PointResult& q = b.at(g, w);
      const bool same = p.status == q.status && p.reason == q.reason && same_bits(p.alpha_hat, q.alpha_hat) &&
                        same_bits(p.c_hat, q.c_hat) && same_bits(p.sigma_alpha_hat, q.sigma_alpha_hat) &&
                        same_bits(p.sigma_c_hat, q.sigma_c_hat);
      if (!same || p.status == table::PointStatus::missing) {
        std::cerr << "point (i_gamma=" << g << ", i_omega=" << w << ") differs or is missing: " << to_string(p.status)
                  << " vs " << to_string(q.status) << "\n";
        ++differences;
      }
    }
  }
  if (differences == 0) std::cout << "tables agree: " << a.grid().size() << " points\n";
  return differences == 0 ? 0 : 1;
}

int fill(int argc, char** argv) {
  const table::TableGridFile grid = table::read_grid_file(argv[1]);
  const std::string out = argv[2];
  int point_ms = 0;
  int die_after = -1;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--point-ms") point_ms = std::stoi(argv[i + 1]);
    else if (option == "--die-after") die_after = std::stoi(argv[i + 1]);
    else throw std::invalid_argument("unknown option " + option);
  }
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int calls = 0;
  const sedwave::forward::LatticeModel lattice;
  const table::PointFunction theory = [&](MPI_Comm group, double omega_hat, double gamma_hat) {
    if (rank == 0 && calls++ == die_after) {
      std::cerr << "farm_driver: dying on purpose after " << die_after << " points\n";
      std::_Exit(3);
    }
    const bool outrun_rank_0 = die_after >= 0 && rank != 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(outrun_rank_0 ? 10 * point_ms : point_ms));
    // Collective over the group, as the DEM is: every rank of a group must take part.
    double value[2] = {lattice.evaluate(omega_hat, gamma_hat).alpha_hat, lattice.evaluate(omega_hat, gamma_hat).c_hat};
    MPI_Allreduce(MPI_IN_PLACE, value, 2, MPI_DOUBLE, MPI_MAX, group);
    if (omega_hat >= 1.9) throw std::runtime_error("deliberate failure at omega_hat " + std::to_string(omega_hat));
    if (omega_hat > 1.5) return table::unresolved_point("above the test's cutoff omega_hat 1.5");
    table::PointResult p;
    p.status = table::PointStatus::ok;
    p.alpha_hat = value[0];
    p.c_hat = value[1];
    p.sigma_alpha_hat = 1e-3 * value[0];
    p.sigma_c_hat = 1e-3 * value[1];
    return p;
  };
  table::TableMetadata metadata;
  metadata.scene_toml = "# farm test: lattice theory, no scene\n";
  metadata.engine = "lattice-theory (farm test)";
  const table::FarmReport report = table::run_task_farm(MPI_COMM_WORLD, out, grid.grid, metadata, theory,
                                                        table::FarmSettings{grid.ranks_per_point, nullptr, false});
  if (rank == 0) {
    std::cout << "points " << report.points << " already_finished " << report.already_finished << " computed "
              << report.computed << " ok " << report.ok << " unresolved " << report.unresolved << " failed "
              << report.failed << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "--compare") return compare(argv[2], argv[3]);
  if (argc < 3) {
    std::cerr << "usage: farm_driver GRID.toml OUT.h5 [--point-ms MS] [--die-after K] | --compare A.h5 B.h5\n";
    return 2;
  }
  MPI_Init(&argc, &argv);
  int status = 0;
  try {
    status = fill(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "farm_driver: " << e.what() << "\n";
    status = 1;
  }
  MPI_Finalize();
  return status;
}
