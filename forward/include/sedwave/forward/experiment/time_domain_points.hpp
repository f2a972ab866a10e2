#pragma once
// The time-domain (DEM) engine's table points, for the task farm (table/task_farm.hpp): a driven run
// of the prepared packing per point, or one pulse run per band of the grid's frequencies.
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/table/table.hpp"
#include "sedwave/forward/table/task_farm.hpp"

namespace sedwave::forward::experiment {

/// What a driven run measured, as a table point (table::point_from_measurement); unresolved, with
/// the warning as its reason, when its windows were still not steady after every extension.
[[nodiscard]] table::PointResult point_from_acoustic(const channel::AcousticResult& result);

/// A pulse covers a band well up to this ratio of its highest to its lowest frequency.
inline constexpr double kPulseBandRatio = 8.0;

/// The grid's omega_hat values (ascending) cut into consecutive bands, each spanning at most
/// kPulseBandRatio.
[[nodiscard]] std::vector<std::vector<double>> pulse_bands(const std::vector<double>& omega_hats);

/// The DEM point function: every point drives the same prepared packing (its grains spread over the
/// ranks of each group in any way, e.g. all on the group's rank 0) with `drive`, its omega_hat and gamma_hat replaced
/// by the grid point's. With a pulse drive (`drive.pulse` set; its own band is ignored), the first
/// point of a (gamma_hat, band of pulse_bands(grid.omega_hat)) that a group meets runs one pulse
/// measuring every grid frequency of that band, and the group's next points of the same band are
/// read from it: the farm hands out points gamma_hat-major, so with G groups a table row costs at
/// most G pulse runs per band instead of one run per point. The references must outlive the farm.
[[nodiscard]] table::PointFunction dem_point_function(const channel::PreparedChannel& packing,
                                                      const dem::ContactSpec& contact,
                                                      const channel::DriveSettings& drive,
                                                      const table::TableGrid& grid);

}  // namespace sedwave::forward::experiment
