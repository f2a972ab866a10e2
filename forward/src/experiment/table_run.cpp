#include "sedwave/forward/experiment/table_run.hpp"

#include <filesystem>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "sedwave/forward/experiment/linear_points.hpp"
#include "sedwave/forward/experiment/packings.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/experiment/time_domain_points.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/io/fingerprint.hpp"

namespace sedwave::forward::experiment {
namespace {

/// The engine a table file names.
std::string engine_tag(const ChannelScene& scene, const TableRun& run) {
  if (run.member >= 0) return member_engine_tag(run.member, scene.linear.ensemble);
  switch (run.engine) {
    case EngineKind::time_domain: return "sedwave-dem";
    case EngineKind::linear: return "sedwave-linear";
    case EngineKind::long_wavelength: return "sedwave-long-wavelength";
  }
  throw std::logic_error("unknown table engine");
}

table::TableMetadata table_metadata(const table::TableGridFile& grid, const ChannelScene& scene, const TableRun& run,
                                    const std::string& packing_provenance, std::string packing_hash, int packings) {
  table::TableMetadata m;
  m.packing_hash = std::move(packing_hash);
  m.packings = packings;
  if (scene.drive.fluid) m.pore_fluid = channel::describe_fluid_groups(*scene.drive.fluid);
  m.scene_toml = scene.text;
  m.engine = engine_tag(scene, run);
  std::ostringstream definitions;
  definitions << table::standard_definitions() << "; " << grid.describe_axes() << "; " << packing_provenance
              << ".\nGrid file " << grid.path.string() << " (verbatim):\n"
              << grid.text;
  m.definitions = definitions.str();
  return m;
}

/// Member k's packing for the table: reused from run.packing, or prepared (and saved there).
ScenePacking table_packing(const ChannelScene& scene, const TableRun& run, int k) {
  const PackingFiles files = PackingFiles::reuse(run.packing);
  if (scene.import_lammps_data) {  // rank 0 looks, so that every rank refuses alike
    const bool missing = parallel::root_says(MPI_COMM_WORLD, [&] {
      std::error_code unreadable;
      return !std::filesystem::exists(member_path(run.packing, k), unreadable);
    });
    if (missing) {
      throw parallel::AgreedFailure(MPI_COMM_WORLD, scene.path.string() + ": scenes with import_lammps_data are not "
                                    "prepared by `sedwave table`; prepare the packing first and pass it with --packing");
    }
  }
  ScenePacking packing = scene_packing(scene, k, files, run.log);
  if (packing.prepared && !packing.channel.report.converged && run.warnings) {
    *run.warnings << "sedwave table: warning: the preparation did not converge\n";
  }
  return packing;
}

/// The time-domain engine: every point drives the one packing, spread over its group's ranks.
table::FarmReport fill_time_domain(const table::TableGridFile& grid, const ChannelScene& scene, const TableRun& run,
                                   const table::FarmSettings& farm) {
  ScenePacking packing = table_packing(scene, run, 0);
  const std::string hash = packing_fingerprint(MPI_COMM_WORLD, packing.channel);
  share_packing_with_groups(MPI_COMM_WORLD, packing.channel, farm.ranks_per_point);
  const table::TableMetadata metadata = table_metadata(grid, scene, run, packing.provenance, hash, 1);
  return table::run_task_farm(MPI_COMM_WORLD, run.table, grid.grid, metadata,
                              dem_point_function(packing.channel, scene.contact, scene.drive, grid.grid), farm);
}

/// The linear engines: every rank solves whole points serially and needs every member's packing.
table::FarmReport fill_linear(const table::TableGridFile& grid, const ChannelScene& scene, const TableRun& run,
                              const table::FarmSettings& farm) {
  std::string provenance;
  std::vector<std::string> packing_hashes;  // member k's at k - first
  std::vector<linear::LinearChannel> members;
  const int first = run.member >= 0 ? run.member : 0;
  const int last = run.member >= 0 ? run.member : scene.linear.ensemble - 1;
  for (int k = first; k <= last; ++k) {
    ScenePacking packing = table_packing(scene, run, k);
    packing_hashes.push_back(packing_fingerprint(MPI_COMM_WORLD, packing.channel));
    share_packing_with_groups(MPI_COMM_WORLD, packing.channel, 1);
    members.emplace_back(packing.channel, scene.contact, scene.linear, scene.drive.fluid);
    provenance += (k > first ? "; " : "") + packing.provenance;
  }
  const table::PointFunction point =
      run.engine == EngineKind::long_wavelength ? long_wavelength_point_function(members, scene.drive.axis)
      : run.member >= 0                          ? member_point_function(members.front(), scene.drive)
                                                 : linear_point_function(members, scene.drive);
  // A member table records its one packing; merging member tables combines them as here.
  const std::string packing_hash = run.member >= 0 ? packing_hashes.front() : io::combined_fingerprint(packing_hashes);
  return table::run_task_farm(
      MPI_COMM_WORLD, run.table, grid.grid,
      table_metadata(grid, scene, run, provenance, packing_hash, static_cast<int>(members.size())), point, farm);
}

}  // namespace

void use_table_engine(ChannelScene& scene, EngineKind engine) {
  scene.engine = engine;
  if (engine == EngineKind::long_wavelength && scene.drive.fluid) {
    // Refused before any packing is prepared: every point would fail (linear/long_wavelength.hpp).
    throw std::invalid_argument(scene.path.string() + ": the long-wavelength limit is not defined with a pore fluid "
                                "([fluid]: its dashpots do not scale with gamma_hat); use --engine linear");
  }
  if (const std::string refusal = engine_refusal(engine, scene.drive); !refusal.empty()) {
    throw std::invalid_argument(scene.path.string() + ": the linear engine cannot run this scene: [drive] " + refusal);
  }
}

int ranks_per_point(const table::TableGridFile& grid, EngineKind engine) {
  return engine == EngineKind::time_domain ? grid.ranks_per_point : 1;
}

table::FarmReport fill_table(const table::TableGridFile& grid, const ChannelScene& scene, const TableRun& run,
                             table::FarmSettings farm) {
  farm.ranks_per_point = ranks_per_point(grid, run.engine);
  if (run.engine == EngineKind::time_domain) return fill_time_domain(grid, scene, run, farm);
  return fill_linear(grid, scene, run, farm);
}

}  // namespace sedwave::forward::experiment
