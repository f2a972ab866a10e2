#pragma once
// The log-density of a point outside the support, shared by the samplers' sources (one definition,
// so a unity build that joins them sees it once).

#include <limits>

namespace sedwave::sampling {

inline constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

}  // namespace sedwave::sampling
