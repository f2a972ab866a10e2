#pragma once
// An ensemble of independently generated packings driven alike: a single disordered channel
// scatters, so alpha_hat and c_hat are the ensemble mean with the standard error of the mean
// (from the spread between packings, which includes each member's own fit error). With one member
// the member's own fit errors are kept.
//
// Also the linear engine's table point function, for the same task farm and table format as the
// time-domain engine (table/task_farm.hpp).
#include <span>
#include <string>
#include <vector>

#include "sedwave/forward/linear/linear_channel.hpp"
#include "sedwave/forward/table/table.hpp"
#include "sedwave/forward/table/task_farm.hpp"

namespace sedwave::forward::linear {

struct EnsembleResult {
  std::vector<LinearResult> members;
  double alpha_hat = 0.0, sigma_alpha_hat = 0.0;
  double c_hat = 0.0, sigma_c_hat = 0.0;
  double reflection = 0.0;  ///< largest over the members (absorbing layer's reflection coefficient)
  std::string warning;      ///< the first member warning, if any
  std::string problem;      ///< a member's problem (then nothing was measured)
  double solve_seconds = 0.0;
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

/// The mean of one number over the members and its standard error (the spread between members over
/// sqrt(n); 0 for a single member).
struct MeanAndError {
  double mean = 0.0;
  double standard_error = 0.0;
};
[[nodiscard]] MeanAndError mean_and_standard_error(std::span<const double> values);

/// Drives every member with `drive` and combines the results.
[[nodiscard]] EnsembleResult respond(const std::vector<LinearChannel>& members, const channel::DriveSettings& drive);

/// The table point: ok with the ensemble mean and standard errors; unresolved with the reason when
/// a member cannot measure the point or alpha_hat is not significantly positive (as the
/// time-domain engine's point_from_acoustic).
[[nodiscard]] table::PointResult point_from_ensemble(const EnsembleResult& result);

/// Point function for the task farm: every point drives all members (which must be on every rank)
/// with `drive`, its omega_hat and gamma_hat replaced by the grid point's. Serial per point: run
/// with ranks_per_point = 1. The references must outlive the farm.
[[nodiscard]] table::PointFunction linear_point_function(const std::vector<LinearChannel>& members,
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
[[nodiscard]] table::PointFunction member_point_function(const LinearChannel& member, const channel::DriveSettings& drive);

/// Merges member tables (member_engine_tag) of one scene and grid into the ensemble's table:
/// per point the mean over the members and its standard error (a single member keeps its own
/// errors), unresolved where any member is, or where the mean attenuation is not significant.
/// Throws std::invalid_argument naming the table at fault for a different grid or scene, a table
/// that is not a member table, members of different ensembles, or a member given twice.
[[nodiscard]] table::DispersionTable merge_member_tables(std::span<const table::DispersionTable> members,
                                                         std::span<const std::string> names);

}  // namespace sedwave::forward::linear
