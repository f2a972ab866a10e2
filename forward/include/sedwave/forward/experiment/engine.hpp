#pragma once
// The engines that can drive a scene's packing, and what each asks of the drive: the one place
// where a scene file, a command-line override and a table agree on which engine may run what.
#include <string>

#include "sedwave/forward/channel/acoustic.hpp"

namespace sedwave::forward::experiment {

/// Which engine drives the packing: the time-domain DEM (any amplitude) or the linear-response
/// engine (small amplitudes, steady state, orders of magnitude faster; docs/linear.md).
enum class EngineKind { time_domain, linear };

/// Why `engine` cannot drive a packing with `drive`, as "key: reason" about the scene's [drive]
/// section, or empty when it can. The linear engine solves the steady state at one frequency at a
/// time, so it takes no pulse, and it needs the absorbing far end (a frozen end reflects the whole
/// wave: its steady state is a standing wave).
[[nodiscard]] std::string engine_refusal(EngineKind engine, const channel::DriveSettings& drive);

}  // namespace sedwave::forward::experiment
