#pragma once
// The linear engine's Newton relaxation (static_equilibrium.hpp) as the last stage of the channel's
// preparation (channel/preparation.hpp): the channel knows nothing of the linear engine, so whoever
// prepares a frictionless packing hands this in.
#include "sedwave/forward/channel/preparation.hpp"

namespace sedwave::forward::linear {

/// relax_to_equilibrium with every rigid body held, to the given residual and step budget.
[[nodiscard]] channel::NewtonRelaxation newton_stage();

}  // namespace sedwave::forward::linear
