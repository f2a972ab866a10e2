// `sedwave table`: fills a dispersion table (alpha_hat, c_hat on an omega_hat x gamma_hat grid) with
// the DEM channel (one driven run per grid point), the linear-response engine (one solve per
// point and ensemble member) or the packing's long-wavelength limit (one quasi-static solve per
// point and member, linear/long_wavelength.hpp), shared among MPI ranks by a task farm. One
// prepared packing serves every point. A killed run, restarted with the same command, continues
// where it stopped (docs/tables.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/experiment/packings.hpp"
#include "sedwave/forward/experiment/table_run.hpp"
#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/table/table_file.hpp"

namespace sedwave::app {
namespace {

namespace experiment = forward::experiment;
namespace table = forward::table;

struct TableOptions {
  std::string grid_file;
  std::string out;
  std::string packing;
  std::string engine;  ///< "time_domain", "linear" or "long_wavelength"; empty: the scene's
  int member = -1;      ///< >= 0: this ensemble member alone (a member table, for sedwave merge)
  bool quiet = false;
  bool retry_failed = false;
  bool allow_changed_inputs = false;
};

/// The table, its journal and packings that do not exist yet are written; the grid, the scene and
/// existing packings are read. All checked before any work.
void check_table_paths(const TableOptions& o, const table::TableGridFile& grid, const experiment::ChannelScene& scene) {
  std::vector<OutputPath> outputs{{"--out", o.out, io::OutputFormat::seekable},
                                  {"--out", table::TableFile::journal_path(o.out), io::OutputFormat::seekable}};
  std::vector<std::filesystem::path> inputs{grid.path, grid.scene_path};
  if (scene.import_lammps_data) inputs.push_back(*scene.import_lammps_data);
  for (int k = 0; !o.packing.empty() && k < scene.linear.ensemble; ++k) {
    std::filesystem::path packing = experiment::member_path(o.packing, k);
    if (std::filesystem::exists(packing)) {
      inputs.push_back(packing);
    } else {
      outputs.push_back({"--packing", packing, io::OutputFormat::seekable});
      outputs.push_back({"--packing", packing.replace_extension(".data")});  // its LAMMPS twin
    }
  }
  check_outputs(outputs, inputs, "table");
  table::require_table_or_nothing(o.out);  // a file of another kind is refused now, not after the packing
}

/// The options a run of this scene can honour; throws std::invalid_argument for the others.
void check_table_options(const TableOptions& o, const table::TableGridFile& grid, const experiment::ChannelScene& scene,
                         experiment::EngineKind engine, const MpiSession& mpi) {
  if (mpi.size() % grid.ranks_per_point != 0) {
    throw std::invalid_argument(o.grid_file + ": ranks_per_point = " + std::to_string(grid.ranks_per_point) +
                                " does not divide the " + std::to_string(mpi.size()) + " MPI ranks");
  }
  if (o.member >= 0 && engine != experiment::EngineKind::linear) {
    throw std::invalid_argument("--member is for the driven linear engine (--engine linear, or engine = \"linear\" "
                                "in the scene)");
  }
  if (o.member >= scene.linear.ensemble) {
    throw std::invalid_argument(grid.scene_path.string() + ": --member " + std::to_string(o.member) +
                                " is outside the scene's ensemble of " + std::to_string(scene.linear.ensemble));
  }
}

void print_report(const table::FarmReport& report, const std::string& out, int ranks, int ranks_per_point) {
  const double busy = report.wall_seconds > 0.0 ? report.point_seconds / (report.wall_seconds * ranks) : 0.0;
  std::cout << "table " << out << ": " << report.points << " points, " << report.already_finished
            << " already finished, " << report.computed << " computed (" << report.ok << " ok, "
            << report.unresolved << " unresolved, " << report.failed << " failed) in " << report.wall_seconds
            << " s on " << ranks << " rank(s); points took " << report.point_seconds
            << " s in all (ranks busy " << static_cast<int>(100.0 * busy * ranks_per_point + 0.5)
            << " % of the time)\n";
}

int run_table(const TableOptions& o, const MpiSession& mpi) {
  // Every rank reads both files: they are small, and a mistake in them is told once.
  table::TableGridFile grid;
  experiment::ChannelScene scene;
  mpi.alike([&] {
    grid = table::read_grid_file(o.grid_file);
    scene = experiment::read_scene(grid.scene_path);
    if (!o.engine.empty()) experiment::use_table_engine(scene, experiment::engine_named(o.engine));
    check_table_options(o, grid, scene, scene.engine, mpi);
    check_table_paths(o, grid, scene);
  });
  const experiment::EngineKind engine = scene.engine;
  const bool talk = mpi.rank() == 0 && !o.quiet;
  const experiment::TableRun run{o.out, o.packing, engine, o.member, talk ? &std::cout : nullptr,
                                 mpi.rank() == 0 ? &std::cerr : nullptr};
  const table::FarmReport report = experiment::fill_table(
      grid, scene, run, {1, talk ? &std::cout : nullptr, o.retry_failed, o.allow_changed_inputs});
  if (mpi.rank() == 0) print_report(report, o.out, mpi.size(), experiment::ranks_per_point(grid, engine));
  return report.failed == 0 ? kExitOk : kExitIncomplete;
}

}  // namespace

Command add_table_command(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  CLI::App* cmd = app.add_subcommand(
      "table", "Fill a dispersion table (alpha_hat, c_hat on an omega_hat x gamma_hat grid) with the DEM channel "
               "or the linear-response engine (--engine); "
               "run under mpirun to share the points among ranks; rerun the same command to resume");
  cmd->add_option("grid", o->grid_file, "grid file (TOML): scene, omega_hat and gamma_hat axes (docs/tables.md)")
      ->required();
  cmd->add_option("--out", o->out, "table file (HDF5) to create, or to resume if it exists")->required();
  cmd->add_option("--packing", o->packing,
                  "packing file (HDF5): reused if it exists, else the prepared packing is saved there");
  cmd->add_option("--engine", o->engine,
                  "override the scene's engine: time_domain (DEM), linear (linear response) or long_wavelength "
                  "(the packing's omega_hat -> 0 limit at fixed omega_hat*gamma_hat, for field frequencies)")
      ->check(CLI::IsMember(experiment::engine_names()));
  cmd->add_option("--member", o->member,
                  "with --engine linear: compute ensemble member K alone (seed + K, packing FILE.member<K>) into a "
                  "member table, for ensembles too large for one process; combine the members with sedwave merge")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--retry-failed", o->retry_failed, "when resuming, compute failed points again");
  cmd->add_flag("--allow-changed-inputs", o->allow_changed_inputs,
                "when resuming, accept a table whose packing or sedwave version differs from this run's (the "
                "table then mixes them)");
  cmd->add_flag("--quiet", o->quiet, "no progress lines");
  return {cmd, [o]() {
    const MpiSession mpi;
    return mpi.run([&] { return run_table(*o, mpi); });
  }};
}

}  // namespace sedwave::app
