#include "sedwave/forward/channel/contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::channel {
namespace {

constexpr int kDecades = 12;

int decade_bin(double magnitude) {
  if (!(magnitude > 0.0)) return kDecades - 1;
  return std::clamp(static_cast<int>(std::floor(-std::log10(magnitude))), 0, kDecades - 1);
}

/// Visits every neighbour-list pair (i local, j local or ghost) with its signed overlap.
/// `weight` is 1 for a local pair (listed once) and 1/2 across a boundary (listed from both sides).
template <class F>
void for_each_pair(const dem::Engine& engine, F&& f) {
  const dem::GrainArrays& g = engine.grains();
  const dem::NeighborList& list = engine.neighbor_list();
  const auto partners = list.partners();
  for (std::size_t i = 0; i < list.n_rows(); ++i) {
    for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k) {
      const auto j = static_cast<std::size_t>(partners[k]);
      const dem::Vec3 d = g.position[i] - (g.position[j] + list.shift(k));
      const double distance = dem::norm(d);
      const bool ghost = k >= list.ghost_begin(i);
      f(i, j, ghost, d, distance, g.radius[i] + g.radius[j] - distance);
    }
  }
}

}  // namespace

std::vector<int> contact_counts(const dem::Engine& engine) {
  const dem::GrainArrays& g = engine.grains();
  std::vector<int> counts(engine.n_local(), 0);
  for_each_pair(engine, [&](std::size_t i, std::size_t j, bool ghost, const dem::Vec3&, double, double overlap) {
    if (overlap <= 0.0) return;
    ++counts[i];
    if (!ghost) ++counts[j];
  });
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (g.group[i] != kFlowGroup) counts[i] = 0;
  }
  return counts;
}

ContactMeans contact_means(const dem::Engine& engine, const dem::ContactSpec& contact) {
  if (engine.settings().newton) throw std::logic_error("contact means: the pairs across ranks are listed once with newton on");
  const dem::GrainArrays& g = engine.grains();
  const dem::AnyContactModel unit = unit_damping_law(contact);
  std::array<double, 3> sum{};  // contacts, stiffness, dashpot; a pair across ranks counts half on each
  for_each_pair(engine, [&](std::size_t i, std::size_t j, bool ghost, const dem::Vec3&, double, double overlap) {
    if (overlap <= 0.0 || (g.body[i] != dem::kFreeBody && g.body[j] != dem::kFreeBody)) return;
    const double weight = ghost ? 0.5 : 1.0;
    const double m_eff = pair_effective_mass(g.mass[i], g.body[i], g.mass[j], g.body[j]);
    const PairLinearisation l = linearise_pair(unit, m_eff, g.radius[i], g.radius[j], overlap);
    sum[0] += weight;
    sum[1] += weight * l.stiffness;
    sum[2] += weight * l.dashpot;
  });
  parallel::sum(engine.domain().comm(), std::span(sum));
  ContactMeans means;
  means.contacts = std::llround(sum[0]);
  if (sum[0] > 0.0) {
    means.stiffness = sum[1] / sum[0];
    means.dashpot = sum[2] / sum[0];
  }
  return means;
}

PackingStats packing_stats(const dem::Engine& engine, double mean_diameter, double width) {
  const dem::GrainArrays& g = engine.grains();
  const MPI_Comm comm = engine.domain().comm();
  // Sums: contacts (weighted), force sum, overlap sum, flow grains, contact ends on flow grains,
  // rattlers, contact ends on non-rattlers, non-rattlers, flow volume, wall z sums and counts.
  enum { kContacts, kForce, kVirial, kOverlap, kFlow, kEnds, kRattlers, kEndsKept, kKept, kVolume, kLowZ, kLowR, kLowN,
         kHighZ, kHighR, kHighN, kSums };
  std::array<double, kSums> sum{};
  std::array<double, 2> maxima{};  // residual force, overlap
  std::vector<std::int64_t> overlaps(kDecades, 0), gaps(kDecades, 0);

  for_each_pair(engine, [&](std::size_t i, std::size_t j, bool ghost, const dem::Vec3& d, double distance,
                            double overlap) {
    if (g.group[i] != kFlowGroup && g.group[j] != kFlowGroup) return;
    const double weight = ghost ? 0.5 : 1.0;
    if (overlap > 0.0) {
      sum[kContacts] += weight;
      const double force = dem::static_normal_force(engine.contact_model(), overlap, g.radius[i], g.radius[j]);
      sum[kForce] += weight * force;
      sum[kVirial] += weight * force * d.z * d.z / distance;
      sum[kOverlap] += weight * overlap / mean_diameter;
      maxima[1] = std::max(maxima[1], overlap / mean_diameter);
      // Histograms count each contact once: cross-boundary pairs only from the lower global id.
      if (!ghost || g.id[i] < g.id[j]) ++overlaps[static_cast<size_t>(decade_bin(overlap / mean_diameter))];
    } else if (!ghost || g.id[i] < g.id[j]) {
      ++gaps[static_cast<size_t>(decade_bin(-overlap / mean_diameter))];
    }
  });

  const std::vector<int> counts = contact_counts(engine);
  for (std::size_t i = 0; i < engine.n_local(); ++i) {
    switch (g.group[i]) {
      case kFlowGroup: {
        sum[kFlow] += 1.0;
        sum[kEnds] += counts[i];
        sum[kVolume] += std::numbers::pi / 6.0 * std::pow(2.0 * g.radius[i], 3);
        maxima[0] = std::max(maxima[0], dem::norm(g.force[i]));
        // Frictionless spheres need at least d + 1 = 4 contacts to be held in place.
        if (counts[i] < 4) {
          sum[kRattlers] += 1.0;
        } else {
          sum[kEndsKept] += counts[i];
          sum[kKept] += 1.0;
        }
        break;
      }
      case kLowerWallGroup:
        sum[kLowZ] += g.position[i].z;
        sum[kLowR] += g.radius[i];
        sum[kLowN] += 1.0;
        break;
      default:
        sum[kHighZ] += g.position[i].z;
        sum[kHighR] += g.radius[i];
        sum[kHighN] += 1.0;
    }
  }
  parallel::sum(comm, std::span(sum));
  parallel::max(comm, std::span(maxima));
  parallel::sum(comm, std::span(overlaps));
  parallel::sum(comm, std::span(gaps));

  PackingStats s;
  s.flow_grains = static_cast<std::int64_t>(sum[kFlow]);
  s.contacts = std::llround(sum[kContacts]);
  s.mean_contact_force = sum[kContacts] > 0 ? sum[kForce] / sum[kContacts] : 0.0;
  s.mean_overlap = sum[kContacts] > 0 ? sum[kOverlap] / sum[kContacts] : 0.0;
  s.max_overlap = maxima[1];
  s.max_residual_force = maxima[0];
  s.coordination = sum[kFlow] > 0 ? sum[kEnds] / sum[kFlow] : 0.0;
  s.coordination_without_rattlers = sum[kKept] > 0 ? sum[kEndsKept] / sum[kKept] : 0.0;
  s.rattler_fraction = sum[kFlow] > 0 ? sum[kRattlers] / sum[kFlow] : 0.0;
  if (sum[kLowN] > 0 && sum[kHighN] > 0) {
    // Between the walls' mean surfaces: mean centre heights, less one mean wall-grain radius each.
    s.column_height = (sum[kHighZ] - sum[kHighR]) / sum[kHighN] - (sum[kLowZ] + sum[kLowR]) / sum[kLowN];
  } else if (engine.settings().box.periodic[2]) {
    s.column_height = engine.settings().box.length(2);
  }
  if (s.column_height > 0.0) s.packing_fraction = sum[kVolume] / (width * width * s.column_height);
  s.virial_zz = sum[kVirial];
  s.overlap_histogram = overlaps;
  s.gap_histogram = gaps;
  return s;
}

}  // namespace sedwave::forward::channel
