#include "sedwave/forward/dem/time_step.hpp"

#include <sstream>

namespace sedwave::forward::dem {

double verlet_critical_step(double omega0, double beta) {
  // Rationalised root of omega0^2 h^2 + 2 beta h - 4 = 0: no cancellation, valid at omega0 = 0.
  return 4.0 / (beta + std::sqrt(beta * beta + 4.0 * omega0 * omega0));
}

std::string TimeStepLimits::summary() const {
  std::ostringstream s;
  s << "collision time " << collision_time << ", stable step " << stable_step << ", default step "
    << default_step;
  return s.str();
}

}  // namespace sedwave::forward::dem
