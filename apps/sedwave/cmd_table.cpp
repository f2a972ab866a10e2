// `sedwave table`: fills a dispersion table (alpha_hat, c_hat on an omega_hat x gamma_hat grid) with
// the DEM channel (one driven run per grid point), the linear-response engine (one solve per
// point and ensemble member) or the packing's long-wavelength limit (one quasi-static solve per
// point and member, linear/long_wavelength.hpp), shared among MPI ranks by a task farm. One
// prepared packing serves every point. A killed run, restarted with the same command, continues
// where it stopped (docs/tables.md).
#include <mpi.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/channel/run_file.hpp"
#include "sedwave/forward/channel/scene.hpp"
#include "sedwave/forward/table/grid_file.hpp"
#include "sedwave/forward/linear/ensemble.hpp"
#include "sedwave/forward/linear/long_wavelength.hpp"
#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/task_farm.hpp"
#include "scene_packings.hpp"
#include "sedwave/io/fingerprint.hpp"

namespace sedwave::app {
namespace {

namespace channel = forward::channel;
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

/// The one packing every grid point starts from: read from --packing if that file exists, otherwise
/// prepared (collectively) and, with --packing, saved there so a restart skips the preparation.
channel::PreparedChannel packing_for_table(const channel::ChannelScene& scene, const TableOptions& o,
                                           const MpiSession& mpi, int member, std::string& provenance) {
  const std::string path = o.packing.empty() ? std::string{} : member_path(o.packing, member);
  if (!path.empty() && std::filesystem::exists(path)) {
    provenance = "packing read from " + path;
    if (mpi.rank() == 0) return channel::read_packing(path);
    return channel::PreparedChannel{};  // run_acoustic needs the grains on rank 0 only
  }
  if (scene.import_lammps_data) {
    throw std::invalid_argument(scene.path.string() + ": scenes with import_lammps_data are not prepared by "
                                "`sedwave table`; prepare the packing first and pass it with --packing");
  }
  channel::PreparedChannel packing =
      prepare_member(scene, member, mpi.rank(), (mpi.rank() == 0 && !o.quiet) ? &std::cout : nullptr);
  provenance = "packing prepared from the scene (seed + " + std::to_string(member) + ") on " +
               std::to_string(mpi.size()) + " rank(s)";
  if (!packing.report.converged) provenance += " (preparation did NOT converge: see the log)";
  if (mpi.rank() == 0) {
    if (!packing.report.converged) std::cerr << "sedwave table: warning: the preparation did not converge\n";
    if (!path.empty()) {
      channel::write_packing(path, packing, scene.text);
      provenance += ", saved to " + path;
    }
  }
  return packing;
}

table::TableMetadata table_metadata(const table::TableGridFile& grid, const channel::ChannelScene& scene,
                                    const std::string& packing_provenance, std::string packing_hash,
                                    bool long_wavelength, int member, int packings) {
  table::TableMetadata m;
  m.packing_hash = std::move(packing_hash);
  m.packings = packings;
  m.scene_toml = scene.text;
  m.engine = long_wavelength ? "sedwave-long-wavelength"
                             : (scene.engine == channel::EngineKind::linear ? "sedwave-linear" : "sedwave-dem");
  if (member >= 0) m.engine = forward::linear::member_engine_tag(member, scene.linear.ensemble);
  std::ostringstream definitions;
  definitions << table::standard_definitions() << "; " << grid.describe_axes() << "; " << packing_provenance
              << ".\nGrid file " << grid.path.string() << " (verbatim):\n"
              << grid.text;
  m.definitions = definitions.str();
  return m;
}

/// The table, its journal and packings that do not exist yet are written; the grid, the scene and
/// existing packings are read. All checked before any work.
void check_table_paths(const TableOptions& o, const table::TableGridFile& grid, const channel::ChannelScene& scene) {
  std::vector<OutputPath> outputs{{"--out", o.out}, {"--out", table::TableFile::journal_path(o.out)}};
  std::vector<std::filesystem::path> inputs{grid.path, grid.scene_path};
  if (scene.import_lammps_data) inputs.push_back(*scene.import_lammps_data);
  for (int k = 0; !o.packing.empty() && k < scene.linear.ensemble; ++k) {
    std::filesystem::path packing = member_path(o.packing, k);
    if (std::filesystem::exists(packing)) {
      inputs.push_back(packing);
    } else {
      outputs.push_back({"--packing", packing});
      outputs.push_back({"--packing", packing.replace_extension(".data")});  // its LAMMPS twin
    }
  }
  check_outputs(outputs, inputs, "table");
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
      ->check(CLI::IsMember({"time_domain", "linear", "long_wavelength"}));
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
    MpiSession mpi;
    // Every rank reads both files: they are small, and errors then stop all ranks alike.
    const table::TableGridFile grid = table::read_grid_file(o->grid_file);
    channel::ChannelScene scene = channel::read_scene(grid.scene_path);
    const bool long_wavelength = o->engine == "long_wavelength";
    if (!o->engine.empty()) {
      scene.engine = o->engine == "time_domain" ? channel::EngineKind::time_domain : channel::EngineKind::linear;
      // The long-wavelength engine solves a quasi-static problem: it reads neither the drive's
      // signal nor its far end, so only the driven linear engine checks them.
      if (o->engine == "linear" && scene.drive.pulse) {
        throw std::invalid_argument(grid.scene_path.string() +
                                    ": --engine linear solves each frequency directly; the scene's pulse drive "
                                    "is for the time-domain engine (use signal = \"sinusoid\")");
      }
      if (o->engine == "linear" && scene.drive.far_end != channel::FarEnd::absorbing) {
        throw std::invalid_argument(grid.scene_path.string() +
                                    ": --engine linear needs [drive] far_end = \"absorbing\" (a steady state "
                                    "with a frozen end is a standing wave)");
      }
    }
    if (mpi.size() % grid.ranks_per_point != 0) {
      throw std::invalid_argument(o->grid_file + ": ranks_per_point = " + std::to_string(grid.ranks_per_point) +
                                  " does not divide the " + std::to_string(mpi.size()) + " MPI ranks");
    }
    if (o->member >= 0 && (scene.engine != channel::EngineKind::linear || long_wavelength)) {
      throw std::invalid_argument("--member is for the driven linear engine (--engine linear, or engine = \"linear\" "
                                  "in the scene)");
    }
    if (o->member >= scene.linear.ensemble) {
      throw std::invalid_argument(grid.scene_path.string() + ": --member " + std::to_string(o->member) +
                                  " is outside the scene's ensemble of " + std::to_string(scene.linear.ensemble));
    }
    check_table_paths(*o, grid, scene);
    const int ranks_per_point = scene.engine == channel::EngineKind::linear ? 1 : grid.ranks_per_point;
    const table::FarmSettings settings{ranks_per_point, (mpi.rank() == 0 && !o->quiet) ? &std::cout : nullptr,
                                       o->retry_failed, o->allow_changed_inputs};
    table::FarmReport report;
    if (scene.engine == channel::EngineKind::linear) {
      // Every rank solves whole points serially and needs every member's packing.
      std::string provenance;
      std::vector<std::string> packing_hashes;  // member k's at k - first
      std::vector<forward::linear::LinearChannel> members;
      const int first = o->member >= 0 ? o->member : 0;
      const int last = o->member >= 0 ? o->member : scene.linear.ensemble - 1;
      for (int k = first; k <= last; ++k) {
        std::string member_provenance;
        channel::PreparedChannel packing = packing_for_table(scene, *o, mpi, k, member_provenance);
        table::share_packing_with_groups(MPI_COMM_WORLD, packing, 1);
        packing_hashes.push_back(channel::packing_fingerprint(packing));
        members.emplace_back(packing, scene.contact, scene.linear);
        provenance += (k > first ? "; " : "") + member_provenance;
      }
      const table::PointFunction point =
          long_wavelength  ? forward::linear::long_wavelength_point_function(members, scene.drive.axis)
          : o->member >= 0 ? forward::linear::member_point_function(members.front(), scene.drive)
                           : forward::linear::linear_point_function(members, scene.drive);
      // A member table records its one packing; merging member tables combines them as here.
      const std::string packing_hash =
          o->member >= 0 ? packing_hashes.front() : io::combined_fingerprint(packing_hashes);
      report = table::run_task_farm(MPI_COMM_WORLD, o->out, grid.grid,
                                    table_metadata(grid, scene, provenance, packing_hash, long_wavelength, o->member,
                                                   static_cast<int>(members.size())),
                                    point, settings);
    } else {
      std::string provenance;
      channel::PreparedChannel packing = packing_for_table(scene, *o, mpi, 0, provenance);
      table::share_packing_with_groups(MPI_COMM_WORLD, packing, grid.ranks_per_point);
      const table::TableMetadata metadata =
          table_metadata(grid, scene, provenance, channel::packing_fingerprint(packing), false, -1, 1);
      report = table::run_task_farm(MPI_COMM_WORLD, o->out, grid.grid, metadata,
                                    table::dem_point_function(packing, scene.contact, scene.drive, grid.grid), settings);
    }
    if (mpi.rank() == 0) {
      const double busy = report.wall_seconds > 0.0 ? report.point_seconds / (report.wall_seconds * mpi.size()) : 0.0;
      std::cout << "table " << o->out << ": " << report.points << " points, " << report.already_finished
                << " already finished, " << report.computed << " computed (" << report.ok << " ok, "
                << report.unresolved << " unresolved, " << report.failed << " failed) in " << report.wall_seconds
                << " s on " << mpi.size() << " rank(s); points took " << report.point_seconds
                << " s in all (ranks busy " << static_cast<int>(100.0 * busy * ranks_per_point + 0.5)
                << " % of the time)\n";
    }
    return report.failed == 0 ? kExitOk : kExitIncomplete;
  }};
}

}  // namespace sedwave::app
