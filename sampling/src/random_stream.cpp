#include "sedwave/sampling/random_stream.hpp"

#include <cmath>

namespace sedwave::sampling {

double RandomStream::uniform() {
  constexpr double kTwoToMinus53 = 0x1.0p-53;
  return static_cast<double>(engine_() >> 11) * kTwoToMinus53;
}

int RandomStream::index(int n) {
  const int i = static_cast<int>(uniform() * static_cast<double>(n));
  return i < n ? i : n - 1;
}

double RandomStream::normal() {
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return spare_normal_;
  }
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_normal_ = true;
  return u * factor;
}

}  // namespace sedwave::sampling
