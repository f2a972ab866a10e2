#pragma once
// The static contact network of a prepared packing, contact by contact: geometry, static force,
// tangent stiffness and dashpot, i.e. each contact linearised about the static state. Also the
// nearly touching pairs (gaps), which a drive can close. The linear engine assembles its matrices
// from it; the packing's units (kappa of Hertz contacts) come from it too.
//
// Serial: call it on the rank that holds the grains (the linear engine solves one packing per rank;
// the task farm spreads frequencies and packings over ranks). Periodic images follow the box as in the DEM engine: a pair touches through
// every image within reach, each touching image being its own contact. Pairs of grains that are both
// in rigid bodies (wall-wall) are left out: their relative motion is prescribed.
//
// Units: those of the packing (lengths, forces and stiffnesses as stored in its grains and contact
// law).
#include <cstdint>
#include <span>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::channel {

/// One touching pair, or one nearly touching pair (then force and stiffness are 0).
struct StaticPair {
  std::int32_t i = 0;      ///< index into the packing's grains
  std::int32_t j = 0;      ///< index into the packing's grains (the image actually touched)
  dem::Vec3 normal;        ///< unit vector from j's image to i
  double distance = 0.0;   ///< between the centres
  double overlap = 0.0;    ///< r_i + r_j - distance: > 0 for contacts, < 0 (minus the gap) for gaps
  double force = 0.0;      ///< static normal force (repulsive > 0)
  double stiffness = 0.0;  ///< tangent normal stiffness dF/d(overlap) at the static overlap
  /// Normal dashpot at the static overlap per unit damping coefficient of the law (Hooke: 1 per
  /// unit gamma; Hertz-Tsuji: sqrt(m_eff k_h sqrt(delta)) per unit alpha). Gaps: at zero overlap.
  double dashpot = 0.0;
  double effective_mass = 0.0;  ///< 1 / (1/m_i + 1/m_j); a rigid-wall grain counts as infinitely heavy
  double arm_i = 0.0;           ///< lever arms to the middle of the overlap, r - overlap / 2, as the DEM
  double arm_j = 0.0;
  double energy = 0.0;          ///< elastic energy stored in the contact (0 for gaps)
};

struct ContactNetwork {
  std::vector<StaticPair> contacts;
  std::vector<StaticPair> gaps;           ///< pairs closer than the gap search distance
  std::vector<int> contacts_per_grain;    ///< per packing grain
  double mean_stiffness = 0.0;       ///< mean tangent stiffness over contacts
  double mean_dashpot = 0.0;         ///< mean dashpot per unit damping coefficient over contacts
};

/// A pair's normal contact linearised about its static overlap (> 0 for a contact) under `unit`, a
/// law whose damping coefficient is 1 (unit_damping_law): tangent stiffness, and dashpot per unit
/// coefficient. Gaps (overlap <= 0): the dashpot at zero overlap and no stiffness.
struct PairLinearisation {
  double force = 0.0;
  double stiffness = 0.0;
  double dashpot = 0.0;
  double energy = 0.0;
};
[[nodiscard]] dem::AnyContactModel unit_damping_law(const dem::ContactSpec& contact);
[[nodiscard]] PairLinearisation linearise_pair(const dem::AnyContactModel& unit, double effective_mass,
                                               double radius_i, double radius_j, double overlap);
/// A pair's effective mass 1 / (1/m_i + 1/m_j), where a grain of a rigid body (body != kFreeBody)
/// counts as infinitely heavy, as in the DEM engine.
[[nodiscard]] double pair_effective_mass(double mass_i, int body_i, double mass_j, int body_j);

/// Finds every contact, and every gap narrower than `gap_search` (same length unit), of `grains`
/// in `box` (periodic in x, y; open or periodic in z) under the normal law of `contact` (its damping
/// setting is ignored: dashpots are per unit coefficient). Throws std::invalid_argument for a box
/// narrower than twice the largest grain across, or shorter than four times it along a periodic z.
[[nodiscard]] ContactNetwork find_contacts(std::span<const dem::Grain> grains, const dem::Box& box,
                                           const dem::ContactSpec& contact, double gap_search = 0.0);

/// The static force of the other grains on rigid body `body` (Grain::body), summed over the
/// network's contacts: what holds a wall in place.
[[nodiscard]] dem::Vec3 static_body_force(std::span<const dem::Grain> grains, const ContactNetwork& network, int body);

}  // namespace sedwave::forward::channel
