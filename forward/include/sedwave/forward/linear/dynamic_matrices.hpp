#pragma once
// The linearised equations of motion of a packing about its static state,
//   M u'' + gamma C1 u' + K u = - sum_b (K_b + gamma C1_b d/dt) U_b(t),
// for the translations u of the free grains (3 per grain) when the rigid bodies (walls) move by
// prescribed translations U_b(t).
//
// Per contact (i, j) with unit normal n (from j to i), centre distance r, static normal force f and
// tangent stiffness k (Hooke: kn; Hertz: dF/d(overlap) at the static overlap) the stiffness block is
//   k n n^T - (f / r) (I - n n^T):
// the second term is the pre-stress (a compressed contact that rotates loses part of its force
// along the original line); it is what makes a compressed packing's K differ from a spring network's.
// The dashpot block is c n n^T, c the contact's dashpot per unit damping coefficient of its law
// (StaticPair::dashpot: 1 for the thesis's constant Hooke dashpot), so C = coefficient x C1 and K,
// C1, M are assembled once for any damping and frequency.
//
// Units: those of the packing (force/length for K, mass for M; C1 is dimensionless).
#include <Eigen/Sparse>
#include <cstdint>
#include <span>
#include <vector>

#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/channel/contact_network.hpp"

namespace sedwave::forward::linear {

using channel::ContactNetwork;
using channel::StaticPair;

struct DynamicMatrices {
  std::vector<std::int32_t> grain_of_node;   ///< free grains in ascending z (node n: unknowns 3n..3n+2)
  std::vector<std::int32_t> node_of_grain;   ///< per packing grain; -1 for grains of rigid bodies
  Eigen::SparseMatrix<double> stiffness;     ///< K, 3n x 3n, symmetric
  Eigen::SparseMatrix<double> dashpots;      ///< C1, 3n x 3n, symmetric
  Eigen::VectorXd mass;                      ///< diagonal of M, 3n
  /// Per rigid body (index body - 1): coupling of its translation (3 columns) to the free unknowns.
  std::vector<Eigen::SparseMatrix<double>> body_stiffness;
  std::vector<Eigen::SparseMatrix<double>> body_dashpots;

  [[nodiscard]] Eigen::Index unknowns() const { return mass.size(); }
};

/// Equivalent linear properties per pair, replacing the tangent ones (equivalent_linearisation.hpp):
/// for every contact and then every gap, in network order, a normal stiffness [force/length] and a
/// factor on the unit dashpot.
struct PairLinearisation {
  std::vector<double> stiffness;
  std::vector<double> dashpot;
};

/// Assembles K, C1, M and the body couplings of `grains` over `network`. `n_bodies` is the number of
/// rigid bodies (Grain::body runs over 1..n_bodies for their grains). Without `pairs`, contacts get
/// their tangent stiffness and a unit dashpot, gaps nothing; with it, each pair gets its own.
[[nodiscard]] DynamicMatrices assemble(std::span<const dem::Grain> grains, const ContactNetwork& network,
                                       int n_bodies, const PairLinearisation* pairs = nullptr);

}  // namespace sedwave::forward::linear
