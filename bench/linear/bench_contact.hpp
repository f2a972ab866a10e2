#pragma once
// The contact law the linear-engine benches drive their packings with: Hooke kn (the thesis's 726),
// or Hertz from a Young's modulus with the scenes' Poisson ratio 2/7. The restitution only damps
// the preparation; driven runs replace it by gamma_hat. Units: those of the packings.
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::bench {

/// Hertz when youngs_modulus > 0, else Hooke with stiffness kn.
inline forward::dem::ContactSpec bench_contact(double kn, double youngs_modulus) {
  forward::dem::ContactSpec contact;
  contact["kn"] = kn;
  contact["restitution"] = 0.9;
  if (youngs_modulus > 0.0) {
    contact.normal = "hertz";
    contact["effective_modulus"] =
        forward::hertz_effective_modulus(youngs_modulus, 2.0 / 7.0, youngs_modulus, 2.0 / 7.0);
  }
  return contact;
}

}  // namespace sedwave::bench
