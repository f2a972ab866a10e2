#pragma once
// Constant-torque rolling resistance (rolling friction "model A" of the DEM literature; the report's
// mu_r): a torque of fixed magnitude mu_r R_eff |F_n| opposes the relative rolling angular velocity
//   omega_r = (omega_i - omega_j) - ((omega_i - omega_j).n) n.
// A strictly constant torque chatters when omega_r passes through zero; it is regularised below
// omega_reg as tanh(|omega_r|/omega_reg), which changes nothing while the grains roll.
// (Ai, Chen, Rotter & Ooi 2011, Powder Technology 206, 269: model type A.)
#include <array>
#include <cmath>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"

namespace sedwave::forward::dem {

struct ConstantTorqueRolling {
  static constexpr std::string_view name = "constant_torque";
  static constexpr std::string_view label = "rolling";  ///< its part of describe(), if not its name
  static constexpr ContactKey friction_key{"rolling_friction", "rolling-friction",
                                           "constant_torque mu_r: torque mu_r R_eff |F_n| (default 0)",
                                           io::Range::non_negative()};
  static constexpr ContactKey regularisation_key{"rolling_regularisation", "rolling-regularisation",
                                                 "constant_torque omega_reg [1/time] (default 1e-3)",
                                                 io::Range::positive()};
  static constexpr std::array keys{&friction_key, &regularisation_key};
  static constexpr bool enabled = true;
  /// A torque of fixed magnitude has no linear part the linear engine could hold.
  static constexpr bool linearised = false;

  double rolling_friction;        ///< mu_r (dimensionless, times R_eff gives a lever arm)
  double regularising_spin_rate;  ///< omega_reg [1/time]

  static ConstantTorqueRolling from(const ContactValues& v) {
    return {v.get(friction_key, 0.0), v.get(regularisation_key, 1e-3)};
  }

  /// The pair's lever arm, mu_r R_eff (1/R_eff = 1/r_i + 1/r_j).
  struct Pair {
    double lever;
  };
  [[nodiscard]] Pair pair(double /*effective_mass*/, double r_i, double r_j) const {
    return {rolling_friction * r_i * r_j / (r_i + r_j)};
  }
  /// Rolling torque on i (the torque on j is its opposite).
  [[nodiscard]] Vec3 torque(const ContactPoint& c, const Pair& p, const Vec3& relative_spin,
                            double normal_force) const {
    const Vec3 roll = relative_spin - dot(relative_spin, c.normal) * c.normal;
    const double rate = norm(roll);
    if (rate == 0.0) return {};
    const double magnitude = p.lever * std::abs(normal_force) * std::tanh(rate / regularising_spin_rate);
    return -(magnitude / rate) * roll;
  }
};

}  // namespace sedwave::forward::dem
