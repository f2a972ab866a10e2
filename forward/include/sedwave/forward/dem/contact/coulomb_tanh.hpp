#pragma once
// History-free regularised Coulomb friction ("Coulomb-tanh", 2021 paper, eq. 19b):
//   F_t = -mu |F_n| tanh(k_s |v_t|) v_t / |v_t|.
// Smooth in v_t, so sliding and sticking need no state and no event detection; k_s [time/length]
// sets how sharply the force saturates (|v_t| >> 1/k_s: full Coulomb sliding). It acts like a
// viscous dashpot of coefficient mu |F_n| k_s at small slip, which bounds the stable time step.
#include <cmath>

#include "sedwave/forward/dem/contact/contact_point.hpp"

namespace sedwave::forward::dem {

struct CoulombTanhFriction {
  static constexpr bool enabled = true;
  static constexpr bool needs_history = false;

  double friction;        ///< mu
  double velocity_scale;  ///< k_s [time/length]: tanh(k_s |v_t|)

  struct Pair {};  ///< nothing per pair
  [[nodiscard]] Pair pair(double /*effective_mass*/, double /*r_i*/, double /*r_j*/) const { return {}; }
  [[nodiscard]] Vec3 force(const ContactPoint& /*c*/, const Pair& /*p*/, const Vec3& tangential_velocity,
                           double normal_force, double /*dt*/, Vec3& /*unused*/) const {
    const double speed = norm(tangential_velocity);
    const double x = velocity_scale * speed;
    // tanh(x)/speed, continued to k_s at zero slip (no division by zero, no branch in the result).
    const double tanh_over_speed = x > 1e-8 ? std::tanh(x) / speed : velocity_scale;
    return -(friction * std::abs(normal_force) * tanh_over_speed) * tangential_velocity;
  }
  [[nodiscard]] ContactOscillator oscillator(double /*effective_mass*/, double normal_force) const {
    return {0.0, friction * std::abs(normal_force) * velocity_scale};
  }
};

}  // namespace sedwave::forward::dem
