#include "scene_packings.hpp"

#include <filesystem>
#include <stdexcept>

#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"

namespace sedwave::app {
namespace {

/// The loose column from the scene (generated, or a LAMMPS data file), on rank 0 only.
forward::channel::ChannelConfiguration initial_column(const forward::channel::ChannelScene& scene, int k, int rank) {
  using namespace forward::channel;
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
  const forward::dem::LammpsData data = forward::dem::read_lammps_data(scene.import_lammps_data->string());
  ChannelConfiguration c;
  c.box = data.box;
  c.box.periodic = {true, true, false};
  for (forward::dem::Grain g : data.grains) {
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

std::string member_path(const std::string& path, int k) {
  if (k == 0) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + ".member" + std::to_string(k) + p.extension().string())).string();
}

forward::channel::PreparedChannel prepare_member(const forward::channel::ChannelScene& scene, int k, int rank,
                                                 std::ostream* log) {
  forward::channel::PreparationSettings settings = scene.preparation;
  settings.log = log;
  forward::channel::PreparedChannel packing = forward::channel::prepare_channel(
      MPI_COMM_WORLD, initial_column(scene, k, rank), scene.contact, scene.geometry.width, settings);
  if (!scene.tiling) return packing;
  if (log) *log << "periodic cell:\n" << forward::channel::describe(packing.report) << "\n";
  const int copies = scene.geometry.n_grains / scene.tiling->cell_grains;
  forward::channel::PreparedChannel channel = forward::channel::tile_periodic_cell(
      MPI_COMM_WORLD, packing, scene.contact, copies, scene.tiling->wall_thickness);
  if (log) *log << "tiled " << copies << " copies of the cell into a channel of " << scene.geometry.n_grains << " grains\n";
  return channel;
}

}  // namespace sedwave::app
