#pragma once
// Direct solver for the steady response of a long channel,
//   (K + i omega (gamma C1 + C_t + D) - omega^2 M) U = F,
// exploiting its quasi-1D structure. Unknowns are ordered by z and cut into slabs at least as thick
// as the longest contact (in z), so every contact joins a slab only to itself or a neighbour: the
// matrix is block tridiagonal, and block Gaussian elimination along z (the block Thomas algorithm)
// costs O(number of slabs x slab size^3) = O(N) for a fixed cross-section, in O(N) memory. K, C1 and
// M are cut into real blocks once; each solve combines them for its omega and gamma.
//
// The matrix is complex symmetric (not Hermitian); blocks are factorised by LU with partial pivoting,
// so the solve is stable for any damping, including gamma = 0 away from resonances, and for rattlers
// (a grain with too few contacts makes K singular, but never -omega^2 M + K at omega > 0 together
// with any damping).
//
// Units: any consistent set (those of DynamicMatrices).
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <span>
#include <vector>

#include "sedwave/forward/linear/dynamic_matrices.hpp"

namespace sedwave::forward::linear {

/// Which unknowns the block below the diagonal joins: rows[s] (local to slab s) and cols[s] (local
/// to slab s-1) are those of grains with a contact across the boundary between slabs s-1 and s.
struct SlabCoupling {
  std::vector<std::vector<Eigen::Index>> rows, cols;
};

class SlabSolver {
 public:
  /// `node_z`: z of each node (ascending, as DynamicMatrices orders them). Throws std::logic_error if
  /// the matrices couple slabs that are not neighbours (cannot happen for contacts found in z).
  SlabSolver(const DynamicMatrices& matrices, std::span<const double> node_z);

  /// Solves for every column of `rhs` (one elimination). `extra_damping` is a diagonal damping per
  /// unknown (e.g. an absorbing layer), or empty for none.
  [[nodiscard]] Eigen::MatrixXcd solve(double omega, double gamma, const Eigen::VectorXd& extra_damping,
                                       const Eigen::MatrixXcd& rhs) const;

  /// Solves (K + mass_shift M) X = B for every column of B by block Cholesky: a step of a static
  /// relaxation (static_equilibrium.hpp). Returns nullopt when K + mass_shift M is not positive
  /// definite (a packing away from a minimum has unstable directions, and rattlers make K singular),
  /// which tells the caller to shift further. Damping plays no part.
  [[nodiscard]] std::optional<Eigen::MatrixXd> solve_shifted(double mass_shift, const Eigen::MatrixXd& rhs) const;

  [[nodiscard]] std::size_t slabs() const { return k_diagonal_.size(); }
  [[nodiscard]] Eigen::Index largest_slab() const;     ///< unknowns in the largest slab
  [[nodiscard]] double slab_thickness() const { return thickness_; }

 private:
  /// Block elimination of K + damping_factor (gamma C1 + C_t + D) + mass_factor M for the columns of
  /// rhs: damping_factor = i omega, mass_factor = -omega^2 for a steady drive.
  [[nodiscard]] Eigen::MatrixXcd eliminate(std::complex<double> damping_factor, std::complex<double> mass_factor,
                                           double gamma, const Eigen::VectorXd& extra_damping,
                                           const Eigen::MatrixXcd& rhs) const;

  /// Cuts the blocks below the diagonal down to their coupled rows and columns (coupling_).
  void keep_coupled_corners();

  std::vector<Eigen::Index> offset_;  ///< first unknown of each slab, plus the total at the end
  SlabCoupling coupling_;
  /// lower[s]: rows s, cols s-1, restricted to coupling_.rows[s] x coupling_.cols[s]
  std::vector<Eigen::MatrixXd> k_diagonal_, k_lower_, c_diagonal_, c_lower_;
  std::vector<Eigen::MatrixXd> t_diagonal_, t_lower_;  ///< C_t blocks (empty when C_t is: no friction, no fluid)
  Eigen::VectorXd mass_;
  double thickness_ = 0.0;
};

/// One unknown w bordering a solved system (a loaded wall's translation):
///   [A b; b^T a] [u; w] = [f; g].
/// Given x = A^-1 [f b] (both columns from one elimination), w = (g - b^T x_f) / pivot with the
/// Schur complement pivot = a - b^T x_b, and u = x_f - w x_b. The matrices are symmetric (complex
/// symmetric for a steady drive), so the border's row is b^T, not b^H.
template <class Scalar>
struct BorderedSolution {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> u;
  Scalar w;
  Scalar pivot;
};

template <class Scalar>
[[nodiscard]] BorderedSolution<Scalar> eliminate_border(const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& x,
                                                        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b, Scalar a,
                                                        Scalar g) {
  const Scalar pivot = a - (b.transpose() * x.col(1)).value();
  const Scalar w = (g - (b.transpose() * x.col(0)).value()) / pivot;
  return {x.col(0) - w * x.col(1), w, pivot};
}

}  // namespace sedwave::forward::linear
