#include "sedwave/forward/experiment/packings.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <system_error>
#include <type_traits>

#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/linear/newton_stage.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/io/file_lock.hpp"

namespace sedwave::forward::experiment {
namespace {

/// The loose column from the scene (generated, or a LAMMPS data file), on rank 0 only.
channel::ChannelConfiguration initial_column(const ChannelScene& scene, int k, int rank) {
  using namespace channel;
  if (rank != 0) return {};
  if (!scene.import_lammps_data) {
    ChannelGeometry geometry = scene.geometry;
    geometry.seed += static_cast<std::uint64_t>(k);
    if (scene.tiling) {
      geometry.n_grains = scene.tiling->cell_grains;
      geometry.periodic = true;
    }
    return generate_channel(geometry);
  }
  if (k > 0) throw std::invalid_argument(scene.path.string() + ": an imported packing cannot form an ensemble");
  const dem::LammpsData data = dem::read_lammps_data(scene.import_lammps_data->string());
  ChannelConfiguration c;
  c.box = data.box;
  c.box.periodic = {true, true, false};
  for (dem::Grain g : data.grains) {
    // Thesis convention: type 1 flow grains, 2 lower wall, 3 upper wall.
    g.group -= 1;
    if (g.group < kFlowGroup || g.group > kUpperWallGroup) {
      throw std::runtime_error(scene.import_lammps_data->string() + ": atom " + std::to_string(g.id) +
                               " has a type other than 1 (flow), 2 (lower wall) or 3 (upper wall)");
    }
    g.body = g.group == kLowerWallGroup ? kLowerWallBody : g.group == kUpperWallGroup ? kUpperWallBody : 0;
    c.grains.push_back(g);
  }
  return c;
}

}  // namespace

std::vector<dem::Grain> spread_by_id(MPI_Comm comm, const std::vector<dem::Grain>& grains) {
  std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = std::numeric_limits<std::int64_t>::min();
  for (const dem::Grain& g : grains) {
    lo = std::min(lo, g.id);
    hi = std::max(hi, g.id);
  }
  lo = parallel::min(comm, lo);
  hi = parallel::max(comm, hi);
  const int ranks = parallel::size(comm);
  std::vector<std::vector<dem::Grain>> outgoing(static_cast<std::size_t>(ranks));
  if (lo <= hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
    const std::uint64_t width = (span + static_cast<std::uint64_t>(ranks) - 1) / static_cast<std::uint64_t>(ranks);
    for (const dem::Grain& g : grains) outgoing[static_cast<std::uint64_t>(g.id - lo) / width].push_back(g);
  }
  std::vector<dem::Grain> mine = parallel::all_to_all(comm, outgoing);
  std::sort(mine.begin(), mine.end(), [](const dem::Grain& a, const dem::Grain& b) { return a.id < b.id; });
  return mine;
}

std::string member_path(const std::string& path, int k) {
  if (k == 0) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + ".member" + std::to_string(k) + p.extension().string())).string();
}

channel::PreparedChannel prepare_member(const ChannelScene& scene, int k, int rank, std::ostream* log) {
  channel::PreparationSettings settings = scene.preparation;
  settings.log = log;
  channel::PreparedChannel packing = channel::prepare_channel(
      MPI_COMM_WORLD, initial_column(scene, k, rank), scene.contact, scene.geometry.width, settings,
      linear::newton_stage());
  if (!scene.tiling) return packing;
  if (log) *log << "periodic cell:\n" << channel::describe(packing.report) << "\n";
  const int copies = scene.geometry.n_grains / scene.tiling->cell_grains;
  channel::PreparedChannel tiled = channel::tile_periodic_cell(
      MPI_COMM_WORLD, packing, scene.contact, copies, scene.tiling->wall_thickness);
  // Saved, fingerprinted and shared with the task farm's groups in id order, no rank holding all.
  tiled.grains = spread_by_id(MPI_COMM_WORLD, tiled.grains);
  if (log) *log << "tiled " << copies << " copies of the cell into a channel of " << scene.geometry.n_grains << " grains\n";
  return tiled;
}

ScenePacking scene_packing(const ChannelScene& scene, int k, const PackingFiles& files, std::ostream* log) {
  const int rank = parallel::rank(MPI_COMM_WORLD);
  const std::string save = files.save.empty() ? std::string() : member_path(files.save, k);
  std::string read = files.read.empty() ? std::string() : member_path(files.read, k);
  const auto saved = [&] {
    return parallel::root_says(MPI_COMM_WORLD, [&] {
      std::error_code unreadable;  // a folder this run cannot look into: not saved, and the lock says why
      return std::filesystem::exists(save, unreadable);
    });
  };
  // One run at a time prepares and saves a packing path (rank 0 holds its lock): a second run saving
  // there waits, and one reusing it (a table of another grid sharing its --packing) then reads what
  // the first saved instead of preparing its own. A packing already there is read without the lock,
  // so it may lie where this run cannot write.
  std::optional<io::FileLock> lock;
  if (!save.empty() && !(files.reuse() && saved())) {
    std::string error;
    if (rank == 0) {
      error = parallel::failure_of([&] {
        lock.emplace(save + ".lock", [&] {
          if (log != nullptr) *log << "waiting while another process prepares or writes " << save << std::endl;
        });
      }, "cannot lock " + save);
    }
    parallel::barrier_sleeping(MPI_COMM_WORLD);  // the other ranks wait for rank 0's lock without spinning
    parallel::throw_first_failure(MPI_COMM_WORLD, error);
    if (files.reuse() && !saved()) read.clear();
  }
  ScenePacking out;
  if (!read.empty()) {
    out.provenance = "packing read from " + read;
    out.channel = read_packing(MPI_COMM_WORLD, read);
    return out;
  }
  out.channel = prepare_member(scene, k, rank, log);
  out.prepared = true;
  out.provenance = "packing prepared from the scene (seed + " + std::to_string(k) + ") on " +
                   std::to_string(parallel::size(MPI_COMM_WORLD)) + " rank(s)";
  if (!out.channel.report.converged) out.provenance += " (preparation did NOT converge: see the log)";
  if (!save.empty()) {
    write_packing(MPI_COMM_WORLD, save, out.channel, scene.text);
    out.provenance += ", saved to " + save;
  }
  return out;
}

void share_packing_with_groups(MPI_Comm world, channel::PreparedChannel& packing, int ranks_per_point) {
  static_assert(std::is_trivially_copyable_v<dem::Grain> && std::is_trivially_copyable_v<dem::Box>);
  parallel::broadcast(world, std::as_writable_bytes(std::span(&packing.box, 1)));
  // Rank q of every group takes the grains of the world ranks w = q (mod ranks_per_point): the ranks
  // at one place in every group meet in one communicator and each gets all its members' grains.
  const parallel::SubCommunicator place(world, parallel::SubCommunicator::Colour{parallel::rank(world) % ranks_per_point});
  std::vector<dem::Grain> grains = parallel::gather_on_root(place.get(), packing.grains);
  parallel::broadcast(place.get(), grains);
  packing.grains = std::move(grains);
}

}  // namespace sedwave::forward::experiment
