#pragma once
// The engines that can drive a scene's packing, and what each asks of the drive: the one place
// where a scene file, a command-line override and a table agree on which engine may run what.
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"

namespace sedwave::forward::experiment {

/// Which engine computes: the time-domain DEM (any amplitude), the linear-response engine (small
/// amplitudes, steady state, orders of magnitude faster; docs/linear.md), or the linear engine's
/// packings in their long-wavelength limit (linear/long_wavelength.hpp), which solves a
/// quasi-static problem and so reads neither the drive's signal nor its far end. A scene names one
/// of the first two (they drive the packing); tables may also use the third.
enum class EngineKind { time_domain, linear, long_wavelength };

/// The engines' names, in the order of EngineKind: "time_domain", "linear", "long_wavelength".
[[nodiscard]] const std::vector<std::string>& engine_names();

/// The engine called `name` (one of engine_names()); throws std::invalid_argument otherwise.
[[nodiscard]] EngineKind engine_named(std::string_view name);

/// Why `engine` cannot drive a packing with `drive`, as "key: reason" about the scene's [drive]
/// section, or empty when it can. The linear engine solves the steady state at one frequency at a
/// time, so it takes no pulse, and it needs the absorbing far end (a frozen end reflects the whole
/// wave: its steady state is a standing wave).
[[nodiscard]] std::string engine_refusal(EngineKind engine, const channel::DriveSettings& drive);

}  // namespace sedwave::forward::experiment
