#pragma once
// The contact the periodic-cell tests build their packings with: linear (Hooke) normal springs of
// kn = 726 with restitution 0.9, in the channel's units.
#include "sedwave/forward/dem/contact/contact_spec.hpp"

namespace sedwave::forward::channel::testing {

inline dem::ContactSpec hooke_contact() {
  dem::ContactSpec c;
  c.normal = "hooke";
  c["kn"] = 726.0;
  c["restitution"] = 0.9;
  return c;
}

}  // namespace sedwave::forward::channel::testing
