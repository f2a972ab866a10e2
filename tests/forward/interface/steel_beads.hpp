#pragma once
// The interface tests' granules: steel beads of 5 mm on aluminium (docs/interface.md, "Choices").
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"

namespace sedwave::forward::interface::test {

inline const GrainMaterial steel{200e9, 0.3};
inline constexpr double steel_density = 7850.0;
inline constexpr double bead_radius = 2.5e-3;
inline const plate::PlateMaterial aluminium{70e9, 0.33, 2700.0, 5e-3};

/// A packing of rows x columns steel beads; the caller sets gap, offset, lift and orientation.
inline HexPacking steel_beads(int rows, int columns) {
  HexPacking p;
  p.rows = rows;
  p.columns = columns;
  p.radius = bead_radius;
  p.density = steel_density;
  return p;
}

/// A free 6 x 2-element plate (every edge free: it may move as a whole), 30 x 10 mm of aluminium.
inline plate::ElasticPlate free_plate() {
  const plate::PlateEdges free{plate::EdgeCondition::free, plate::EdgeCondition::free, plate::EdgeCondition::free,
                               plate::EdgeCondition::free};
  return plate::ElasticPlate(aluminium, {6, 2, 30e-3, 10e-3}, free);
}

/// A rectangular pulse of duration tau [s] on free_plate()'s inner top-edge nodes, into the plate,
/// unequal (-100 i N on node i) so that the plate also deforms; its total force goes to `total` [N].
inline PlatePulse top_edge_pulse(const plate::ElasticPlate& plate, double tau, double& total) {
  PlatePulse pulse;
  pulse.forces.assign(static_cast<std::size_t>(plate.dof_count()), 0.0);
  total = 0.0;
  for (int i = 1; i <= 4; ++i) {
    const double f = -100.0 * i;
    pulse.forces[static_cast<std::size_t>(2 * plate.node(i, 2) + 1)] = f;
    total += f;
  }
  pulse.duration = tau;
  return pulse;
}

/// A straight chain of n touching beads along y (the first at the bottom), at rest, `lift` above
/// the plate.
inline std::vector<Grain> chain(int n, double lift = 1.0) {
  HexPacking p = steel_beads(1, n);
  p.lift = lift;
  p.orientation = HexOrientation::rows_perpendicular;
  return make_hex_packing(p);
}

/// 3 x 4 beads a micrometre apart and a micrometre above the plate, from x = 2 mm: the top row struck
/// down at 1 m/s and the last bead sheared at 0.3 m/s, so that friction and rotation act.
inline std::vector<Grain> struck_packing() {
  HexPacking p = steel_beads(3, 4);
  p.gap = 1e-6;
  p.x_offset = 2e-3;
  p.lift = 1e-6;
  auto grains = make_hex_packing(p);
  for (auto& g : grains)
    if (g.y > 10e-3) g.vy = -1.0;
  grains.back().vx = 0.3;
  return grains;
}

/// `contacts`' default grain contact (Hertz of steel, friction's mu) with the DEM's history spring
/// (kt = 2e6 N/m) for Coulomb-tanh and constant-torque rolling resistance (mu_r = 0.05,
/// omega_reg = 10 1/s).
inline dem::ContactSpec history_and_rolling(const InterfaceContacts& contacts) {
  dem::ContactSpec spec = grain_contact_spec(contacts, steel);
  spec.tangential = "spring_history";
  spec.erase("tanh_velocity_scale");
  spec["kt"] = 2e6;
  spec.rolling = "constant_torque";
  spec["rolling_friction"] = 0.05;
  spec["rolling_regularisation"] = 10.0;
  return spec;
}

}  // namespace sedwave::forward::interface::test
