#pragma once
// Equivalent linearisation of one-sided contacts (describing functions). A contact whose relative
// normal motion a exceeds its static overlap delta0 opens for part of every cycle ("claps"); a gap
// narrower than a closes for part of it. Over a cycle delta(theta) = delta0 + a cos(theta), and the
// first harmonic of the force gives the equivalent stiffness
//   k_eq = (2 / (pi a)) integral_0^pi F(delta0 + a cos theta) cos theta dtheta,   F = 0 when open,
// and the dashpot (active only while closed) the factor
//   c_eq / gamma = (theta_c - sin theta_c cos theta_c) / pi,   cos theta_c = -delta0 / a (clamped).
// For Hooke, k_eq = kn (theta_c - sin theta_c cos theta_c) / pi: the contact's full stiffness when it
// never opens (theta_c = pi), less when it claps, and > 0 for a gap that closes. Hertz contacts,
// whose stiffness vanishes with the overlap, change far less. The linear engine iterates these to a
// self-consistent field (LinearChannel::respond_equivalent). Units: those of the force law.
#include <functional>

namespace sedwave::forward::linear {

struct EquivalentContact {
  double stiffness = 0.0;     ///< k_eq [force/length]
  double dashpot = 0.0;       ///< c_eq / gamma, in [0, 1]
};

/// `force`: the elastic normal force at overlap delta > 0 (the law's static force). `overlap`:
/// delta0, negative for a gap. `amplitude`: a >= 0. `tangent`: dF/d(delta) at delta0, used when the
/// motion is too small to matter (a below 1e-6 of |delta0|) for a contact.
[[nodiscard]] EquivalentContact equivalent_contact(const std::function<double(double)>& force, double overlap,
                                                   double amplitude, double tangent);

}  // namespace sedwave::forward::linear
