#pragma once
// History-free regularised Coulomb friction ("Coulomb-tanh", 2021 paper, eq. 19b):
//   F_t = -mu |F_n| tanh(k_s |v_t|) v_t / |v_t|.
// Smooth in v_t, so sliding and sticking need no state and no event detection; k_s [time/length]
// sets how sharply the force saturates (|v_t| >> 1/k_s: full Coulomb sliding). It acts like a
// viscous dashpot of coefficient mu |F_n| k_s at small slip, which bounds the stable time step.
#include <array>
#include <cmath>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"
#include "sedwave/forward/dem/contact/tanh_over_x.hpp"

namespace sedwave::forward::dem {

struct CoulombTanhFriction {
  static constexpr std::string_view name = "coulomb_tanh";
  static constexpr ContactKey velocity_scale_key{"tanh_velocity_scale", "tanh-velocity-scale",
                                                 "coulomb_tanh k_s [time/length]: F_t saturates above |v_t| ~ 1/k_s",
                                                 io::Range::positive()};
  static constexpr std::array keys{&keys::friction, &velocity_scale_key};
  static constexpr bool enabled = true;
  static constexpr bool needs_history = false;
  /// A velocity-dependent force whose small-slip dashpot grows with the normal force: not a linear
  /// block the linear engine could hold.
  static constexpr bool linearised = false;

  double friction;        ///< mu
  double velocity_scale;  ///< k_s [time/length]: tanh(k_s |v_t|)

  static CoulombTanhFriction from(const ContactValues& v, double /*normal_stiffness*/) {
    return {v.get(keys::friction, 0.0), v.required(velocity_scale_key, name)};
  }

  struct Pair {};  ///< nothing per pair
  [[nodiscard]] Pair pair(double /*effective_mass*/, double /*r_i*/, double /*r_j*/) const { return {}; }
  [[nodiscard]] Vec3 force(const ContactPoint& /*c*/, const Pair& /*p*/, const Vec3& tangential_velocity,
                           double normal_force, double /*dt*/, Vec3& /*unused*/) const {
    return -drag(norm(tangential_velocity), normal_force, [](double x) { return tanh_over_x(x); }) *
           tangential_velocity;
  }
  /// The force's size over the slip speed, mu |F_n| tanh(k_s |v|)/|v|: the force is -drag v. tanh(x)/x
  /// is `tanh_over_x_form`'s (tanh_over_x, or tanh_over_x_in_lanes in SIMD lanes).
  template <class TanhOverX>
  [[nodiscard]] double drag(double slip_speed, double normal_force, TanhOverX tanh_over_x_form) const {
    // tanh(k_s |v|)/|v| = k_s tanh(x)/x, continued to k_s at zero slip (no division by zero).
    const double tanh_over_speed = velocity_scale * tanh_over_x_form(velocity_scale * slip_speed);
    return friction * std::abs(normal_force) * tanh_over_speed;
  }
  [[nodiscard]] ContactOscillator oscillator(double /*effective_mass*/, double /*radius*/, double /*overlap*/,
                                             double normal_force) const {
    return {0.0, friction * std::abs(normal_force) * velocity_scale};
  }
  /// No spring: nothing stored.
  [[nodiscard]] double energy(double /*overlap*/, double /*r_i*/, double /*r_j*/, const Vec3& /*shear*/) const {
    return 0.0;
  }
};

}  // namespace sedwave::forward::dem
