#include "sedwave/forward/linear/dynamic_matrices.hpp"

#include <Eigen/Dense>
#include <algorithm>
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

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& n) {
  Eigen::Matrix3d c;
  c << 0.0, -n.z(), n.y(), n.z(), 0.0, -n.x(), -n.y(), n.x(), 0.0;
  return c;
}

/// Where one pair's forces go: the free unknowns' matrices and each rigid body's couplings.
struct Targets {
  Triplets matrix;
  std::vector<Triplets> body;
  std::vector<Eigen::Matrix3d> body_self;  ///< each body's translation on itself
};

/// Adds the energy 1/2 r^T S r of a relative motion r = A_i x_i + A_j x_j (A: 3 x dofs of each
/// grain, x = its unknowns, or for a rigid-body grain its body's translation) to the matrix.
void add_pair(Targets& t, const Eigen::Matrix3d& s, const Operator& a_i, const Operator& a_j, std::int32_t node_i,
              std::int32_t node_j, int body_i, int body_j, int dofs) {
  const OperatorColumns ai = a_i.leftCols(dofs), aj = a_j.leftCols(dofs);
  const std::pair<const OperatorColumns*, std::int32_t> ends[2] = {{&ai, node_i}, {&aj, node_j}};
  const int bodies[2] = {body_i, body_j};
  for (int r = 0; r < 2; ++r) {
    if (ends[r].second < 0) {
      // A rigid body's grain: only its body's own translation block (pairs inside a body are never
      // listed, so the other end is free).
      t.body_self[static_cast<std::size_t>(bodies[r] - 1)] +=
          ends[r].first->leftCols(3).transpose() * s * ends[r].first->leftCols(3);
      continue;
    }
    const Eigen::Index row = dofs * static_cast<Eigen::Index>(ends[r].second);
    for (int c = 0; c < 2; ++c) {
      if (ends[c].second >= 0) {
        add_block(t.matrix, row, dofs * static_cast<Eigen::Index>(ends[c].second),
                  Block(ends[r].first->transpose() * s * *ends[c].first));
      } else {
        // A rigid body's grain moves with the body's translation (its first three columns).
        add_block(t.body[static_cast<std::size_t>(bodies[c] - 1)], row, 0,
                  Block(ends[r].first->transpose() * s * ends[c].first->leftCols(3)));
      }
    }
  }
}

Eigen::SparseMatrix<double> from_triplets(const Triplets& t, Eigen::Index rows, Eigen::Index cols) {
  Eigen::SparseMatrix<double> m(rows, cols);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

}  // namespace

DynamicMatrices assemble(std::span<const dem::Grain> grains, const ContactNetwork& network, int n_bodies,
                         const dem::ContactSpec& contact, const PairLinearisation* pairs) {
  if (contact.rolling != dem::RollingLawKind::none || contact.tangential == dem::TangentialLawKind::coulomb_tanh) {
    throw std::invalid_argument("linear engine: rolling resistance and the Coulomb-tanh law are not linearised; "
                                "use the time-domain engine");
  }
  const bool friction = contact.tangential == dem::TangentialLawKind::spring_history;
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

  Targets k{{}, std::vector<Triplets>(static_cast<std::size_t>(n_bodies)),
            std::vector<Eigen::Matrix3d>(static_cast<std::size_t>(n_bodies), Eigen::Matrix3d::Zero())};
  Targets c = k, ct = k;
  const std::size_t n_pairs = network.contacts.size() + (pairs ? network.gaps.size() : 0);
  if (pairs && (pairs->stiffness.size() != n_pairs || pairs->dashpot.size() != n_pairs)) {
    throw std::invalid_argument("linear engine: one equivalent stiffness and dashpot per contact and gap needed");
  }
  for (std::size_t q = 0; q < n_pairs; ++q) {
    const bool touching = q < network.contacts.size();
    const StaticPair& p = touching ? network.contacts[q] : network.gaps[q - network.contacts.size()];
    const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
    const Eigen::Matrix3d nn = n * n.transpose(), tangent_plane = Eigen::Matrix3d::Identity() - nn;
    const std::int32_t ni = m.node_of_grain[static_cast<std::size_t>(p.i)];
    const std::int32_t nj = m.node_of_grain[static_cast<std::size_t>(p.j)];
    const int bi = grains[static_cast<std::size_t>(p.i)].body, bj = grains[static_cast<std::size_t>(p.j)].body;
    // Normal law on u_i - u_j: tangent stiffness plus pre-stress, and the normal dashpot.
    Operator translation_i = Operator::Zero(), translation_j = Operator::Zero();
    translation_i.leftCols<3>().setIdentity();
    translation_j.leftCols<3>() = -Eigen::Matrix3d::Identity();
    const double normal_stiffness = pairs ? pairs->stiffness[q] : p.stiffness;
    add_pair(k, normal_stiffness * nn - (p.force / p.distance) * tangent_plane, translation_i, translation_j, ni, nj,
             bi, bj, dofs);
    add_pair(c, p.dashpot * (pairs ? pairs->dashpot[q] : 1.0) * nn, translation_i, translation_j, ni, nj, bi, bj, dofs);
    if (!friction || !touching) continue;
    // Sticking tangential spring and dashpot on the contact point's tangential displacement.
    const SlipOperators slip = slip_operators(p);
    add_pair(k, contact.kt * Eigen::Matrix3d::Identity(), slip.i, slip.j, ni, nj, bi, bj, dofs);
    add_pair(ct, contact.gamma_t * p.effective_mass * Eigen::Matrix3d::Identity(), slip.i, slip.j, ni, nj, bi, bj,
             dofs);
  }
  m.stiffness = from_triplets(k.matrix, unknowns, unknowns);
  m.dashpots = from_triplets(c.matrix, unknowns, unknowns);
  m.fixed_dashpots = from_triplets(ct.matrix, unknowns, unknowns);
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
