#include "sedwave/forward/channel/periodic_cell.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/channel/contacts.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::channel {
namespace {

/// The channel's grains (rank 0): flow grains of every copy first, then the lower and upper walls,
/// numbered 1, 2, ... in that order.
std::vector<dem::Grain> stacked_grains(const PreparedChannel& cell, int copies, double wall_thickness) {
  const double lo = cell.box.lo.z, length = cell.box.length(2);
  const double top = lo + copies * length;
  std::vector<dem::Grain> flow, lower, upper;
  for (int k = 0; k < copies; ++k) {
    for (dem::Grain g : cell.grains) {
      g.position.z += k * length;
      g.velocity = dem::Vec3{};
      if (g.position.z < lo + wall_thickness) {
        g.group = kLowerWallGroup;
        g.body = kLowerWallBody;
        lower.push_back(g);
      } else if (g.position.z >= top - wall_thickness) {
        g.group = kUpperWallGroup;
        g.body = kUpperWallBody;
        upper.push_back(g);
      } else {
        g.group = kFlowGroup;
        g.body = dem::kFreeBody;
        flow.push_back(g);
      }
    }
  }
  std::vector<dem::Grain> out;
  out.reserve(flow.size() + lower.size() + upper.size());
  for (const auto* part : {&flow, &lower, &upper}) out.insert(out.end(), part->begin(), part->end());
  for (std::size_t k = 0; k < out.size(); ++k) out[k].id = static_cast<std::int64_t>(k) + 1;
  return out;
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
  if (parallel::rank(comm) == 0) out.grains = stacked_grains(cell, copies, wall_thickness);

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
