#pragma once
// Frequency axes: a table's grid and a pulse's measured frequencies are spaced evenly in log.
#include <cstddef>
#include <vector>

namespace sedwave::forward {

/// n values from first to last, equally spaced in log (n >= 2), last exactly `last`.
[[nodiscard]] std::vector<double> log_spaced(double first, double last, std::size_t n);

}  // namespace sedwave::forward
