#pragma once
// Stability limits of velocity Verlet for one linearised contact, m x'' = -k x - c x' with
// omega0^2 = k/m and beta = c/m, in the two forms the explicit schemes of this tree take, and the
// factors by which a hexagonal packing's collective modes exceed one pair's (docs/dem.md, "Numerics";
// docs/interface.md, "The self-adaptive step").
//
// Both schemes kick, drift and kick; they differ in the velocity a velocity-dependent force sees at
// t_{n+1}:
//  * the half-step velocity w = v_{n+1/2} (LAMMPS, the DEM engine): one step is a 2x2 map with
//    trace 2 - h^2 omega0^2 - h beta and determinant 1 - h beta; Jury's conditions give
//    h^2 omega0^2 + 2 h beta <= 4, h_c = 4 / (beta + sqrt(beta^2 + 4 omega0^2)) (2/beta for a dashpot);
//  * the predicted velocity w = v_{n+1/2} + (h/2) a_n (the granular-solid interface, second order with
//    friction): the map of (x, v, a) has the characteristic polynomial
//      2 L^3 + (3 h beta + 2 h^2 omega0^2 - 4) L^2 + (2 - 4 h beta) L + h beta,
//    whose root crosses the unit circle at L = -1 when h^2 omega0^2 + 4 h beta = 4:
//      h_c = 2 / (beta + sqrt(beta^2 + omega0^2))   (1/beta for a dashpot, 2/omega0 for a spring).
//    At zeta = beta/(2 omega0) = 0.5 that is 0.83/omega0 against 1.24/omega0 for the half-step form.
#include <cmath>
#include <limits>

namespace sedwave::forward::dem {

/// h_c of velocity Verlet whose forces see the half-step velocity (the DEM engine); infinite when
/// omega0 = beta = 0.
[[nodiscard]] inline double verlet_critical_step(double omega0, double beta) {
  // Rationalised root of omega0^2 h^2 + 2 beta h - 4 = 0: no cancellation, valid at omega0 = 0.
  const double denominator = beta + std::sqrt(beta * beta + 4.0 * omega0 * omega0);
  return denominator > 0.0 ? 4.0 / denominator : std::numeric_limits<double>::infinity();
}

/// h_c of velocity Verlet whose forces see the predicted velocity v_{n+1/2} + (h/2) a_n (the
/// granular-solid interface); infinite when omega0 = beta = 0.
[[nodiscard]] inline double predicted_velocity_critical_step(double omega0, double beta) {
  // Rationalised root of omega0^2 h^2 + 4 beta h - 4 = 0.
  const double denominator = beta + std::sqrt(beta * beta + omega0 * omega0);
  return denominator > 0.0 ? 2.0 / denominator : std::numeric_limits<double>::infinity();
}

/// The largest eigenvalue of a hexagonal (triangular) packing of equal disks against one pair's, for
/// equal contacts (Bloch analysis over the Brillouin zone; the test checks the rotational one):
///  * normal springs or dashpots, sum_bonds 2 (1 - cos q.e) e e^T: 6 k/m at the zone's edge (M)
///    against 2 k/m for a pair, so omega^2 and beta grow 3x;
///  * a tangential dashpot c with rotation (solid spheres, I = 2/5 m r^2): the uniform spin, each
///    grain's six contacts slipping at 2 r w, decays at 30 c/m against 7 c/m for a pair (30/7);
///    without rotation, as the springs, 6 c/m against 2 c/m.
struct HexagonalCollective {
  static constexpr double normal = 3.0;                    ///< omega^2 and the normal dashpot's beta
  static constexpr double friction_with_spin = 30.0 / 7.0;  ///< a tangential dashpot's beta, grains rotating
  static constexpr double friction_without_spin = 3.0;      ///< and with spins held
};

/// h_c of a hexagonal packing's grain contacts under the predicted-velocity scheme: the pair's
/// omega0^2, normal dashpot beta_n and tangential dashpot beta_t scaled to the collective modes and
/// taken as one oscillator (the largest frequency with the largest damping: the springs' and
/// dashpots' modes need not coincide, so this bounds the packing's limit from below).
[[nodiscard]] inline double hexagonal_packing_critical_step(double omega0_squared, double beta_normal,
                                                            double beta_tangential, bool rotation) {
  const double f_t = rotation ? HexagonalCollective::friction_with_spin : HexagonalCollective::friction_without_spin;
  return predicted_velocity_critical_step(std::sqrt(HexagonalCollective::normal * omega0_squared),
                                          HexagonalCollective::normal * beta_normal + f_t * beta_tangential);
}

}  // namespace sedwave::forward::dem
