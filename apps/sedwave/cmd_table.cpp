// `sedwave table`: fills a dispersion table (alpha_hat, c_hat on an omega_hat x gamma_hat grid) with
// the DEM channel, one driven run per grid point, shared among MPI ranks by a task farm. One
// prepared packing serves every point. A killed run, restarted with the same command, continues
// where it stopped (docs/tables.md).
#include <mpi.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "sedwave/forward/channel/run_file.hpp"
#include "sedwave/forward/channel/scene.hpp"
#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/table/task_farm.hpp"

namespace sedwave::app {
namespace {

namespace channel = forward::channel;
namespace table = forward::table;

struct TableOptions {
  std::string grid_file;
  std::string out;
  std::string packing;
  bool quiet = false;
  bool retry_failed = false;
};

/// The one packing every grid point starts from: read from --packing if that file exists, otherwise
/// prepared (collectively) and, with --packing, saved there so a restart skips the preparation.
channel::PreparedChannel packing_for_table(const channel::ChannelScene& scene, const TableOptions& o,
                                           const MpiSession& mpi, std::string& provenance) {
  if (!o.packing.empty() && std::filesystem::exists(o.packing)) {
    provenance = "packing read from " + o.packing;
    if (mpi.rank() == 0) return channel::read_packing(o.packing);
    return channel::PreparedChannel{};  // run_acoustic needs the grains on rank 0 only
  }
  if (scene.import_lammps_data) {
    throw std::invalid_argument(scene.path.string() + ": scenes with import_lammps_data are not prepared by "
                                "`sedwave table`; prepare the packing first and pass it with --packing");
  }
  channel::PreparationSettings settings = scene.preparation;
  settings.log = (mpi.rank() == 0 && !o.quiet) ? &std::cout : nullptr;
  channel::PreparedChannel packing = channel::prepare_channel(
      MPI_COMM_WORLD, channel::generate_channel(scene.geometry), scene.contact, scene.geometry.width, settings);
  provenance = "packing prepared from the scene on " + std::to_string(mpi.size()) + " rank(s)";
  if (!packing.report.converged) provenance += " (preparation did NOT converge: see the log)";
  if (mpi.rank() == 0) {
    if (!packing.report.converged) std::cerr << "sedwave table: warning: the preparation did not converge\n";
    if (!o.packing.empty()) {
      channel::write_packing(o.packing, packing, scene.text);
      provenance += ", saved to " + o.packing;
    }
  }
  return packing;
}

table::TableMetadata table_metadata(const table::TableGridFile& grid, const channel::ChannelScene& scene,
                                    const std::string& packing_provenance) {
  table::TableMetadata m;
  m.scene_toml = scene.text;
  m.engine = "sedwave-dem";
  std::ostringstream definitions;
  definitions << table::standard_definitions() << "; " << grid.describe_axes() << "; " << packing_provenance
              << ".\nGrid file " << grid.path.string() << " (verbatim):\n"
              << grid.text;
  m.definitions = definitions.str();
  return m;
}

}  // namespace

Command add_table_command(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  CLI::App* cmd = app.add_subcommand(
      "table", "Fill a dispersion table (alpha_hat, c_hat on an omega_hat x gamma_hat grid) with the DEM channel; "
               "run under mpirun to share the points among ranks; rerun the same command to resume");
  cmd->add_option("grid", o->grid_file, "grid file (TOML): scene, omega_hat and gamma_hat axes (docs/tables.md)")
      ->required();
  cmd->add_option("--out", o->out, "table file (HDF5) to create, or to resume if it exists")->required();
  cmd->add_option("--packing", o->packing,
                  "packing file (HDF5): reused if it exists, else the prepared packing is saved there");
  cmd->add_flag("--retry-failed", o->retry_failed, "when resuming, compute failed points again");
  cmd->add_flag("--quiet", o->quiet, "no progress lines");
  return {cmd, [o]() {
    MpiSession mpi;
    // Every rank reads both files: they are small, and errors then stop all ranks alike.
    const table::TableGridFile grid = table::read_grid_file(o->grid_file);
    const channel::ChannelScene scene = channel::read_scene(grid.scene_path);
    if (mpi.size() % grid.ranks_per_point != 0) {
      throw std::invalid_argument(o->grid_file + ": ranks_per_point = " + std::to_string(grid.ranks_per_point) +
                                  " does not divide the " + std::to_string(mpi.size()) + " MPI ranks");
    }
    std::string provenance;
    channel::PreparedChannel packing = packing_for_table(scene, *o, mpi, provenance);
    table::share_packing_with_groups(MPI_COMM_WORLD, packing, grid.ranks_per_point);

    const table::FarmSettings settings{grid.ranks_per_point, (mpi.rank() == 0 && !o->quiet) ? &std::cout : nullptr,
                                       o->retry_failed};
    const table::FarmReport report =
        table::run_task_farm(MPI_COMM_WORLD, o->out, grid.grid, table_metadata(grid, scene, provenance),
                             table::dem_point_function(packing, scene.contact, scene.drive), settings);
    if (mpi.rank() == 0) {
      const double busy = report.wall_seconds > 0.0 ? report.point_seconds / (report.wall_seconds * mpi.size()) : 0.0;
      std::cout << "table " << o->out << ": " << report.points << " points, " << report.already_finished
                << " already finished, " << report.computed << " computed (" << report.ok << " ok, "
                << report.unresolved << " unresolved, " << report.failed << " failed) in " << report.wall_seconds
                << " s on " << mpi.size() << " rank(s); points took " << report.point_seconds
                << " s in all (ranks busy " << static_cast<int>(100.0 * busy * grid.ranks_per_point + 0.5)
                << " % of the time)\n";
    }
    return report.failed == 0 ? 0 : 2;
  }};
}

}  // namespace sedwave::app
