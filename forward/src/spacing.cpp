#include "sedwave/forward/spacing.hpp"

#include <cmath>
#include <stdexcept>

namespace sedwave::forward {

std::vector<double> log_spaced(double first, double last, std::size_t n) {
  if (n < 2 || !(first > 0.0) || !(last > first)) throw std::invalid_argument("log_spaced: need 0 < first < last, n >= 2");
  std::vector<double> values(n);
  const double step = std::log(last / first) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) values[i] = first * std::exp(step * static_cast<double>(i));
  values.back() = last;
  return values;
}

}  // namespace sedwave::forward
