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

/// y -= a x for n complex numbers, on the interleaved real and imaginary parts so that the compiler
/// vectorises it (std::complex's operator* checks for NaN and does not).
void subtract_scaled(std::complex<double>* y, std::complex<double> a, const std::complex<double>* x, Eigen::Index n) {
  double* yd = reinterpret_cast<double*>(y);
  const double* xd = reinterpret_cast<const double*>(x);
  const double ar = a.real(), ai = a.imag();
  for (Eigen::Index i = 0; i < 2 * n; i += 2) {
    yd[i] -= ar * xd[i] - ai * xd[i + 1];
    yd[i + 1] -= ar * xd[i + 1] + ai * xd[i];
  }
}

/// LU factorisation with partial pivoting of a small dense complex matrix, unblocked, column
/// oriented. For the 20-60 unknown blocks of a channel, Eigen's blocked factorisation and triangular
/// solves spend most of their time packing panels; these loops take half the time (30 x 30 LU: 24
/// against 53 us, -O3, measured side by side). Same interface as the Eigen factorisations
/// block_thomas also takes.
class ComplexLu {
 public:
  explicit ComplexLu(Eigen::MatrixXcd a) : lu_(std::move(a)), pivot_(static_cast<std::size_t>(lu_.rows())) {
    const Eigen::Index n = lu_.rows();
    for (Eigen::Index k = 0; k < n; ++k) {
      Eigen::Index p = 0;
      lu_.col(k).tail(n - k).cwiseAbs2().maxCoeff(&p);
      p += k;
      pivot_[static_cast<std::size_t>(k)] = p;
      if (p != k) lu_.row(k).swap(lu_.row(p));
      const Eigen::Index below = n - k - 1;
      lu_.col(k).tail(below) *= 1.0 / lu_(k, k);  // a zero pivot gives inf/NaN, which callers check
      for (Eigen::Index j = k + 1; j < n; ++j) {
        subtract_scaled(lu_.col(j).data() + k + 1, lu_(k, j), lu_.col(k).data() + k + 1, below);
      }
    }
    inverse_pivot_ = lu_.diagonal().cwiseInverse();
  }

  [[nodiscard]] Eigen::MatrixXcd solve(const Eigen::MatrixXcd& b) const { return solve_rows_from(b, 0); }

  /// Rows first .. n-1 of A^{-1} B (the rows above are left unfinished): the back substitution
  /// stops there. With zeros in B skipped, the cost follows the rows B and the result occupy; the
  /// slab solver's right-hand sides live in a slab's upper rows and it needs only those rows back.
  [[nodiscard]] Eigen::MatrixXcd solve_rows_from(const Eigen::MatrixXcd& b, Eigen::Index first) const {
    Eigen::MatrixXcd x = b;
    const Eigen::Index n = lu_.rows();
    for (Eigen::Index k = 0; k < n; ++k) {
      if (pivot_[static_cast<std::size_t>(k)] != k) x.row(k).swap(x.row(pivot_[static_cast<std::size_t>(k)]));
    }
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      std::complex<double>* xj = x.col(j).data();
      for (Eigen::Index k = 0; k < n; ++k) {
        if (xj[k] != 0.0) subtract_scaled(xj + k + 1, xj[k], lu_.col(k).data() + k + 1, n - k - 1);
      }
      for (Eigen::Index k = n; k-- > first;) {
        xj[k] *= inverse_pivot_(k);
        subtract_scaled(xj + first, xj[k], lu_.col(k).data() + first, k - first);
      }
    }
    return x;
  }

 private:
  Eigen::MatrixXcd lu_;
  std::vector<Eigen::Index> pivot_;
  Eigen::VectorXcd inverse_pivot_;  // 1 / U_kk: a multiplication per row instead of a division
};

/// Rows first .. of F^{-1} B where the factorisation can stop early; all of it otherwise. The
/// indices of the rows kept are those of the full result.
template <class Factorisation, class Matrix>
Matrix solve_rows_from(const Factorisation& f, const Matrix& b, Eigen::Index first) {
  if constexpr (std::is_same_v<Factorisation, ComplexLu>) {
    return f.solve_rows_from(b, first);
  } else {
    return f.solve(b);
  }
}

/// Block Gaussian elimination of a symmetric block-tridiagonal matrix (the block Thomas algorithm).
/// Forward: Schur complements S_s = Z_s - L_s S_{s-1}^{-1} L_s^T and W_s = S_s^{-1} (B_s - L_s W_{s-1});
/// back: U_s = W_s - S_s^{-1} L_{s+1}^T U_{s+1}. Slab s holds unknowns offset[s] .. offset[s+1];
/// diagonal(s) is Z_s. L_s (rows slab s, columns slab s-1) is zero outside a few rows and columns,
/// those of grains with a contact across the boundary: lower(s) is L_s restricted to them,
/// coupling.rows[s] x coupling.cols[s]: only those rows of S_{s-1}^{-1} L_s^T are needed, and the
/// factors of each slab are kept for the back substitution instead of S_s^{-1} L_{s+1}^T in full.
/// Factorisation is Eigen::LLT (real symmetric positive definite; returns nullopt at the first
/// block that is not, so the matrix is not) or ComplexLu (any regular complex matrix).
template <class Factorisation, class Matrix, class Diagonal, class Lower>
std::optional<Matrix> block_thomas(std::span<const Eigen::Index> offset, const SlabCoupling& coupling,
                                   Diagonal diagonal, Lower lower, const Matrix& rhs) {
  const std::size_t slabs = offset.size() - 1;
  auto rows = [&](std::size_t s) { return offset[s + 1] - offset[s]; };
  std::vector<Factorisation> factor;
  factor.reserve(slabs);
  std::vector<Matrix> w(slabs);
  Matrix next_lower;  // L_{s+1} on its coupled rows and columns
  Matrix reach;       // S_s^{-1} L_{s+1}^T on the columns of slab s that couple to slab s+1
  for (std::size_t s = 0; s < slabs; ++s) {
    Matrix schur = diagonal(s);
    Matrix y = rhs.middleRows(offset[s], rows(s));
    if (s > 0 && !coupling.rows[s].empty()) {
      const auto& r = coupling.rows[s];
      schur(r, r) -= next_lower * reach;
      y(r, Eigen::all) -= next_lower * w[s - 1](coupling.cols[s], Eigen::all);
    }
    factor.emplace_back(schur);
    if constexpr (std::is_same_v<Factorisation, Eigen::LLT<Matrix>>) {
      if (factor.back().info() != Eigen::Success) return std::nullopt;
    }
    w[s] = factor.back().solve(y);
    if (s + 1 < slabs && !coupling.cols[s + 1].empty()) {
      const auto& c = coupling.cols[s + 1];  // ascending
      next_lower = lower(s + 1);
      Matrix lt = Matrix::Zero(rows(s), next_lower.rows());
      lt(c, Eigen::all) = next_lower.transpose();
      reach = solve_rows_from(factor.back(), lt, c.front())(c, Eigen::all);
    }
  }
  Matrix u(rhs.rows(), rhs.cols());
  u.middleRows(offset[slabs - 1], rows(slabs - 1)) = w[slabs - 1];
  for (std::size_t s = slabs - 1; s-- > 0;) {
    Matrix us = w[s];
    if (!coupling.rows[s + 1].empty()) {
      Matrix t = Matrix::Zero(rows(s), rhs.cols());
      t(coupling.cols[s + 1], Eigen::all) =
          lower(s + 1).transpose() * u.middleRows(offset[s + 1], rows(s + 1))(coupling.rows[s + 1], Eigen::all);
      us -= factor[s].solve(t);
    }
    u.middleRows(offset[s], rows(s)) = us;
  }
  return u;
}

/// z += a t for a real t: as z += a * t.cast<Complex>() up to the sign of exact zeros, without a
/// complex product (and its NaN checks) per entry.
void add_scaled(Eigen::MatrixXcd& z, std::complex<double> a, const Eigen::MatrixXd& t) {
  z.real() += a.real() * t;
  z.imag() += a.imag() * t;
}

}  // namespace

SlabSolver::SlabSolver(const DynamicMatrices& m, std::span<const double> node_z) : mass_(m.mass) {
  const auto nodes = static_cast<Eigen::Index>(node_z.size());
  const int dofs = m.dofs_per_node;
  if (dofs * nodes != m.unknowns()) throw std::invalid_argument("slab solver: one z per node is needed");
  // Slabs of thickness h >= the longest coupling: neighbours in z are at most one slab apart.
  // Slab boundaries fall between nodes; empty slabs are dropped (nothing couples across them).
  // C_t counts too: a pore fluid's squeeze films join grains across gaps that K leaves apart. (C1
  // joins no pair that K does not: every pair with a dashpot has a spring.)
  thickness_ =
      std::max(longest_coupling(m.stiffness, node_z, dofs), longest_coupling(m.fixed_dashpots, node_z, dofs)) *
      (1.0 + 1e-9);
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
  keep_coupled_corners();
}

void SlabSolver::keep_coupled_corners() {
  coupling_.rows.assign(k_lower_.size(), {});
  coupling_.cols.assign(k_lower_.size(), {});
  for (std::size_t s = 1; s < k_lower_.size(); ++s) {
    Eigen::MatrixXd pattern = k_lower_[s].cwiseAbs() + c_lower_[s].cwiseAbs();
    if (!t_lower_.empty()) pattern += t_lower_[s].cwiseAbs();
    for (Eigen::Index i = 0; i < pattern.rows(); ++i) {
      if (pattern.row(i).any()) coupling_.rows[s].push_back(i);
    }
    for (Eigen::Index j = 0; j < pattern.cols(); ++j) {
      if (pattern.col(j).any()) coupling_.cols[s].push_back(j);
    }
    auto corner = [&](Eigen::MatrixXd& block) {
      block = Eigen::MatrixXd(block(coupling_.rows[s], coupling_.cols[s]));
    };
    corner(k_lower_[s]);
    corner(c_lower_[s]);
    if (!t_lower_.empty()) corner(t_lower_[s]);
  }
}

Eigen::Index SlabSolver::largest_slab() const {
  Eigen::Index largest = 0;
  for (std::size_t s = 0; s + 1 < offset_.size(); ++s) largest = std::max(largest, offset_[s + 1] - offset_[s]);
  return largest;
}

Eigen::MatrixXcd SlabSolver::solve(double omega, double gamma, const Eigen::VectorXd& extra_damping,
                                   const Eigen::MatrixXcd& rhs) const {
  return eliminate({0.0, omega}, {-omega * omega, 0.0}, gamma, extra_damping, rhs);
}

std::optional<Eigen::MatrixXd> SlabSolver::solve_shifted(double mass_shift, const Eigen::MatrixXd& rhs) const {
  auto lower = [&](std::size_t s) -> const Eigen::MatrixXd& { return k_lower_[s]; };
  auto diagonal = [&](std::size_t s) -> Eigen::MatrixXd {
    Eigen::MatrixXd z = k_diagonal_[s];
    z.diagonal() += mass_shift * mass_.segment(offset_[s], offset_[s + 1] - offset_[s]);
    return z;
  };
  return block_thomas<Eigen::LLT<Eigen::MatrixXd>>(offset_, coupling_, diagonal, lower, rhs);
}

Eigen::MatrixXcd SlabSolver::eliminate(std::complex<double> damping_factor, std::complex<double> mass_factor,
                                       double gamma, const Eigen::VectorXd& extra_damping,
                                       const Eigen::MatrixXcd& rhs) const {
  using Complex = std::complex<double>;
  const Complex a = damping_factor;
  const bool fixed = !t_diagonal_.empty();  // C_t: friction or a fluid
  auto lower = [&](std::size_t s) -> Eigen::MatrixXcd {
    Eigen::MatrixXcd z = k_lower_[s].cast<Complex>() + (a * gamma) * c_lower_[s].cast<Complex>();
    if (fixed) add_scaled(z, a, t_lower_[s]);
    return z;
  };
  auto diagonal = [&](std::size_t s) -> Eigen::MatrixXcd {
    const Eigen::Index o = offset_[s], n = offset_[s + 1] - offset_[s];
    Eigen::MatrixXcd z = k_diagonal_[s].cast<Complex>() + (a * gamma) * c_diagonal_[s].cast<Complex>();
    if (fixed) add_scaled(z, a, t_diagonal_[s]);
    z.diagonal() += mass_factor * mass_.segment(o, n).cast<Complex>();
    if (extra_damping.size() > 0) z.diagonal() += a * extra_damping.segment(o, n).cast<Complex>();
    return z;
  };
  // LU never refuses a block: a singular one gives inf/NaN, which the caller's checks see.
  return *block_thomas<ComplexLu>(offset_, coupling_, diagonal, lower, rhs);
}

}  // namespace sedwave::forward::linear
