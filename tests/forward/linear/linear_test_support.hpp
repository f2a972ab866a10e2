#pragma once
// Shared helpers of the linear engine's tests.
#include "sedwave/forward/dem/contact/contact_spec.hpp"

namespace sedwave::forward::linear::testing {

/// A Hooke contact of stiffness kn whose preparation damping is e_n = 0.9 (the drive sets its own).
inline dem::ContactSpec hooke(double kn) {
  dem::ContactSpec c;
  c["kn"] = kn;
  c["restitution"] = 0.9;
  return c;
}

}  // namespace sedwave::forward::linear::testing
