#include "sedwave/forward/channel/packing_units.hpp"

#include <numbers>
#include <stdexcept>

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {

PackingUnits packing_units(MPI_Comm comm, const PreparedChannel& packing, const dem::ContactSpec& contact) {
  // Sums on whichever rank holds the grains: flow count, diameters, masses / volumes (density),
  // lower wall (z + r) and count, upper wall (z - r) and count.
  double s[7] = {0, 0, 0, 0, 0, 0, 0};
  for (const dem::Grain& g : packing.grains) {
    if (g.group == kFlowGroup) {
      s[0] += 1.0;
      s[1] += 2.0 * g.radius;
      s[2] += g.mass / (std::numbers::pi / 6.0 * std::pow(2.0 * g.radius, 3));
    } else if (g.group == kLowerWallGroup) {
      s[3] += g.position.z + g.radius;
      s[4] += 1.0;
    } else {
      s[5] += g.position.z - g.radius;
      s[6] += 1.0;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 7, MPI_DOUBLE, MPI_SUM, comm);
  if (s[0] < 1 || s[4] < 1 || s[6] < 1) throw std::invalid_argument("packing has no flow grains or lacks a wall");
  PackingUnits u;
  u.diameter = s[1] / s[0];
  u.mass = grain_mass(s[2] / s[0], u.diameter);
  u.kappa = contact.normal == dem::NormalLawKind::hooke ? contact.kn : 1.0;
  u.wall_surface = s[3] / s[4];
  u.column_top = s[5] / s[6];
  return u;
}

}  // namespace sedwave::forward::channel
