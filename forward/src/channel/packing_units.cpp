#include "sedwave/forward/channel/packing_units.hpp"

#include <array>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/channel/contacts.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {

StaticContacts static_contacts(MPI_Comm comm, const PreparedChannel& packing, const dem::ContactSpec& contact) {
  std::array<double, 3> v{};  // mean stiffness, mean dashpot, force on the upper wall
  if (parallel::sum(comm, packing.grains.empty() ? 0 : 1) <= 1) {
    // One rank holds the packing: its contact network, as the linear engine sees it. A refusal
    // there (a box too small for the network) reaches every rank.
    const std::string error = parallel::failure_of(
        [&] {
          if (packing.grains.empty()) return;
          const ContactNetwork n = find_contacts(packing.grains, packing.box, contact);
          v = {n.mean_stiffness, n.mean_dashpot, static_body_force(packing.grains, n, kUpperWallBody).z};
        },
        "contact network failed");
    parallel::throw_first_failure(comm, error);
    parallel::sum(comm, std::span(v));
  } else {
    // Spread over ranks: the DEM engine's ghosts and lists find the pairs across them. Without its
    // dashpot, the wall's force is the springs' alone, as in the contact network, whatever
    // velocities the grains carry.
    dem::EngineSettings settings;
    settings.box = broadcast_box(comm, packing.box);
    settings.contact = dem::without_dashpot(contact);
    const dem::Engine engine(comm, settings, packing.grains,
                             {dem::RigidBody("lower_wall", dem::Frozen{}), dem::RigidBody("upper_wall", dem::Frozen{})});
    const ContactMeans means = contact_means(engine, contact);
    v = {means.stiffness, means.dashpot, engine.bodies()[1].contact_force().z};
  }
  return {v[0], v[1], v[2]};
}

bool units_need_static_contacts(const dem::ContactSpec& contact) {
  return !(dem::stiffness_at_contact(dem::undamped_contact_model(contact)) > 0.0);
}

PackingUnits packing_units(MPI_Comm comm, const PreparedChannel& packing, const dem::ContactSpec& contact,
                           const StaticContacts* known) {
  // Sums over every rank's grains: flow count, diameters, masses / volumes (density), lower wall
  // (z + r) and count, upper wall (z - r) and count, flow volume.
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
  if (s[0] < 1 || s[4] < 1 || s[6] < 1) throw parallel::AgreedFailure(comm, "packing has no flow grains or lacks a wall");
  PackingUnits u;
  u.diameter = s[1] / s[0];
  u.mass = grain_mass(s[2] / s[0], u.diameter);
  // A linear normal law has one stiffness; any other is measured over the packing's contacts.
  u.kappa = dem::stiffness_at_contact(dem::undamped_contact_model(contact));
  double dashpot = 1.0;  // mean dashpot per unit coefficient
  if (units_need_static_contacts(contact)) {
    const StaticContacts network = known != nullptr ? *known : static_contacts(comm, packing, contact);
    if (!(network.mean_stiffness > 0.0)) throw parallel::AgreedFailure(comm, "packing units: the packing has no contacts");
    u.kappa = network.mean_stiffness;
    dashpot = network.mean_dashpot;
  }
  u.wall_surface = s[3] / s[4];
  u.column_top = s[5] / s[6];
  const dem::Box box = broadcast_box(comm, packing.box);  // as rank 0 holds it
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
