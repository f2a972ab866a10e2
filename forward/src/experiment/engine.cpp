#include "sedwave/forward/experiment/engine.hpp"

#include <algorithm>
#include <stdexcept>

namespace sedwave::forward::experiment {

const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names{"time_domain", "linear", "long_wavelength"};
  return names;
}

EngineKind engine_named(std::string_view name) {
  const std::vector<std::string>& names = engine_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw std::invalid_argument("unknown engine '" + std::string(name) + "'");
  return static_cast<EngineKind>(it - names.begin());
}

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
