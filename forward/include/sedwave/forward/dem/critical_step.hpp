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
///  * a tangential spring or dashpot with rotation (solid spheres, I = 2/5 m r^2): the uniform spin,
///    each grain's six contacts slipping at 2 r w, at 30 c/m against 7 c/m for a pair (30/7);
///    without rotation, as the normal springs, 6 c/m against 2 c/m;
///  * a rolling dashpot c_r on the relative spin: at most its rows' sum, 6 contacts x 2 c_r/I,
///    against 2 c_r/I for a pair (a bound, Gershgorin's).
struct HexagonalCollective {
  static constexpr double normal = 3.0;                    ///< omega^2 and the normal dashpot's beta
  static constexpr double friction_with_spin = 30.0 / 7.0;  ///< tangential springs' and dashpots', grains rotating
  static constexpr double friction_without_spin = 3.0;      ///< and with spins held
  static constexpr double rolling = 6.0;                   ///< a rolling dashpot's beta
};

/// One pair's rates, each the largest over the pairs: the normal spring's omega^2 = k/m and dashpot's
/// beta = c/m, a tangential spring's and dashpot's on the slip's inertia 1/m_t = 1/m_i + 1/m_j +
/// a_i^2/I_i + a_j^2/I_j, and a rolling dashpot's on the relative spin's, 1/I_i + 1/I_j.
struct PairRates {
  double normal_omega_squared = 0.0;
  double normal_beta = 0.0;
  double tangential_omega_squared = 0.0;
  double tangential_beta = 0.0;
  double rolling_beta = 0.0;
};

/// The packing's largest omega^2 and beta: each operator's pair rate scaled by HexagonalCollective,
/// the springs' and the dashpots' summed (the largest eigenvalue of a sum is at most the sum of theirs).
struct OscillatorRates {
  double omega_squared = 0.0;
  double beta = 0.0;
};
[[nodiscard]] inline OscillatorRates hexagonal_collective(const PairRates& pair, bool rotation) {
  const double f_t = rotation ? HexagonalCollective::friction_with_spin : HexagonalCollective::friction_without_spin;
  return {HexagonalCollective::normal * pair.normal_omega_squared + f_t * pair.tangential_omega_squared,
          HexagonalCollective::normal * pair.normal_beta + f_t * pair.tangential_beta +
              HexagonalCollective::rolling * pair.rolling_beta};
}

/// h_c of a hexagonal packing's grain contacts under the predicted-velocity scheme: one oscillator of
/// the packing's largest omega^2 with its largest beta (the springs' and dashpots' modes need not
/// coincide, so this bounds the packing's limit from below).
[[nodiscard]] inline double hexagonal_packing_critical_step(const PairRates& pair, bool rotation) {
  const OscillatorRates packing = hexagonal_collective(pair, rotation);
  return predicted_velocity_critical_step(std::sqrt(packing.omega_squared), packing.beta);
}
/// The same for a normal spring and dashpot and a tangential dashpot (Coulomb-tanh at small slip).
[[nodiscard]] inline double hexagonal_packing_critical_step(double omega0_squared, double beta_normal,
                                                            double beta_tangential, bool rotation) {
  PairRates pair;
  pair.normal_omega_squared = omega0_squared;
  pair.normal_beta = beta_normal;
  pair.tangential_beta = beta_tangential;
  return hexagonal_packing_critical_step(pair, rotation);
}

}  // namespace sedwave::forward::dem
