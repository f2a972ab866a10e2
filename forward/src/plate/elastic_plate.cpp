#include "sedwave/forward/plate/elastic_plate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace sedwave::forward::plate {
namespace {

void check(const PlateMaterial& m, const PlateMesh& mesh) {
  if (!(m.youngs_modulus > 0.0)) throw std::invalid_argument("plate: youngs_modulus must be > 0");
  if (!(m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5))
    throw std::invalid_argument("plate: poisson_ratio must lie in [0, 0.5)");
  if (!(m.density > 0.0)) throw std::invalid_argument("plate: density must be > 0");
  if (!(m.thickness > 0.0)) throw std::invalid_argument("plate: thickness must be > 0");
  if (mesh.elements_x < 1 || mesh.elements_y < 1)
    throw std::invalid_argument("plate: elements_x and elements_y must be >= 1");
  // Node and degree-of-freedom indices are int: counted in 64 bits, refused before they overflow.
  const std::int64_t dofs = 2 * (std::int64_t{mesh.elements_x} + 1) * (std::int64_t{mesh.elements_y} + 1);
  if (dofs > std::numeric_limits<int>::max())
    throw std::invalid_argument("plate: " + std::to_string(mesh.elements_x) + " x " + std::to_string(mesh.elements_y) +
                                " elements: more degrees of freedom than an int indexes");
  if (!(mesh.length_x > 0.0 && mesh.length_y > 0.0))
    throw std::invalid_argument("plate: length_x and length_y must be > 0");
}

// Plane-stress bilinear rectangle a x b, thickness t, 2x2 Gauss quadrature (exact for this element).
// Shape functions N_k = (1 + xi xi_k)(1 + eta eta_k)/4 (Zienkiewicz & Taylor, vol. 1, ch. 6).
Eigen::Matrix<double, 8, 8> rectangle_stiffness(const PlateMaterial& m, double a, double b) {
  const double e = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio);
  Eigen::Matrix3d D;
  D << e, e * m.poisson_ratio, 0.0, e * m.poisson_ratio, e, 0.0, 0.0, 0.0, e * 0.5 * (1.0 - m.poisson_ratio);
  const double xi_k[4] = {-1.0, 1.0, 1.0, -1.0};
  const double eta_k[4] = {-1.0, -1.0, 1.0, 1.0};
  const double g = 1.0 / std::sqrt(3.0);
  Eigen::Matrix<double, 8, 8> K = Eigen::Matrix<double, 8, 8>::Zero();
  for (const double xi : {-g, g}) {
    for (const double eta : {-g, g}) {
      Eigen::Matrix<double, 3, 8> B = Eigen::Matrix<double, 3, 8>::Zero();
      for (int k = 0; k < 4; ++k) {
        const double dndx = 0.25 * xi_k[k] * (1.0 + eta * eta_k[k]) * 2.0 / a;
        const double dndy = 0.25 * eta_k[k] * (1.0 + xi * xi_k[k]) * 2.0 / b;
        B(0, 2 * k) = dndx;
        B(1, 2 * k + 1) = dndy;
        B(2, 2 * k) = dndy;
        B(2, 2 * k + 1) = dndx;
      }
      K += B.transpose() * D * B * (m.thickness * a * b / 4.0);  // unit Gauss weights, dA = ab/4
    }
  }
  return K;
}

}  // namespace

double dilatational_speed(const PlateMaterial& m) {
  return std::sqrt(m.youngs_modulus / (m.density * (1.0 - m.poisson_ratio * m.poisson_ratio)));
}

double shear_speed(const PlateMaterial& m) {
  return std::sqrt(m.youngs_modulus / (2.0 * m.density * (1.0 + m.poisson_ratio)));
}

// The uniform rectangle's stencil has the mesh's mirror symmetries: a block at offset (dx, dy) is the
// block at (-dx, dy) with its x-y coupling negated, and likewise in y. The centre and axis blocks
// therefore couple x to y not at all, the two axis neighbours along a line are alike, and the four
// corners share one diagonal and one coupling, +c at (-1, 1) and (1, -1), -c at (1, 1) and (-1, -1).
// Each coefficient is the mean over the blocks that share it (they differ by round-off in the
// quadrature, about 1e-16 of the centre); the form is checked against every entry.
ElasticPlate::NodeStencil ElasticPlate::compact_stencil(const Eigen::Matrix<double, 2, 18>& stencil) {
  const auto block = [&](int dx, int dy) { return Eigen::Matrix2d(stencil.block<2, 2>(0, 6 * (dy + 1) + 2 * (dx + 1))); };
  const auto diagonal = [](const Eigen::Matrix2d& m) { return Eigen::Array2d(m(0, 0), m(1, 1)); };
  NodeStencil s;
  s.centre = diagonal(block(0, 0));
  s.along_x = 0.5 * (diagonal(block(-1, 0)) + diagonal(block(1, 0)));
  s.along_y = 0.5 * (diagonal(block(0, -1)) + diagonal(block(0, 1)));
  s.corner = 0.25 * (diagonal(block(-1, -1)) + diagonal(block(1, -1)) + diagonal(block(-1, 1)) + diagonal(block(1, 1)));
  double coupling = 0.0;
  for (const auto& [dx, dy] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{-1, 1}, std::pair{1, 1}}) {
    const Eigen::Matrix2d m = block(dx, dy);
    coupling -= dx * dy * (m(0, 1) + m(1, 0));
  }
  s.corner_coupling = coupling / 8.0;
  const double scale = stencil.cwiseAbs().maxCoeff();
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const Eigen::Array2d d = dx == 0 && dy == 0 ? s.centre : dy == 0 ? s.along_x : dx == 0 ? s.along_y : s.corner;
      const double c = dx * dy == 0 ? 0.0 : -dx * dy * s.corner_coupling;
      Eigen::Matrix2d compact;
      compact << d(0), c, c, d(1);
      if (!((compact - block(dx, dy)).cwiseAbs().maxCoeff() <= 1e-12 * scale))
        throw std::logic_error("plate: the node stencil lacks the uniform mesh's symmetry");
    }
  return s;
}

ElasticPlate::ElasticPlate(const PlateMaterial& material, const PlateMesh& mesh, const PlateEdges& edges)
    : material_(material), mesh_(mesh), a_(0.0), b_(0.0) {
  check(material, mesh);
  a_ = mesh.length_x / mesh.elements_x;
  b_ = mesh.length_y / mesh.elements_y;
  element_stiffness_ = rectangle_stiffness(material, a_, b_);
  const int row_order[4] = {0, 1, 3, 2};  // counter-clockwise index of each node in row order
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c)
      row_stiffness_(r, c) = element_stiffness_(2 * row_order[r / 2] + r % 2, 2 * row_order[c / 2] + c % 2);
  // Node a of an element couples to node b at the offset (b - a) in the mesh: an interior node sums
  // the blocks of its four elements into one 3 x 3 stencil.
  // A node of an edge has the elements in which it is node a for the a listed.
  const auto stencil_of = [&](std::initializer_list<int> present) {
    Eigen::Matrix<double, 2, 18> s = Eigen::Matrix<double, 2, 18>::Zero();
    for (const int a : present)
      for (int b = 0; b < 4; ++b) {
        const int dx = b % 2 - a % 2, dy = b / 2 - a / 2;
        s.block<2, 2>(0, 6 * (dy + 1) + 2 * (dx + 1)) += row_stiffness_.block<2, 2>(2 * a, 2 * b);
      }
    return s;
  };
  stencil_ = stencil_of({0, 1, 2, 3});
  node_stencil_ = compact_stencil(stencil_);
  edge_stencil_[0] = stencil_of({0, 1}).rightCols<12>();  // bottom: the node's row and the one above
  edge_stencil_[1] = stencil_of({2, 3}).leftCols<12>();   // top: the row below and the node's
  const Eigen::Matrix<double, 2, 18> left = stencil_of({0, 2}), right = stencil_of({1, 3});
  for (int dy = 0; dy < 3; ++dy) {  // left: the node and its right neighbour; right: its left one and the node
    edge_stencil_[2].block<2, 4>(0, 4 * dy) = left.block<2, 4>(0, 6 * dy + 2);
    edge_stencil_[3].block<2, 4>(0, 4 * dy) = right.block<2, 4>(0, 6 * dy);
  }

  const auto n = static_cast<std::size_t>(dof_count());
  mass_.assign(n, 0.0);
  damping_.assign(n, 0.0);
  fixed_.assign(n, 0);
  const double quarter = material.density * material.thickness * a_ * b_ / 4.0;
  for (int j = 0; j < mesh.elements_y; ++j)
    for (int i = 0; i < mesh.elements_x; ++i)
      for (const int k : {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)}) {
        mass_[static_cast<std::size_t>(2 * k)] += quarter;
        mass_[static_cast<std::size_t>(2 * k + 1)] += quarter;
      }

  // Irons' bound: the largest eigenvalue of the element pencil (K_e, M_e), M_e = quarter I.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 8, 8>> eig(element_stiffness_, Eigen::EigenvaluesOnly);
  omega_bound_ = std::sqrt(eig.eigenvalues().maxCoeff() / quarter);

  // Edges. Lysmer & Kuhlemeyer (1969): a dashpot rho c t per unit length of edge along the normal
  // (c = c_L) and along the edge (c = c_S) absorbs plane waves at normal incidence exactly.
  const double z_normal = material.density * dilatational_speed(material) * material.thickness;
  const double z_shear = material.density * shear_speed(material) * material.thickness;
  auto apply = [&](EdgeCondition condition, int node_index, int normal_component, double tributary_length) {
    const auto dof = [&](int c) { return static_cast<std::size_t>(2 * node_index + c); };
    switch (condition) {
      case EdgeCondition::free: break;
      case EdgeCondition::clamped: fixed_[dof(0)] = fixed_[dof(1)] = 1; break;
      case EdgeCondition::absorbing:
        damping_[dof(normal_component)] += z_normal * tributary_length;
        damping_[dof(1 - normal_component)] += z_shear * tributary_length;
        break;
    }
  };
  for (int i = 0; i < nodes_x(); ++i) {
    const double length = (i == 0 || i == mesh.elements_x) ? 0.5 * a_ : a_;
    apply(edges.bottom, node(i, 0), 1, length);
    apply(edges.top, node(i, mesh.elements_y), 1, length);
  }
  for (int j = 0; j < nodes_y(); ++j) {
    const double length = (j == 0 || j == mesh.elements_y) ? 0.5 * b_ : b_;
    apply(edges.left, node(0, j), 0, length);
    apply(edges.right, node(mesh.elements_x, j), 0, length);
  }
  inverse_mass_.resize(n);
  for (std::size_t d = 0; d < n; ++d) {
    if (fixed_[d]) damping_[d] = 0.0;
    inverse_mass_[d] = fixed_[d] ? 0.0 : 1.0 / mass_[d];
  }
}

void ElasticPlate::fix(int node_index, int component) {
  if (node_index < 0 || node_index >= node_count() || component < 0 || component > 1)
    throw std::out_of_range("ElasticPlate::fix: node " + std::to_string(node_index) + " component " +
                            std::to_string(component));
  const auto d = static_cast<std::size_t>(2 * node_index + component);
  fixed_[d] = 1;
  damping_[d] = 0.0;
  inverse_mass_[d] = 0.0;
}

// Interior nodes by the 3 x 3 stencil in its compact form (node_stencil_), the edges' nodes by the
// stencils of their two elements (edge_stencil_), the four corners from their element's rows of the
// element stiffness. In row order a node row's unknowns are
// consecutive, so both read runs of values without an index table.
//
// Each node's (x, y) pair is one two-lane vector. With column sums P = u_above + u_below and
// differences Q = u_above - u_below, an interior node's K u is
//   centre u + along_x (u_left + u_right) + along_y P + corner (P_left + P_right)
//   + corner_coupling swap(Q_left - Q_right),
// where swap exchanges x and y; P and Q of the right column are carried to the next node, so a
// node reads three new pairs and costs five products instead of the stencil's 36.
template <ElasticPlate::Accumulate mode>
void ElasticPlate::apply_stiffness(const double* u, double* f, int element_rows) const {
  using Pair = Eigen::Array2d;
  using Vec4 = Eigen::Matrix<double, 4, 1>;
  const auto load = [](const double* at) { return Pair(Eigen::Map<const Pair>(at)); };
  const int nx = mesh_.elements_x, ny = element_rows;
  const auto row = static_cast<std::size_t>(2 * nodes_x());
  const auto& [centre, along_x, along_y, corner, coupling] = node_stencil_;
  const auto accumulate = [](auto&& force, const auto& ku) {
    if constexpr (mode == Accumulate::overwrite)
      force = -ku;
    else if constexpr (mode == Accumulate::subtract)
      force -= ku;
    else
      force += ku;
  };
  for (int j = 1; j < ny; ++j) {
    const double* below = u + static_cast<std::size_t>(j - 1) * row;
    const double* level = below + row;
    const double* above = level + row;
    double* out = f + static_cast<std::size_t>(j) * row;
    Pair sum_left = load(above) + load(below), diff_left = load(above) - load(below);
    Pair sum_here = load(above + 2) + load(below + 2), diff_here = load(above + 2) - load(below + 2);
    Pair u_left = load(level), u_here = load(level + 2);
    for (std::size_t d = 2; d < row - 2; d += 2) {
      const Pair u_right = load(level + d + 2);
      const Pair sum_right = load(above + d + 2) + load(below + d + 2);
      const Pair diff_right = load(above + d + 2) - load(below + d + 2);
      const Pair ku = centre * u_here + along_x * (u_left + u_right) + along_y * sum_here +
                      corner * (sum_left + sum_right) + coupling * (diff_left - diff_right).reverse();
      accumulate(Eigen::Map<Pair>(out + d), ku);
      u_left = u_here, u_here = u_right;
      sum_left = sum_here, sum_here = sum_right;
      diff_left = diff_here, diff_here = diff_right;
    }
  }
  const auto store = [&](std::size_t at, const Eigen::Vector2d& ku) {
    accumulate(Eigen::Map<Eigen::Vector2d>(f + at), ku);
  };
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  const auto top = static_cast<std::size_t>(ny) * row;
  // A bottom or top edge's stencil on its two node rows' runs of three nodes, read in place.
  const auto along_edge = [&](const Eigen::Matrix<double, 2, 12>& stencil, const double* lower) -> Eigen::Vector2d {
    return stencil.leftCols<6>() * Eigen::Map<const Vec6>(lower) +
           stencil.rightCols<6>() * Eigen::Map<const Vec6>(lower + row);
  };
  for (std::size_t d = 2; d < row - 2; d += 2) {  // the bottom and top edges but their corners
    store(d, along_edge(edge_stencil_[0], u + d - 2));
    store(top + d, along_edge(edge_stencil_[1], u + top - row + d - 2));
  }
  for (int j = 1; j < ny; ++j) {  // the left and right edges but their corners
    const auto below = static_cast<std::size_t>(j - 1) * row;
    Vec12 around;
    around << Eigen::Map<const Vec4>(u + below), Eigen::Map<const Vec4>(u + below + row),
        Eigen::Map<const Vec4>(u + below + 2 * row);
    store(below + row, edge_stencil_[2] * around);
    const std::size_t last = row - 4;
    around << Eigen::Map<const Vec4>(u + below + last), Eigen::Map<const Vec4>(u + below + row + last),
        Eigen::Map<const Vec4>(u + below + 2 * row + last);
    store(below + row + last + 2, edge_stencil_[3] * around);
  }
  const auto corner_node = [&](int i, int j) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) {  // the node is node a of the element whose lower left is (i, j) - offset(a)
      const int ei = i - a % 2, ej = j - a / 2;
      if (ei < 0 || ei >= nx || ej < 0 || ej >= ny) continue;
      const double* lower = u + static_cast<std::size_t>(ej) * row + static_cast<std::size_t>(2 * ei);
      Eigen::Matrix<double, 8, 1> ue;
      ue << Eigen::Map<const Vec4>(lower), Eigen::Map<const Vec4>(lower + row);
      sum += row_stiffness_.block<2, 8>(2 * a, 0) * ue;
    }
    store(static_cast<std::size_t>(j) * row + static_cast<std::size_t>(2 * i), sum);
  };
  for (const int j : {0, ny})
    for (const int i : {0, nx}) corner_node(i, j);
}

// The top row of elements is a plate one element high on the two top rows of nodes: the same
// stencils, its lower row of nodes taking the bottom edge's (each of them has only the elements above
// it here) and its ends the corners'.
void ElasticPlate::add_top_row_forces(const std::vector<double>& u, std::vector<double>& f, double sign) const {
  const std::size_t base = static_cast<std::size_t>(mesh_.elements_y - 1) * static_cast<std::size_t>(2 * nodes_x());
  if (sign == 1.0)
    apply_stiffness<Accumulate::subtract>(u.data() + base, f.data() + base, 1);
  else if (sign == -1.0)
    apply_stiffness<Accumulate::add>(u.data() + base, f.data() + base, 1);
  else
    throw std::invalid_argument("ElasticPlate::add_top_row_forces: sign must be 1 or -1");
}

void ElasticPlate::add_elastic_forces(const std::vector<double>& u, std::vector<double>& f) const {
  apply_stiffness<Accumulate::subtract>(u.data(), f.data(), mesh_.elements_y);
}

void ElasticPlate::elastic_forces(const std::vector<double>& u, std::vector<double>& f) const {
  f.resize(u.size());
  apply_stiffness<Accumulate::overwrite>(u.data(), f.data(), mesh_.elements_y);
}

double ElasticPlate::strain_energy(const std::vector<double>& u) const {
  std::vector<double> f(u.size(), 0.0);
  add_elastic_forces(u, f);
  double e = 0.0;
  for (std::size_t d = 0; d < u.size(); ++d) e -= 0.5 * u[d] * f[d];
  return e;
}

ElasticPlate::EdgePoint ElasticPlate::top_edge_point(double x) const {
  // Clamped as a double: a NaN or far-off abscissa must not reach the conversion to int.
  const double cell = std::floor(x / a_);
  const int column = cell >= 0.0 ? static_cast<int>(std::min(cell, static_cast<double>(mesh_.elements_x - 1))) : 0;
  const double xi = x / a_ - column;
  const int j = mesh_.elements_y;
  return {node(column, j), node(column + 1, j), 1.0 - xi, xi};
}

ElasticPlate::EdgePoint ElasticPlate::top_edge_node(double x) const {
  const double nearest = std::round(x / a_);  // clamped as a double, as above
  const int i = nearest >= 0.0 ? static_cast<int>(std::min(nearest, static_cast<double>(mesh_.elements_x))) : 0;
  const int n = node(i, mesh_.elements_y);
  return {n, n, 1.0, 0.0};
}

}  // namespace sedwave::forward::plate
