#include "sedwave/forward/channel/contact_network.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <variant>

namespace sedwave::forward::channel {
dem::AnyContactModel unit_damping_law(const dem::ContactSpec& contact) {
  // Unit damping coefficient: a constant dashpot of 1 (Hooke) or alpha = 1 (Hertz-Tsuji).
  dem::ContactSpec unit = dem::without_dashpot(contact);
  unit[std::string(dem::keys::gamma.key)] = 1.0;
  return dem::make_contact_model(unit);
}

PairLinearisation linearise_pair(const dem::AnyContactModel& unit, double effective_mass, double radius_i,
                                 double radius_j, double overlap) {
  PairLinearisation p;
  const double r_eff = radius_i * radius_j / (radius_i + radius_j);
  std::visit(
      [&](const auto& m) {
        const dem::ContactOscillator linearised = m.normal.oscillator(effective_mass, r_eff, std::max(overlap, 0.0));
        p.dashpot = linearised.damping;
        if (overlap <= 0.0) return;
        p.force = dem::static_normal_force(m.normal, overlap, radius_i, radius_j);
        p.stiffness = linearised.stiffness;
        p.energy = m.normal.energy(overlap, radius_i, radius_j);
      },
      unit);
  return p;
}

double pair_effective_mass(double mass_i, int body_i, double mass_j, int body_j) {
  if (body_i != dem::kFreeBody) return mass_j;
  if (body_j != dem::kFreeBody) return mass_i;
  return mass_i * mass_j / (mass_i + mass_j);
}

ContactNetwork find_contacts(std::span<const dem::Grain> grains, const dem::Box& box,
                             const dem::ContactSpec& contact, double gap_search) {
  const dem::AnyContactModel model = unit_damping_law(contact);
  double max_radius = 0.0;
  for (const dem::Grain& g : grains) max_radius = std::max(max_radius, g.radius);
  const double reach = 2.0 * max_radius + gap_search;
  for (int a = 0; a < 2; ++a) {
    if (box.periodic[static_cast<std::size_t>(a)] && box.length(a) < reach) {
      throw std::invalid_argument("contact network: the periodic box is narrower than two grain diameters");
    }
  }
  // Along z a pair may touch through one image at most, so every image is found once.
  if (box.periodic[2] && box.length(2) < 2.0 * reach) {
    throw std::invalid_argument("contact network: a z-periodic box must be at least four grain diameters long");
  }
  // Sweep along z: every pair within `reach` in z, each periodic image tested.
  std::vector<std::int32_t> order(grains.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return grains[static_cast<std::size_t>(a)].position.z < grains[static_cast<std::size_t>(b)].position.z;
  });
  const int sx = box.periodic[0] ? 1 : 0;
  const int sy = box.periodic[1] ? 1 : 0;

  ContactNetwork net;
  net.contacts_per_grain.assign(grains.size(), 0);
  double stiffness_sum = 0.0, dashpot_sum = 0.0;
  // Tests grain i against every x-y image of grain j lifted by shift_z.
  const auto test_pair = [&](std::int32_t i, std::int32_t j, double shift_z) {
    const dem::Grain& gi = grains[static_cast<std::size_t>(i)];
    const dem::Grain& gj = grains[static_cast<std::size_t>(j)];
    if (gi.body != dem::kFreeBody && gj.body != dem::kFreeBody) return;
    for (int ix = -sx; ix <= sx; ++ix) {
      for (int iy = -sy; iy <= sy; ++iy) {
        const dem::Vec3 shift{ix * box.length(0), iy * box.length(1), shift_z};
        const dem::Vec3 d = gi.position - (gj.position + shift);
        const double distance = dem::norm(d);
        const double overlap = gi.radius + gj.radius - distance;
        if (overlap <= -gap_search) continue;
        const double m_eff = pair_effective_mass(gi.mass, gi.body, gj.mass, gj.body);
        const PairLinearisation l = linearise_pair(model, m_eff, gi.radius, gj.radius, overlap);
        const StaticPair p{i, j, (1.0 / distance) * d, distance, overlap, l.force, l.stiffness, l.dashpot, m_eff,
                           gi.radius - 0.5 * overlap, gj.radius - 0.5 * overlap, l.energy};
        if (overlap <= 0.0) {
          net.gaps.push_back(p);
          continue;
        }
        net.contacts.push_back(p);
        ++net.contacts_per_grain[static_cast<std::size_t>(p.i)];
        ++net.contacts_per_grain[static_cast<std::size_t>(p.j)];
        stiffness_sum += p.stiffness;
        dashpot_sum += p.dashpot;
      }
    }
  };
  const auto z_of = [&](std::size_t a) { return grains[static_cast<std::size_t>(order[a])].position.z; };
  for (std::size_t a = 0; a < order.size(); ++a) {
    for (std::size_t b = a + 1; b < order.size() && z_of(b) - z_of(a) <= reach; ++b) test_pair(order[a], order[b], 0.0);
  }
  if (box.periodic[2]) {
    // Across the periodic end: grains near the top against the images of those near the bottom.
    const double length = box.length(2);
    for (std::size_t a = order.size(); a-- > 0 && z_of(a) >= box.hi.z - reach;) {
      for (std::size_t b = 0; b < a && z_of(b) + length - z_of(a) <= reach; ++b) test_pair(order[a], order[b], length);
    }
  }
  if (!net.contacts.empty()) {
    net.mean_stiffness = stiffness_sum / static_cast<double>(net.contacts.size());
    net.mean_dashpot = dashpot_sum / static_cast<double>(net.contacts.size());
  }
  return net;
}

dem::Vec3 static_body_force(std::span<const dem::Grain> grains, const ContactNetwork& network, int body) {
  dem::Vec3 f;
  for (const StaticPair& p : network.contacts) {
    // The normal points from j to i; the force pushes i along it and j against it.
    if (grains[static_cast<std::size_t>(p.i)].body == body) f += p.force * p.normal;
    if (grains[static_cast<std::size_t>(p.j)].body == body) f -= p.force * p.normal;
  }
  return f;
}

}  // namespace sedwave::forward::channel
