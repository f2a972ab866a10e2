#pragma once
// The viscous dashpot of a linear (Hooke) contact, F_d = -gamma v_n, in the three conventions found
// in practice. All resolve to gamma(kn, m_eff) for one pair:
//   constant            gamma = c                           [force time/length]  (the thesis's gamma)
//   per_effective_mass  gamma = c m_eff, c = LAMMPS gamma_n [1/time]   (pair gran/hooke convention)
//   restitution         gamma = 2 zeta(e_n) sqrt(kn m_eff)  exact restitution e_n for every pair
// The restitution form uses units.hpp's e_n <-> zeta mapping (exact for a Hooke collision).
#include <cmath>

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::dem {

class LinearDashpot {
 public:
  enum class Scaling { constant, per_effective_mass, restitution };

  static LinearDashpot constant(double gamma) { return {Scaling::constant, gamma}; }
  static LinearDashpot lammps_gamma_n(double gamma_n) { return {Scaling::per_effective_mass, gamma_n}; }
  static LinearDashpot from_restitution(double e_n) {
    return {Scaling::restitution, 2.0 * damping_ratio_from_restitution(e_n)};
  }

  /// Dashpot coefficient gamma [force time/length] of a pair with stiffness kn and effective mass.
  [[nodiscard]] double gamma(double kn, double effective_mass) const {
    switch (scaling_) {
      case Scaling::constant: return coefficient_;
      case Scaling::per_effective_mass: return coefficient_ * effective_mass;
      case Scaling::restitution: return coefficient_ * std::sqrt(kn * effective_mass);
    }
    return coefficient_;
  }
  [[nodiscard]] Scaling scaling() const { return scaling_; }
  [[nodiscard]] double coefficient() const { return coefficient_; }

 private:
  LinearDashpot(Scaling s, double c) : scaling_(s), coefficient_(c) {}
  Scaling scaling_;
  double coefficient_;
};

}  // namespace sedwave::forward::dem
