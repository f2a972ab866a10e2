#include "sedwave/forward/linear/dynamic_matrices.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace sedwave::forward::linear {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

void add_block(Triplets& t, Eigen::Index row, Eigen::Index col, const Eigen::Matrix3d& block, double sign) {
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) t.emplace_back(row + a, col + b, sign * block(a, b));
  }
}

}  // namespace

DynamicMatrices assemble(std::span<const dem::Grain> grains, const ContactNetwork& network, int n_bodies,
                         const PairLinearisation* pairs) {
  DynamicMatrices m;
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
  const auto unknowns = static_cast<Eigen::Index>(3 * m.grain_of_node.size());
  m.mass.resize(unknowns);
  for (std::size_t n = 0; n < m.grain_of_node.size(); ++n) {
    m.mass.segment<3>(static_cast<Eigen::Index>(3 * n)).setConstant(grains[static_cast<std::size_t>(m.grain_of_node[n])].mass);
  }

  Triplets k, c;
  std::vector<Triplets> kb(static_cast<std::size_t>(n_bodies)), cb(static_cast<std::size_t>(n_bodies));
  const std::size_t n_pairs = network.contacts.size() + (pairs ? network.gaps.size() : 0);
  if (pairs && (pairs->stiffness.size() != n_pairs || pairs->dashpot.size() != n_pairs)) {
    throw std::invalid_argument("linear engine: one equivalent stiffness and dashpot per contact and gap needed");
  }
  for (std::size_t q = 0; q < n_pairs; ++q) {
    const bool contact = q < network.contacts.size();
    const StaticPair& p = contact ? network.contacts[q] : network.gaps[q - network.contacts.size()];
    const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
    const double normal_stiffness = pairs ? pairs->stiffness[q] : p.stiffness;
    const Eigen::Matrix3d dashpot = p.dashpot * (pairs ? pairs->dashpot[q] : 1.0) * n * n.transpose();
    const Eigen::Matrix3d unit_nn = n * n.transpose();
    const Eigen::Matrix3d stiffness =
        normal_stiffness * unit_nn - (p.force / p.distance) * (Eigen::Matrix3d::Identity() - unit_nn);
    const std::int32_t ni = m.node_of_grain[static_cast<std::size_t>(p.i)];
    const std::int32_t nj = m.node_of_grain[static_cast<std::size_t>(p.j)];
    for (const auto& [node, other] : {std::pair{ni, nj}, std::pair{nj, ni}}) {
      if (node < 0) continue;
      const Eigen::Index row = 3 * static_cast<Eigen::Index>(node);
      add_block(k, row, row, stiffness, 1.0);
      add_block(c, row, row, dashpot, 1.0);
      if (other >= 0) {
        add_block(k, row, 3 * static_cast<Eigen::Index>(other), stiffness, -1.0);
        add_block(c, row, 3 * static_cast<Eigen::Index>(other), dashpot, -1.0);
      } else {
        const std::int32_t other_grain = node == ni ? p.j : p.i;
        const auto body = static_cast<std::size_t>(grains[static_cast<std::size_t>(other_grain)].body - 1);
        add_block(kb[body], row, 0, stiffness, -1.0);
        add_block(cb[body], row, 0, dashpot, -1.0);
      }
    }
  }
  m.stiffness.resize(unknowns, unknowns);
  m.stiffness.setFromTriplets(k.begin(), k.end());
  m.dashpots.resize(unknowns, unknowns);
  m.dashpots.setFromTriplets(c.begin(), c.end());
  for (std::size_t b = 0; b < kb.size(); ++b) {
    m.body_stiffness.emplace_back(unknowns, 3);
    m.body_stiffness.back().setFromTriplets(kb[b].begin(), kb[b].end());
    m.body_dashpots.emplace_back(unknowns, 3);
    m.body_dashpots.back().setFromTriplets(cb[b].begin(), cb[b].end());
  }
  return m;
}

}  // namespace sedwave::forward::linear
