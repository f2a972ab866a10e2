#pragma once
// The duration of an undamped Hertz collision (tests of the interface's contacts).
#include <cmath>

namespace sedwave::test {

/// 2 int_0^1 dx / sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) = 2.943: an undamped Hertz collision lasts
/// this times delta_max / v (Johnson 1985, Contact Mechanics, sec. 11.1, eq. 11.24).
inline double hertz_time_factor() { return 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9); }

}  // namespace sedwave::test
