#include "sedwave/forward/channel/packing_units.hpp"

#include <numbers>
#include <sstream>
#include <stdexcept>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {

PackingUnits packing_units(MPI_Comm comm, const PreparedChannel& packing, const dem::ContactSpec& contact) {
  // Sums on whichever rank holds the grains: flow count, diameters, masses / volumes (density),
  // lower wall (z + r) and count, upper wall (z - r) and count.
  double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (const dem::Grain& g : packing.grains) {
    if (g.group == kFlowGroup) {
      s[0] += 1.0;
      s[1] += 2.0 * g.radius;
      const double volume = std::numbers::pi / 6.0 * std::pow(2.0 * g.radius, 3);
      s[2] += g.mass / volume;
      s[7] += volume;
    } else if (g.group == kLowerWallGroup) {
      s[3] += g.position.z + g.radius;
      s[4] += 1.0;
    } else {
      s[5] += g.position.z - g.radius;
      s[6] += 1.0;
    }
  }
  parallel::sum(comm, std::span(s));
  if (s[0] < 1 || s[4] < 1 || s[6] < 1) throw std::invalid_argument("packing has no flow grains or lacks a wall");
  PackingUnits u;
  u.diameter = s[1] / s[0];
  u.mass = grain_mass(s[2] / s[0], u.diameter);
  // A linear normal law has one stiffness; any other is measured over the packing's contacts.
  u.kappa = dem::stiffness_at_contact(dem::undamped_contact_model(contact));
  double dashpot = 1.0;  // mean dashpot per unit coefficient
  if (!(u.kappa > 0.0)) {
    double network[2] = {0.0, 0.0};  // mean stiffness, mean dashpot (from the rank holding the grains)
    int holds = packing.grains.empty() ? 0 : 1;
    if (parallel::sum(comm, holds) != 1) {
      throw std::invalid_argument("packing units of Hertz contacts: the grains must be on one rank");
    }
    if (!packing.grains.empty()) {
      const ContactNetwork n = find_contacts(packing.grains, packing.box, contact);
      network[0] = n.mean_stiffness;
      network[1] = n.mean_dashpot;
    }
    parallel::sum(comm, std::span(network));
    if (!(network[0] > 0.0)) throw std::invalid_argument("packing units: the packing has no contacts");
    u.kappa = network[0];
    dashpot = network[1];
  }
  u.wall_surface = s[3] / s[4];
  u.column_top = s[5] / s[6];
  const dem::Box box = broadcast_box(comm, packing.box);  // rank 0 holds the packing
  const double cross_section = box.length(0) * box.length(1);
  u.porosity = 1.0 - s[7] / (cross_section * (u.column_top - u.wall_surface));
  u.damping_scale = std::sqrt(u.kappa * u.mass) / dashpot;
  return u;
}

std::string describe_fluid_groups(const dem::FluidSpec& f) {
  std::ostringstream s;
  s.precision(6);
  s << "mu_hat " << f.viscosity << ", roughness " << f.roughness << " d, cutoff " << f.cutoff << " d, "
    << (f.lubrication ? "lubrication" : "no lubrication") << ", drag " << dem::drag_law_name(f.drag);
  if (f.drag == dem::DragLaw::richardson_zaki) {
    if (f.porosity == 0.0) s << " (porosity of the packing)";
    else s << " (porosity " << f.porosity << ")";
  }
  return s.str();
}

dem::FluidSpec fluid_in_packing_units(const dem::FluidSpec& dimensionless, const PackingUnits& u) {
  dem::FluidSpec f = dimensionless;
  f.viscosity = dimensionless.viscosity * std::sqrt(u.kappa * u.mass) / u.diameter;
  f.roughness = dimensionless.roughness * u.diameter;
  f.cutoff = dimensionless.cutoff * u.diameter;
  f.density = dimensionless.density * 6.0 * u.mass / (std::numbers::pi * std::pow(u.diameter, 3));
  if (f.porosity == 0.0) f.porosity = u.porosity;
  return f;
}

}  // namespace sedwave::forward::channel
