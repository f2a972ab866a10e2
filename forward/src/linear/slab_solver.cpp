#include "sedwave/forward/linear/slab_solver.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace sedwave::forward::linear {
namespace {

/// Largest z distance between two nodes coupled by the matrix.
double longest_coupling(const Eigen::SparseMatrix<double>& a, std::span<const double> node_z, int dofs) {
  double longest = 0.0;
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it) {
      longest = std::max(longest, std::abs(node_z[static_cast<std::size_t>(it.row() / dofs)] -
                                           node_z[static_cast<std::size_t>(col / dofs)]));
    }
  }
  return longest;
}

/// Block Gaussian elimination of a symmetric block-tridiagonal matrix (the block Thomas algorithm):
/// Schur complements S_s = Z_s - L_s S_{s-1}^{-1} L_s^T, kept as X_s = S_{s-1}^{-1} L_s^T and
/// W_s = S_s^{-1} (B_s - L_s W_{s-1}); then U_s = W_s - X_{s+1} U_{s+1}. Slab s holds unknowns
/// offset[s] .. offset[s+1]; diagonal(s) is Z_s, lower(s) the block of rows s, columns s-1.
/// Factorisation is Eigen::LLT (real symmetric positive definite; returns nullopt at the first
/// block that is not, so the matrix is not) or Eigen::PartialPivLU (any regular matrix).
template <class Factorisation, class Matrix, class Diagonal, class Lower>
std::optional<Matrix> block_thomas(std::span<const Eigen::Index> offset, Diagonal diagonal, Lower lower,
                                   const Matrix& rhs) {
  const std::size_t slabs = offset.size() - 1;
  auto rows = [&](std::size_t s) { return offset[s + 1] - offset[s]; };
  std::vector<Matrix> x(slabs), w(slabs);
  Matrix next_lower;
  for (std::size_t s = 0; s < slabs; ++s) {
    Matrix schur = diagonal(s);
    Matrix y = rhs.middleRows(offset[s], rows(s));
    if (s > 0) {
      schur.noalias() -= next_lower * x[s];
      y.noalias() -= next_lower * w[s - 1];
    }
    const Factorisation factor(schur);
    if constexpr (std::is_same_v<Factorisation, Eigen::LLT<Matrix>>) {
      if (factor.info() != Eigen::Success) return std::nullopt;
    }
    w[s] = factor.solve(y);
    if (s + 1 < slabs) {
      next_lower = lower(s + 1);
      x[s + 1] = factor.solve(next_lower.transpose());
    }
  }
  Matrix u(rhs.rows(), rhs.cols());
  for (std::size_t s = slabs; s-- > 0;) {
    Matrix us = w[s];
    if (s + 1 < slabs) us.noalias() -= x[s + 1] * u.middleRows(offset[s + 1], rows(s + 1));
    u.middleRows(offset[s], rows(s)) = us;
  }
  return u;
}

}  // namespace

SlabSolver::SlabSolver(const DynamicMatrices& m, std::span<const double> node_z) : mass_(m.mass) {
  const auto nodes = static_cast<Eigen::Index>(node_z.size());
  const int dofs = m.dofs_per_node;
  if (dofs * nodes != m.unknowns()) throw std::invalid_argument("slab solver: one z per node is needed");
  // Slabs of thickness h >= the longest coupling: neighbours in z are at most one slab apart.
  // Slab boundaries fall between nodes; empty slabs are dropped (nothing couples across them).
  thickness_ = longest_coupling(m.stiffness, node_z, dofs) * (1.0 + 1e-9);
  std::vector<Eigen::Index> slab_of_node(node_z.size(), 0);
  Eigen::Index slab = -1;
  long previous_cell = 0;
  for (std::size_t n = 0; n < node_z.size(); ++n) {
    const long cell = thickness_ > 0.0 ? static_cast<long>(std::floor((node_z[n] - node_z[0]) / thickness_))
                                       : static_cast<long>(n);
    if (n == 0 || cell != previous_cell) {
      ++slab;
      offset_.push_back(dofs * static_cast<Eigen::Index>(n));
    }
    previous_cell = cell;
    slab_of_node[n] = slab;
  }
  offset_.push_back(m.unknowns());
  const std::size_t s_count = offset_.size() - 1;
  auto size = [&](std::size_t s) { return offset_[s + 1] - offset_[s]; };
  for (std::size_t s = 0; s < s_count; ++s) {
    k_diagonal_.push_back(Eigen::MatrixXd::Zero(size(s), size(s)));
    c_diagonal_.push_back(Eigen::MatrixXd::Zero(size(s), size(s)));
    k_lower_.push_back(Eigen::MatrixXd::Zero(size(s), s > 0 ? size(s - 1) : 0));
    c_lower_.push_back(Eigen::MatrixXd::Zero(size(s), s > 0 ? size(s - 1) : 0));
  }
  auto scatter = [&](const Eigen::SparseMatrix<double>& a, std::vector<Eigen::MatrixXd>& diagonal,
                     std::vector<Eigen::MatrixXd>& lower) {
    for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
      const auto sc = static_cast<std::size_t>(slab_of_node[static_cast<std::size_t>(col / dofs)]);
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it) {
        const auto sr = static_cast<std::size_t>(slab_of_node[static_cast<std::size_t>(it.row() / dofs)]);
        if (sr == sc) {
          diagonal[sr](it.row() - offset_[sr], col - offset_[sc]) += it.value();
        } else if (sr == sc + 1) {
          lower[sr](it.row() - offset_[sr], col - offset_[sc]) += it.value();
        } else if (sc != sr + 1) {
          throw std::logic_error("slab solver: the matrix couples slabs that are not neighbours");
        }
      }
    }
  };
  scatter(m.stiffness, k_diagonal_, k_lower_);
  scatter(m.dashpots, c_diagonal_, c_lower_);
  if (m.fixed_dashpots.nonZeros() > 0) {
    t_diagonal_ = c_diagonal_;
    t_lower_ = c_lower_;
    for (auto& b : t_diagonal_) b.setZero();
    for (auto& b : t_lower_) b.setZero();
    scatter(m.fixed_dashpots, t_diagonal_, t_lower_);
  }
}

Eigen::Index SlabSolver::largest_slab() const {
  Eigen::Index largest = 0;
  for (std::size_t s = 0; s + 1 < offset_.size(); ++s) largest = std::max(largest, offset_[s + 1] - offset_[s]);
  return largest;
}

Eigen::VectorXcd SlabSolver::solve(double omega, double gamma, const Eigen::VectorXd& extra_damping,
                                   const Eigen::VectorXcd& rhs) const {
  return eliminate({0.0, omega}, {-omega * omega, 0.0}, gamma, extra_damping, rhs);
}

std::optional<Eigen::MatrixXd> SlabSolver::solve_shifted(double mass_shift, const Eigen::MatrixXd& rhs) const {
  auto lower = [&](std::size_t s) -> const Eigen::MatrixXd& { return k_lower_[s]; };
  auto diagonal = [&](std::size_t s) -> Eigen::MatrixXd {
    Eigen::MatrixXd z = k_diagonal_[s];
    z.diagonal() += mass_shift * mass_.segment(offset_[s], offset_[s + 1] - offset_[s]);
    return z;
  };
  return block_thomas<Eigen::LLT<Eigen::MatrixXd>>(offset_, diagonal, lower, rhs);
}

Eigen::MatrixXcd SlabSolver::eliminate(std::complex<double> damping_factor, std::complex<double> mass_factor,
                                       double gamma, const Eigen::VectorXd& extra_damping,
                                       const Eigen::MatrixXcd& rhs) const {
  using Complex = std::complex<double>;
  const Complex a = damping_factor;
  const bool tangential = !t_diagonal_.empty();
  auto lower = [&](std::size_t s) -> Eigen::MatrixXcd {
    Eigen::MatrixXcd z = k_lower_[s].cast<Complex>() + (a * gamma) * c_lower_[s].cast<Complex>();
    if (tangential) z += a * t_lower_[s].cast<Complex>();
    return z;
  };
  auto diagonal = [&](std::size_t s) -> Eigen::MatrixXcd {
    const Eigen::Index o = offset_[s], n = offset_[s + 1] - offset_[s];
    Eigen::MatrixXcd z = k_diagonal_[s].cast<Complex>() + (a * gamma) * c_diagonal_[s].cast<Complex>();
    if (tangential) z += a * t_diagonal_[s].cast<Complex>();
    z.diagonal() += mass_factor * mass_.segment(o, n).cast<Complex>();
    if (extra_damping.size() > 0) z.diagonal() += a * extra_damping.segment(o, n).cast<Complex>();
    return z;
  };
  // LU never refuses a block: a singular one gives inf/NaN, which the caller's checks see.
  return *block_thomas<Eigen::PartialPivLU<Eigen::MatrixXcd>>(offset_, diagonal, lower, rhs);
}

}  // namespace sedwave::forward::linear
