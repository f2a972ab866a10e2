#pragma once
// The linear engine's table points, for the same task farm and table format as the time-domain
// engine (table/task_farm.hpp, time_domain_points.hpp): the driven ensemble's, one member's, and
// the packings' long-wavelength limit; and the merge of member tables into the ensemble's table.
#include <span>
#include <string>
#include <vector>

#include "sedwave/forward/linear/ensemble.hpp"
#include "sedwave/forward/linear/linear_channel.hpp"
#include "sedwave/forward/table/table.hpp"
#include "sedwave/forward/table/task_farm.hpp"

namespace sedwave::forward::experiment {

/// The table point: ok with the ensemble mean and standard errors; unresolved with the reason when
/// a member cannot measure the point or alpha_hat is not significantly positive (as the
/// time-domain engine's point_from_acoustic).
[[nodiscard]] table::PointResult point_from_ensemble(const linear::EnsembleResult& result);

/// Point function for the task farm: every point drives all members (which must be on every rank)
/// with `drive`, its omega_hat and gamma_hat replaced by the grid point's. Serial per point: run
/// with ranks_per_point = 1. The references must outlive the farm.
[[nodiscard]] table::PointFunction linear_point_function(const std::vector<linear::LinearChannel>& members,
                                                         const channel::DriveSettings& drive);

// ---- ensembles too large for one process -------------------------------------------------------
// A member of 10^6 grains holds about 11 GB in the linear engine, so a large ensemble is computed
// one member per table (`sedwave table --member K`) and the member tables are merged afterwards
// (`sedwave merge`) into exactly the table that one run over the whole ensemble would have written:
// a member table keeps the member's own fit wherever it is finite (the ensemble needs the members'
// raw values: one member's insignificant attenuation still counts towards the mean), and the merge
// applies the table's significance rule to the mean, as point_from_ensemble does.

/// The engine tag of member k's table, "sedwave-linear (member k of n)".
[[nodiscard]] std::string member_engine_tag(int k, int n);

/// Point function of member k alone: ok with the member's own fit wherever it is finite (no
/// significance test: that is the merged ensemble's), unresolved with the reason where the member
/// cannot measure the point.
[[nodiscard]] table::PointFunction member_point_function(const linear::LinearChannel& member,
                                                         const channel::DriveSettings& drive);

/// Merges member tables (member_engine_tag) of one scene and grid into the ensemble's table:
/// per point the mean over the members and its standard error (a single member keeps its own
/// errors), unresolved where any member is, or where the mean attenuation is not significant.
/// Throws std::invalid_argument naming the table at fault for a different grid or scene, a table
/// that is not a member table, members of different ensembles, or a member given twice.
[[nodiscard]] table::DispersionTable merge_member_tables(std::span<const table::DispersionTable> members,
                                                         std::span<const std::string> names);


/// Table point function: at (omega_hat, gamma_hat) every member's limit at x = omega_hat gamma_hat,
/// alpha_hat = omega_hat * alpha_over_omega; ensemble mean and standard error of the mean (one
/// member: sigma 0, the limit is a solve, not a fit). Serial per point. The references must outlive
/// the farm.
[[nodiscard]] table::PointFunction long_wavelength_point_function(const std::vector<linear::LinearChannel>& members,
                                                                  channel::DriveAxis axis);

}  // namespace sedwave::forward::experiment
