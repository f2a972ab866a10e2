#include "sedwave/forward/linear/dynamic_matrices.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>

namespace sedwave::forward::linear {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;
using Operator = Eigen::Matrix<double, 3, 6>;  // a grain's (translation, rotation) -> a relative motion
// Blocks of 3 or 6 columns with their storage inline: add_pair runs per contact, and heap-allocated
// temporaries there took most of the assembly time.
using OperatorColumns = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6>;
using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

void add_block(Triplets& t, Eigen::Index row, Eigen::Index col, const Block& block) {
  for (Eigen::Index a = 0; a < block.rows(); ++a) {
    for (Eigen::Index b = 0; b < block.cols(); ++b) {
      if (block(a, b) != 0.0) t.emplace_back(row + a, col + b, block(a, b));
    }
  }
}

/// Where the free grains' blocks live in a compressed-column (CSC) array, the same for K, C1 and
/// C_t: node c's columns hold, for every node coupled to c (c itself included, ascending), a dense
/// dofs x dofs block. Each free pair's four blocks are added in place, with no triplet list to
/// sort: a triplet list of a 5e4-grain channel holds 13 million entries, and building and sorting
/// it took most of the assembly time.
class BlockPattern {
 public:
  /// `ends`: the two nodes of every pair, -1 where an end belongs to a rigid body.
  BlockPattern(std::size_t nodes, std::span<const std::array<std::int32_t, 2>> ends, int dofs)
      : dofs_(dofs), first_(nodes + 1, 0), position_(ends.size(), {-1, -1}) {
    // Count each node's couplings (itself, then both ends of every free pair), list them, sort.
    std::vector<std::int64_t> start(nodes + 1, 0);
    for (std::size_t n = 0; n < nodes; ++n) start[n + 1] = 1;
    for (const auto& e : ends) {
      if (e[0] >= 0 && e[1] >= 0) {
        ++start[static_cast<std::size_t>(e[0]) + 1];
        ++start[static_cast<std::size_t>(e[1]) + 1];
      }
    }
    for (std::size_t n = 0; n < nodes; ++n) start[n + 1] += start[n];
    std::vector<std::int32_t> listed(static_cast<std::size_t>(start[nodes]));
    std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
    for (std::size_t n = 0; n < nodes; ++n) listed[static_cast<std::size_t>(fill[n]++)] = static_cast<std::int32_t>(n);
    for (const auto& e : ends) {
      if (e[0] >= 0 && e[1] >= 0) {
        listed[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
        listed[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
      }
    }
    // Sorted and without repeats (two pairs may join the same nodes), compacted into rows_.
    rows_.reserve(listed.size());
    for (std::size_t n = 0; n < nodes; ++n) {
      const auto begin = listed.begin() + start[n], end = listed.begin() + start[n + 1];
      std::sort(begin, end);
      first_[n] = static_cast<std::int64_t>(rows_.size());
      rows_.insert(rows_.end(), begin, std::unique(begin, end));
    }
    first_[nodes] = static_cast<std::int64_t>(rows_.size());
    for (std::size_t q = 0; q < ends.size(); ++q) {
      const auto [i, j] = ends[q];
      if (i >= 0 && j >= 0) position_[q] = {place(i, j), place(j, i)};
    }
  }

  [[nodiscard]] std::size_t entries() const { return rows_.size() * static_cast<std::size_t>(dofs_ * dofs_); }

  /// Adds `block` at (row node, column node) of pair q's ends: end_row, end_col in {0, 1} (i, j).
  void add(std::vector<double>& values, std::size_t q, const std::array<std::int32_t, 2>& ends, int end_row,
           int end_col, const Block& block) const {
    const std::int32_t column = ends[static_cast<std::size_t>(end_col)];
    const std::int64_t where = end_row == end_col ? place(column, column)
                                                  : position_[q][static_cast<std::size_t>(end_col)];
    add_at(values, column, where, block);
  }

  /// Adds `block` to node `node`'s own (diagonal) block.
  void add_to_node(std::vector<double>& values, std::int32_t node, const Block& block) const {
    add_at(values, node, place(node, node), block);
  }

  /// The matrix of `values` without its exact zeros (blocks of pairs that a law leaves out).
  [[nodiscard]] Eigen::SparseMatrix<double> matrix(const std::vector<double>& values) const {
    const std::size_t nodes = first_.size() - 1;
    const auto unknowns = static_cast<Eigen::Index>(dofs_ * nodes);
    Eigen::SparseMatrix<double> m(unknowns, unknowns);
    m.resizeNonZeros(static_cast<Eigen::Index>(values.size()));
    std::copy(values.begin(), values.end(), m.valuePtr());
    int* outer = m.outerIndexPtr();
    int* inner = m.innerIndexPtr();
    std::size_t k = 0;
    for (std::size_t n = 0; n < nodes; ++n) {
      for (int a = 0; a < dofs_; ++a) {
        *outer++ = static_cast<int>(k);
        for (auto r = first_[n]; r < first_[n + 1]; ++r) {
          for (int b = 0; b < dofs_; ++b) inner[k++] = dofs_ * rows_[static_cast<std::size_t>(r)] + b;
        }
      }
    }
    *outer = static_cast<int>(k);
    m.prune([](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
    return m;
  }

 private:
  /// Adds `block` at the `where`-th node of node `column`'s list.
  void add_at(std::vector<double>& values, std::int32_t column, std::int64_t where, const Block& block) const {
    const std::int64_t length = first_[static_cast<std::size_t>(column) + 1] - first_[static_cast<std::size_t>(column)];
    double* entry = values.data() + dofs_ * (dofs_ * first_[static_cast<std::size_t>(column)] + where);
    for (int a = 0; a < dofs_; ++a, entry += dofs_ * length) {
      for (int b = 0; b < dofs_; ++b) entry[b] += block(b, a);
    }
  }

  /// Index of node `row` in node `column`'s list.
  [[nodiscard]] std::int64_t place(std::int32_t column, std::int32_t row) const {
    const auto begin = rows_.begin() + first_[static_cast<std::size_t>(column)];
    const auto end = rows_.begin() + first_[static_cast<std::size_t>(column) + 1];
    return std::lower_bound(begin, end, row) - begin;
  }

  int dofs_;
  std::vector<std::int64_t> first_;  ///< per node, its first entry in rows_; one past the last at the end
  std::vector<std::int32_t> rows_;   ///< the nodes coupled to each node, ascending
  /// Per pair: where node j sits in node i's column (end_col 0) and node i in node j's (end_col 1).
  std::vector<std::array<std::int64_t, 2>> position_;
};

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& n) {
  Eigen::Matrix3d c;
  c << 0.0, -n.z(), n.y(), n.z(), 0.0, -n.x(), -n.y(), n.x(), 0.0;
  return c;
}

/// Where one pair's forces go: the free unknowns' matrix (values in the BlockPattern's layout) and
/// each rigid body's couplings.
struct Targets {
  std::vector<double> matrix;
  std::vector<Triplets> body;
  std::vector<Eigen::Matrix3d> body_self;  ///< each body's translation on itself
};

/// One pair as assemble() sees it: its index, its grains' nodes (-1: a rigid body's grain) and bodies.
struct PairEnds {
  std::size_t index;
  std::array<std::int32_t, 2> nodes;
  std::array<int, 2> bodies;
};

/// Adds the energy 1/2 r^T S r of a relative motion r = A_i x_i + A_j x_j (A: 3 x dofs of each
/// grain, x = its unknowns, or for a rigid-body grain its body's translation) to the matrix.
void add_pair(Targets& t, const BlockPattern& pattern, const PairEnds& pair, const Eigen::Matrix3d& s,
              const Operator& a_i, const Operator& a_j, int dofs) {
  const OperatorColumns a[2] = {a_i.leftCols(dofs), a_j.leftCols(dofs)};
  for (int r = 0; r < 2; ++r) {
    if (pair.nodes[static_cast<std::size_t>(r)] < 0) {
      // A rigid body's grain: only its body's own translation block (pairs inside a body are never
      // listed, so the other end is free).
      t.body_self[static_cast<std::size_t>(pair.bodies[static_cast<std::size_t>(r)] - 1)] +=
          a[r].leftCols(3).transpose() * s * a[r].leftCols(3);
      continue;
    }
    for (int c = 0; c < 2; ++c) {
      if (pair.nodes[static_cast<std::size_t>(c)] >= 0) {
        pattern.add(t.matrix, pair.index, pair.nodes, r, c, Block(a[r].transpose() * s * a[c]));
      } else {
        // A rigid body's grain moves with the body's translation (its first three columns).
        add_block(t.body[static_cast<std::size_t>(pair.bodies[static_cast<std::size_t>(c)] - 1)],
                  dofs * static_cast<Eigen::Index>(pair.nodes[static_cast<std::size_t>(r)]), 0,
                  Block(a[r].transpose() * s * a[c].leftCols(3)));
      }
    }
  }
}

/// add_pair for the relative translation r = u_i - u_j (A_i = [I 0], A_j = [-I 0]): its blocks are
/// +-S, written without add_pair's operator products (which took most of the time of assembling a
/// fluid's squeeze films). Products with 0 and +-1 are exact: the same sums as add_pair's.
void add_translation_pair(Targets& t, const BlockPattern& pattern, const PairEnds& pair, const Eigen::Matrix3d& s,
                          int dofs) {
  constexpr double sign[2] = {1.0, -1.0};
  Block block = Block::Zero(dofs, dofs);
  for (std::size_t r = 0; r < 2; ++r) {
    if (pair.nodes[r] < 0) {
      t.body_self[static_cast<std::size_t>(pair.bodies[r] - 1)] += s;  // as add_pair: (-I) S (-I)
      continue;
    }
    for (std::size_t c = 0; c < 2; ++c) {
      block.topLeftCorner<3, 3>() = (sign[r] * sign[c]) * s;
      if (pair.nodes[c] >= 0) {
        pattern.add(t.matrix, pair.index, pair.nodes, static_cast<int>(r), static_cast<int>(c), block);
      } else {
        add_block(t.body[static_cast<std::size_t>(pair.bodies[c] - 1)], dofs * static_cast<Eigen::Index>(pair.nodes[r]),
                  0, Block(block.topLeftCorner<3, 3>()));
      }
    }
  }
}

/// The fluid's drag on every free grain's translation, relative to the fluid at rest (the walls,
/// moved by the drive, get none, as in the time-domain engine).
void add_drag(std::vector<double>& values, const BlockPattern& pattern, std::span<const dem::Grain> grains,
              const DynamicMatrices& m, const dem::FluidSpec& fluid) {
  Block drag = Block::Zero(m.dofs_per_node, m.dofs_per_node);
  for (std::size_t n = 0; n < m.grain_of_node.size(); ++n) {
    const dem::Grain& g = grains[static_cast<std::size_t>(m.grain_of_node[n])];
    drag.topLeftCorner<3, 3>().diagonal().setConstant(fluid.drag_coefficient(g.radius));
    pattern.add_to_node(values, static_cast<std::int32_t>(n), drag);
  }
}

Eigen::SparseMatrix<double> from_triplets(const Triplets& t, Eigen::Index rows, Eigen::Index cols) {
  Eigen::SparseMatrix<double> m(rows, cols);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

}  // namespace

DynamicMatrices assemble(std::span<const dem::Grain> grains, const ContactNetwork& network, int n_bodies,
                         const dem::ContactSpec& contact, const PairLinearisation* pairs,
                         const dem::FluidSpec* fluid) {
  const dem::AnyContactModel model = dem::undamped_contact_model(contact);
  if (!dem::linearised(model)) {
    throw std::invalid_argument("linear engine: rolling resistance and the Coulomb-tanh law are not linearised; "
                                "use the time-domain engine");
  }
  const bool friction = dem::has_tangential(model);
  DynamicMatrices m;
  m.dofs_per_node = friction ? 6 : 3;
  const int dofs = m.dofs_per_node;
  for (std::size_t g = 0; g < grains.size(); ++g) {
    if (grains[g].body == dem::kFreeBody) m.grain_of_node.push_back(static_cast<std::int32_t>(g));
    else if (grains[g].body < 1 || grains[g].body > n_bodies) {
      throw std::invalid_argument("linear engine: grain " + std::to_string(grains[g].id) + " names a missing rigid body");
    }
  }
  // Ascending z: the matrices become banded, which the slab solver exploits.
  std::stable_sort(m.grain_of_node.begin(), m.grain_of_node.end(), [&](std::int32_t a, std::int32_t b) {
    return grains[static_cast<std::size_t>(a)].position.z < grains[static_cast<std::size_t>(b)].position.z;
  });
  m.node_of_grain.assign(grains.size(), -1);
  for (std::size_t n = 0; n < m.grain_of_node.size(); ++n) {
    m.node_of_grain[static_cast<std::size_t>(m.grain_of_node[n])] = static_cast<std::int32_t>(n);
  }
  const auto unknowns = static_cast<Eigen::Index>(dofs * m.grain_of_node.size());
  m.mass.resize(unknowns);
  for (std::size_t n = 0; n < m.grain_of_node.size(); ++n) {
    const dem::Grain& g = grains[static_cast<std::size_t>(m.grain_of_node[n])];
    const auto row = static_cast<Eigen::Index>(dofs * n);
    m.mass.segment<3>(row).setConstant(g.mass);
    if (friction) m.mass.segment<3>(row + 3).setConstant(0.4 * g.mass * g.radius * g.radius);  // solid sphere
  }

  // Gaps carry an equivalent spring and dashpot (pairs) or a squeeze film (fluid); a dry packing's
  // tangent matrices leave them out. Pairs q < n_springs act on K and C1, all n_pairs on C_t.
  const std::size_t n_springs = network.contacts.size() + (pairs ? network.gaps.size() : 0);
  const std::size_t n_pairs = network.contacts.size() + (pairs || fluid ? network.gaps.size() : 0);
  if (pairs && (pairs->stiffness.size() != n_pairs || pairs->dashpot.size() != n_pairs)) {
    throw std::invalid_argument("linear engine: one equivalent stiffness and dashpot per contact and gap needed");
  }
  auto pair_at = [&](std::size_t q) -> const StaticPair& {
    return q < network.contacts.size() ? network.contacts[q] : network.gaps[q - network.contacts.size()];
  };
  std::vector<std::array<std::int32_t, 2>> ends(n_pairs);
  for (std::size_t q = 0; q < n_pairs; ++q) {
    ends[q] = {m.node_of_grain[static_cast<std::size_t>(pair_at(q).i)],
               m.node_of_grain[static_cast<std::size_t>(pair_at(q).j)]};
  }
  const BlockPattern pattern(m.grain_of_node.size(), std::span(ends).first(n_springs), dofs);
  // Squeeze films across gaps that K and C1 leave out: C_t's own pattern, so that theirs keeps only
  // what they hold (the first n_springs pairs are the same in both: same indices).
  std::optional<BlockPattern> film_pattern;
  if (n_pairs > n_springs) film_pattern.emplace(m.grain_of_node.size(), ends, dofs);
  const BlockPattern& fixed_pattern = film_pattern ? *film_pattern : pattern;
  Targets k{std::vector<double>(pattern.entries(), 0.0), std::vector<Triplets>(static_cast<std::size_t>(n_bodies)),
            std::vector<Eigen::Matrix3d>(static_cast<std::size_t>(n_bodies), Eigen::Matrix3d::Zero())};
  Targets c = k;
  const bool fixed = friction || fluid != nullptr;  // C_t has entries
  Targets ct{fixed ? std::vector<double>(fixed_pattern.entries(), 0.0) : std::vector<double>{}, k.body, k.body_self};
  if (fluid) add_drag(ct.matrix, fixed_pattern, grains, m, *fluid);
  for (std::size_t q = 0; q < n_pairs; ++q) {
    const bool touching = q < network.contacts.size();
    const StaticPair& p = pair_at(q);
    const PairEnds pair{q, ends[q], {grains[static_cast<std::size_t>(p.i)].body, grains[static_cast<std::size_t>(p.j)].body}};
    const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
    const Eigen::Matrix3d nn = n * n.transpose(), tangent_plane = Eigen::Matrix3d::Identity() - nn;
    // Normal law on u_i - u_j: tangent stiffness plus pre-stress, and the normal dashpot.
    if (q < n_springs) {
      const double normal_stiffness = pairs ? pairs->stiffness[q] : p.stiffness;
      add_translation_pair(k, pattern, pair, normal_stiffness * nn - (p.force / p.distance) * tangent_plane, dofs);
      add_translation_pair(c, pattern, pair, p.dashpot * (pairs ? pairs->dashpot[q] : 1.0) * nn, dofs);
    }
    if (fluid) {
      // The squeeze film at the static gap (a contact overlaps: the film between the asperities, at
      // the roughness gap), normal to the pair like the DEM's. It stays linear and keeps its static
      // gap for any drive; see LinearChannel::respond_equivalent.
      const double lubrication = fluid->lubrication_coefficient(
          -p.overlap, grains[static_cast<std::size_t>(p.i)].radius, grains[static_cast<std::size_t>(p.j)].radius);
      if (lubrication > 0.0) add_translation_pair(ct, fixed_pattern, pair, lubrication * nn, dofs);
    }
    if (!friction || !touching) continue;
    // Sticking tangential spring and dashpot on the contact point's tangential displacement.
    const SlipOperators slip = slip_operators(p);
    const dem::TangentialBlock t = *dem::tangential_block(model, p.overlap, grains[static_cast<std::size_t>(p.i)].radius,
                                                          grains[static_cast<std::size_t>(p.j)].radius);
    add_pair(k, pattern, pair, t.stiffness * Eigen::Matrix3d::Identity(), slip.i, slip.j, dofs);
    add_pair(ct, fixed_pattern, pair, t.damping_per_mass * p.effective_mass * Eigen::Matrix3d::Identity(), slip.i,
             slip.j, dofs);
  }
  m.stiffness = pattern.matrix(k.matrix);
  m.dashpots = pattern.matrix(c.matrix);
  m.fixed_dashpots = fixed ? fixed_pattern.matrix(ct.matrix) : Eigen::SparseMatrix<double>(unknowns, unknowns);
  for (std::size_t b = 0; b < static_cast<std::size_t>(n_bodies); ++b) {
    m.bodies.push_back({from_triplets(k.body[b], unknowns, 3), from_triplets(c.body[b], unknowns, 3),
                        from_triplets(ct.body[b], unknowns, 3), k.body_self[b], c.body_self[b],
                        ct.body_self[b]});
  }
  return m;
}

SlipOperators slip_operators(const StaticPair& p) {
  const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
  const Eigen::Matrix3d tangent_plane = Eigen::Matrix3d::Identity() - n * n.transpose();
  SlipOperators s;
  s.i << tangent_plane, p.arm_i * cross_matrix(n);
  s.j << -tangent_plane, p.arm_j * cross_matrix(n);
  return s;
}

std::vector<double> node_heights(std::span<const dem::Grain> grains, const DynamicMatrices& m) {
  std::vector<double> z;
  z.reserve(m.grain_of_node.size());
  for (const std::int32_t g : m.grain_of_node) z.push_back(grains[static_cast<std::size_t>(g)].position.z);
  return z;
}

}  // namespace sedwave::forward::linear
