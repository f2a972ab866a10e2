#include "sedwave/forward/channel/periodic_cell.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/channel/contacts.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::channel {
namespace {

/// Where each copy's grains go: the lower wall, the upper wall or the flow.
enum class Part { flow, lower, upper };

Part part_of(double z, double lo, double top, double wall_thickness) {
  if (z < lo + wall_thickness) return Part::lower;
  if (z >= top - wall_thickness) return Part::upper;
  return Part::flow;
}

/// This rank's share of the channel, in id order: copies [first, last) of the cell (every rank holds the cell),
/// numbered as if one rank had stacked them all: flow grains of every copy first, then the lower and
/// upper walls, 1, 2, ... in copy order and the cell's order within a copy. Each rank counts the
/// parts of every copy (copies x cell comparisons, no communication) to know where its ids start.
std::vector<dem::Grain> stacked_grains(const PreparedChannel& cell, int copies, double wall_thickness, int first,
                                       int last) {
  const double lo = cell.box.lo.z, length = cell.box.length(2);
  const double top = lo + copies * length;
  // starts[part][k]: the id before copy k's first grain of that part.
  std::array<std::vector<std::int64_t>, 3> starts;
  for (auto& s : starts) s.assign(static_cast<std::size_t>(copies) + 1, 0);
  for (int k = 0; k < copies; ++k) {
    std::array<std::int64_t, 3> counts{};
    for (const dem::Grain& g : cell.grains)
      ++counts[static_cast<std::size_t>(part_of(g.position.z + k * length, lo, top, wall_thickness))];
    for (std::size_t p = 0; p < 3; ++p) starts[p][static_cast<std::size_t>(k) + 1] = starts[p][static_cast<std::size_t>(k)] + counts[p];
  }
  const std::int64_t flow_total = starts[0].back(), lower_total = starts[1].back();
  for (std::int64_t& s : starts[1]) s += flow_total;
  for (std::int64_t& s : starts[2]) s += flow_total + lower_total;

  std::array<std::vector<dem::Grain>, 3> parts;
  for (int k = first; k < last; ++k) {
    std::array<std::int64_t, 3> next{starts[0][static_cast<std::size_t>(k)], starts[1][static_cast<std::size_t>(k)],
                                     starts[2][static_cast<std::size_t>(k)]};
    for (dem::Grain g : cell.grains) {
      g.position.z += k * length;
      g.velocity = dem::Vec3{};
      const Part part = part_of(g.position.z, lo, top, wall_thickness);
      g.group = part == Part::lower ? kLowerWallGroup : part == Part::upper ? kUpperWallGroup : kFlowGroup;
      g.body = part == Part::lower ? kLowerWallBody : part == Part::upper ? kUpperWallBody : dem::kFreeBody;
      g.id = ++next[static_cast<std::size_t>(part)];
      parts[static_cast<std::size_t>(part)].push_back(g);
    }
  }
  // In id order on this rank: the flow, then the walls.
  std::vector<dem::Grain> out = std::move(parts[0]);
  for (std::size_t p = 1; p < 3; ++p) {
    out.insert(out.end(), parts[p].begin(), parts[p].end());
    std::vector<dem::Grain>().swap(parts[p]);
  }
  return out;
}

/// The cell's grains on every rank of comm (a cell is small: 10^4 grains are 1.5 MB).
std::vector<dem::Grain> cell_on_every_rank(MPI_Comm comm, const std::vector<dem::Grain>& grains) {
  std::vector<dem::Grain> all = grains;
  parallel::broadcast(comm, all);
  return all;
}

}  // namespace

PreparedChannel tile_periodic_cell(MPI_Comm comm, const PreparedChannel& cell, const dem::ContactSpec& contact,
                                   int copies, double wall_thickness) {
  // What rank 0 knows about the cell, for every rank to check: z-periodic, largest and mean
  // diameter, flow grains.
  double facts[4] = {cell.box.periodic[2] ? 1.0 : 0.0, 0.0, 0.0, 0.0};
  for (const dem::Grain& g : cell.grains) {
    if (g.group != kFlowGroup) facts[0] = 0.0;  // a cell has flow grains only
    facts[1] = std::max(facts[1], 2.0 * g.radius);
    facts[2] += 2.0 * g.radius;
    facts[3] += 1.0;
  }
  parallel::broadcast(comm, std::span(facts));
  if (facts[0] == 0.0 || facts[3] == 0.0) {
    throw std::invalid_argument("tiling: the cell must be periodic along z and hold flow grains only");
  }
  if (copies < 1) throw std::invalid_argument("tiling: need at least one copy of the cell");
  if (!(wall_thickness >= facts[1])) {
    throw std::invalid_argument("tiling: walls " + std::to_string(wall_thickness) +
                                " thick would cut contacts of flow grains; make them at least the largest grain (" +
                                std::to_string(facts[1]) + ")");
  }

  PreparedChannel out;
  out.box = broadcast_box(comm, cell.box);
  const double lo = out.box.lo.z, length = out.box.length(2);
  out.box.periodic[2] = false;
  out.box.lo.z = lo - 1.0;  // an open axis only describes where the grains are
  out.box.hi.z = lo + copies * length + 1.0;
  {
    PreparedChannel shared;
    shared.box = out.box;
    shared.box.periodic[2] = true;
    shared.box.lo.z = lo;
    shared.box.hi.z = lo + length;
    shared.grains = cell_on_every_rank(comm, cell.grains);
    // Contiguous copies per rank: close to the slabs the engine cuts, so few grains migrate.
    const int rank = parallel::rank(comm), ranks = parallel::size(comm);
    const auto share = [&](int r) { return static_cast<int>(static_cast<std::int64_t>(copies) * r / ranks); };
    out.grains = stacked_grains(shared, copies, wall_thickness, share(rank), share(rank + 1));
  }

  // Measure the channel as the DEM sees it: its forces, contacts and the load on the upper wall.
  dem::EngineSettings settings;
  settings.box = out.box;
  settings.contact = contact;
  const dem::Engine engine(comm, settings, out.grains,
                           {dem::RigidBody("lower_wall", dem::Frozen{}), dem::RigidBody("upper_wall", dem::Frozen{})});
  const double width = out.box.length(0);
  out.report = cell.report;
  out.report.stats = packing_stats(engine, facts[2] / facts[3], width);
  out.report.wall_force = engine.bodies()[1].contact_force().z;
  out.report.pressure = out.report.wall_force / (width * out.box.length(1));
  const PackingStats& s = out.report.stats;
  out.report.residual_ratio = s.mean_contact_force > 0.0 ? s.max_residual_force / s.mean_contact_force : 0.0;
  return out;
}

}  // namespace sedwave::forward::channel
