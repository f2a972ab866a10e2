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
// With friction (a sticking tangential spring kt and dashpot gamma_t per unit m_eff, as the DEM's
// spring_history law) every grain also rotates: 6 unknowns per grain (translation, rotation). A
// sticking contact's tangential displacement at the contact point is
//   d_t = (I - n n^T)(u_i - u_j) + [n]x (arm_i theta_i + arm_j theta_j),
// the spring acts on it (F_t = -kt d_t on i, torque arm_i (F_t x n)), and its dashpot gamma_t m_eff
// goes to a second damping matrix that does not scale with gamma (C_t).
//
// With a pore fluid (dem/fluid.hpp) the viscous forces go to C_t as well, as the time-domain engine
// applies them: every pair closer than the lubrication cut-off h_c (contacts included, at the
// roughness gap) gets the squeeze-film dashpot c_lub n n^T on u_i - u_j, c_lub from the pair's static
// gap (FluidSpec::lubrication_coefficient: Jeffrey & Onishi 1984's singular term, regularised as
// Ball & Melrose 1995), and every free grain's translation the drag c_drag = 6 pi mu r f(eps)
// relative to the fluid at rest (FluidSpec::drag_coefficient: Stokes with the Richardson & Zaki
// 1954 correction). Rigid-body grains get no drag; their lubrication with free grains goes to the
// body couplings as any other pair's.
//
// Units: those of the packing (force/length for K, mass and moment of inertia for M; C1 is
// dimensionless, C_t in force time/length).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cstdint>
#include <span>
#include <vector>

#include "sedwave/forward/dem/fluid.hpp"
#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/channel/contact_network.hpp"

namespace sedwave::forward::linear {

using channel::ContactNetwork;
using channel::StaticPair;

/// Couplings of a rigid body's translation (3 columns) to the free unknowns.
struct BodyCoupling {
  Eigen::SparseMatrix<double> stiffness;
  Eigen::SparseMatrix<double> dashpots;        ///< per unit damping coefficient (scales with gamma)
  Eigen::SparseMatrix<double> fixed_dashpots;  ///< tangential and fluid dashpots (do not scale with gamma)
  /// The body's own translational stiffness and dashpots (its contacts with free grains), for a
  /// body whose translation is an unknown (a wall under a constant force: static_equilibrium.hpp,
  /// and the loaded far wall of a drive, linear_channel.hpp).
  Eigen::Matrix3d self_stiffness = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d self_dashpots = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d self_fixed_dashpots = Eigen::Matrix3d::Zero();
};

struct DynamicMatrices {
  int dofs_per_node = 3;                     ///< 3 (translation) or 6 (translation, rotation)
  std::vector<std::int32_t> grain_of_node;   ///< free grains in ascending z (node n: unknowns dofs n ...)
  std::vector<std::int32_t> node_of_grain;   ///< per packing grain; -1 for grains of rigid bodies
  Eigen::SparseMatrix<double> stiffness;     ///< K, 3n x 3n, symmetric
  Eigen::SparseMatrix<double> dashpots;      ///< C1, symmetric
  /// C_t, symmetric: tangential and fluid dashpots (empty pattern without friction and fluid)
  Eigen::SparseMatrix<double> fixed_dashpots;
  Eigen::VectorXd mass;                      ///< diagonal of M: masses, then moments of inertia 2/5 m r^2
  std::vector<BodyCoupling> bodies;          ///< per rigid body (index body - 1)

  [[nodiscard]] Eigen::Index unknowns() const { return mass.size(); }
};

/// Equivalent linear properties per pair, replacing the tangent ones (equivalent_linearisation.hpp):
/// for every contact and then every gap, in network order, a normal stiffness [force/length] and a
/// factor on the unit dashpot.
struct PairLinearisation {
  std::vector<double> stiffness;
  std::vector<double> dashpot;
};

/// Assembles K, C1, C_t, M and the body couplings of `grains` over `network` for the laws of
/// `contact` (tangential: none or spring_history; rolling resistance and the Coulomb-tanh law are not
/// linearised: std::invalid_argument). `n_bodies` is the number of rigid bodies (Grain::body runs
/// over 1..n_bodies for their grains). Without `pairs`, contacts get their tangent stiffness and a
/// unit dashpot, gaps nothing; with it, each pair gets its own normal stiffness and dashpot factor.
/// With `fluid` (in the packing's units: channel::fluid_in_packing_units) its lubrication and drag
/// dashpots at the static state are added to C_t; the network must then list the gaps up to the
/// fluid's cut-off. Without it the matrices are those of a dry packing.
[[nodiscard]] DynamicMatrices assemble(std::span<const dem::Grain> grains, const ContactNetwork& network,
                                       int n_bodies, const dem::ContactSpec& contact,
                                       const PairLinearisation* pairs = nullptr,
                                       const dem::FluidSpec* fluid = nullptr);

/// The slip of a contact, the relative tangential displacement of its contact point, as
/// i * x_i + j * x_j, x = a grain's (translation, rotation): d_t above. The tangential spring and
/// dashpot act on it (assemble), and it decides whether a contact slides (linear_channel.hpp).
struct SlipOperators {
  Eigen::Matrix<double, 3, 6> i, j;
};
[[nodiscard]] SlipOperators slip_operators(const StaticPair& p);

/// The height z of each node (in node order: ascending), as the slab solver wants them.
[[nodiscard]] std::vector<double> node_heights(std::span<const dem::Grain> grains, const DynamicMatrices& m);

}  // namespace sedwave::forward::linear
