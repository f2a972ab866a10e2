#include "sedwave/forward/experiment/engine.hpp"

namespace sedwave::forward::experiment {

std::string engine_refusal(EngineKind engine, const channel::DriveSettings& drive) {
  if (engine != EngineKind::linear) return {};
  if (drive.pulse) {
    return "signal: the linear engine solves each frequency directly; a pulse is for the time-domain engine";
  }
  if (drive.far_end != channel::FarEnd::absorbing) {
    return "far_end: the linear engine computes the steady state, in which a frozen end reflects the whole wave: use "
           "far_end = \"absorbing\"";
  }
  return {};
}

}  // namespace sedwave::forward::experiment
