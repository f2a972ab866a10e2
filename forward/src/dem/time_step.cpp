#include "sedwave/forward/dem/time_step.hpp"

#include <sstream>

namespace sedwave::forward::dem {

std::string TimeStepLimits::summary() const {
  std::ostringstream s;
  s << "collision time " << collision_time << ", stable step " << stable_step << ", default step "
    << default_step;
  return s.str();
}

}  // namespace sedwave::forward::dem
