#pragma once
// The acoustic channel's initial configuration: a column of polydisperse grains between two rough
// walls, periodic in x and y (cross-section W x W), long along z. Lengths are in units of the mean
// grain diameter; masses follow from the grain density (any consistent unit system works; the
// thesis uses d = 1, rho = 1).
//
// Following the thesis (appendix A): wall grains have twice the mean diameter and random height
// offsets, so the walls are rough and the packing cannot crystallise against them. Flow grains are
// placed by random sequential addition (no overlaps) at a loose packing fraction; compression
// (preparation.hpp) then brings them into contact.
#include <cstdint>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::channel {

/// Grain groups (Grain::group) and rigid bodies (Grain::body) of a channel.
enum ChannelGroup : std::int32_t { kFlowGroup = 0, kLowerWallGroup = 1, kUpperWallGroup = 2 };
inline constexpr std::int32_t kLowerWallBody = 1;  ///< engine body index 0
inline constexpr std::int32_t kUpperWallBody = 2;  ///< engine body index 1

/// Normal distribution of diameters, resampled (not clamped, which would pile grains up at the
/// edges) until inside [min, max]. The thesis uses mean 1, sd 0.2, and its LAMMPS masses assume
/// diameters within [0.8, 1.2].
struct SizeDistribution {
  double mean = 1.0;
  double sd = 0.2;
  double min = 0.8;
  double max = 1.2;
};

struct ChannelGeometry {
  int n_grains = 1000;             ///< flow grains (walls come on top)
  double width = 3.0;              ///< W: periodic cross-section W x W [mean diameters]
  SizeDistribution sizes;
  double density = 1.0;            ///< grain density [mass / length^3]
  double wall_diameter = 2.0;      ///< wall grains [mean diameters]
  double wall_roughness = 0.2;     ///< sd of wall-grain height offsets, clipped to +-0.5 [mean d]
  double initial_packing_fraction = 0.25;  ///< of the random loose column (RSA jams below 0.38, lower in narrow channels)
  std::uint64_t seed = 1;
  /// A cell periodic along z, without walls: the building block of long channels
  /// (periodic_cell.hpp). Its length follows from the grains' volume and the initial packing fraction.
  bool periodic = false;
};

struct ChannelConfiguration {
  dem::Box box;
  std::vector<dem::Grain> grains;  ///< flow grains (ids 1..N), then lower and upper wall grains (if any)
  double flow_bottom = 0.0;        ///< z below which no flow grain starts
  double flow_top = 0.0;           ///< z above which no flow grain starts
};

/// Builds the loose column. Reproducible: the same geometry (seed included) gives the same grains
/// wherever the C library's log/sin/cos agree (std::mt19937_64 is exact by the standard; normal
/// deviates come from our own Box-Muller transform, not the unspecified std::normal_distribution).
/// Throws std::invalid_argument for an impossible geometry.
[[nodiscard]] ChannelConfiguration generate_channel(const ChannelGeometry& geometry);

/// Mass of a sphere of diameter d and the given density.
[[nodiscard]] double sphere_mass(double density, double diameter);

}  // namespace sedwave::forward::channel
