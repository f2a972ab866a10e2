#pragma once
// Long channels from a periodic cell: prepare a short column that is periodic along z (no walls; its
// length holds the pressure), then stack copies of it and freeze the grains at the two ends into
// the walls.
//
// Why: preparing a channel costs far more than solving it. Compression and FIRE grow with the
// column's length (docs/linear.md, "Preparing long channels"): about 6 minutes for 10^4 grains and
// an hour for 10^5 on one core, where the linear engine solves 10^5 grains in about 2 s. A
// periodic cell in static equilibrium tiles into a channel that is in static equilibrium too, with
// no further relaxation: every grain away from the ends has exactly the contacts, overlaps and
// forces it had in the cell, where its partners across the cell's end were images of the grains
// that the next copy now holds. Cutting the ends into walls loses no contact of a flow grain as
// long as the walls are at least one largest grain diameter thick.
//
// What tiling does to the physics: the disorder repeats with the cell's length L, so the channel
// is a periodic medium. Measured (docs/linear.md, "Channels of 10^5 to 10^6 grains"): 2000-grain
// cells (L ~ 180 d) stacked five times agree with directly prepared 10^4-grain channels within the
// ensembles' errors at omega_hat = 0.015 ... 1; 10^6-grain stacks follow the long-wavelength limit
// of the same cells to ~1 % at omega_hat <= 3e-3; between, single members show resonances of the
// repeated cell (up to 2x in alpha_hat at gamma_hat <= 1) that a random channel would average out.
//
// Units: those of the packing (lengths in mean grain diameters).
#include <mpi.h>

#include "sedwave/forward/channel/preparation.hpp"

namespace sedwave::forward::channel {

/// How a channel is built from a periodic cell (scene: [geometry.periodic_cell]).
struct CellTiling {
  int cell_grains = 10000;      ///< grains in the periodic cell; the channel holds copies of it
  double wall_thickness = 1.5;  ///< grains whose centres lie this close to an end become its wall [mean d]
};

/// Stacks `copies` images of a prepared z-periodic cell (grains on rank 0) along z into a channel
/// open along z, whose grains within `wall_thickness` of the lower and upper ends become the lower
/// and upper wall (groups, bodies and id order as generate_channel's: flow grains first). The
/// channel's grains come back spread over the ranks: every rank receives the cell and builds only
/// its share of the copies (contiguous along z, with the ids one rank stacking them all would give),
/// so no rank holds the whole channel; parallel::gather_on_root collects them where one rank must. The report
/// keeps the cell's preparation counts and its `converged`, and measures the channel itself: its
/// contact statistics, residual forces and the force on the upper wall, from a DEM force evaluation
/// (collective). The residual grows with the channel's length by round-off alone: heights near
/// 10^5 d carry an absolute error of about 1e-11 d, which at a typical overlap of 1e-2 d is 1e-9 of
/// a contact force.
/// Throws std::invalid_argument for a cell that is not z-periodic, fewer than one copy, or walls
/// thinner than the largest grain (a flow grain would lose a partner).
[[nodiscard]] PreparedChannel tile_periodic_cell(MPI_Comm comm, const PreparedChannel& cell, const dem::ContactSpec& contact,
                                                 int copies, double wall_thickness);

}  // namespace sedwave::forward::channel
