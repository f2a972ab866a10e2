#pragma once
// The static contact network of a packing: which pairs touch, how hard, and what that says about
// the packing (coordination, rattlers, overlaps, gaps). Used to judge a prepared packing and to
// decide when it is in mechanical equilibrium. Units: those of the engine.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "sedwave/forward/dem/engine.hpp"

namespace sedwave::forward::channel {

/// Summary of the contact network over all ranks (collective to compute).
struct PackingStats {
  std::int64_t flow_grains = 0;
  std::int64_t contacts = 0;               ///< touching pairs with at least one flow grain
  double mean_contact_force = 0.0;         ///< static normal force (positive = repulsive)
  double max_residual_force = 0.0;         ///< largest |total force| on a flow grain
  double coordination = 0.0;               ///< mean contacts per flow grain (all of them)
  double coordination_without_rattlers = 0.0;
  double rattler_fraction = 0.0;           ///< flow grains with fewer than 4 contacts
  double mean_overlap = 0.0;               ///< over contacts, in units of the mean diameter
  double max_overlap = 0.0;                ///< in units of the mean diameter
  double packing_fraction = 0.0;           ///< flow-grain volume / (W^2 x column height)
  /// Between the walls' mean surfaces (centres -+ radius); a periodic cell without walls: its length
  double column_height = 0.0;
  /// Sum over contacts of the static normal force's z component times the contact's z extent,
  /// f n_z dz = f dz^2 / r (the zz contact virial). Over the volume it is the stress the grains carry
  /// along z: in a periodic cell of length L the force across every cross-section is virial_zz / L.
  double virial_zz = 0.0;
  /// Counts of overlaps (contacts) and gaps (listed pairs not touching) per decade of
  /// |separation| / mean diameter: bin k covers [1e-(k+1), 1e-k), k = 0..11; the last bin also
  /// holds anything smaller.
  std::vector<std::int64_t> overlap_histogram;
  std::vector<std::int64_t> gap_histogram;
};

/// Computes the statistics of the engine's current state (collective). Gaps are counted among
/// neighbour-list pairs only (within the Verlet skin). `mean_diameter` sets the unit of overlaps.
[[nodiscard]] PackingStats packing_stats(const dem::Engine& engine, double mean_diameter, double width);

/// Means over the contacts of the engine's current state, as find_contacts computes them for a
/// packing on one rank (contact_network.hpp): tangent normal stiffness, and dashpot per unit damping
/// coefficient, under the normal law of `contact`; pairs of two rigid-body grains left out.
struct ContactMeans {
  std::int64_t contacts = 0;
  double stiffness = 0.0;
  double dashpot = 0.0;
};
/// Collective; needs the engine's neighbour list from both sides of a rank boundary (newton off).
[[nodiscard]] ContactMeans contact_means(const dem::Engine& engine, const dem::ContactSpec& contact);

/// Every flow grain's contact count (local grains, in local order), for rattler removal and tests.
[[nodiscard]] std::vector<int> contact_counts(const dem::Engine& engine);

}  // namespace sedwave::forward::channel
