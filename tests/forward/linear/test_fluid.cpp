// The pore fluid in the linear engine against closed forms (dem/fluid.hpp):
//  - the assembled dashpots of a hand-built packing: squeeze film 6 pi mu R_eff^2 / max(h, h_r) n n^T
//    between pairs closer than h_c (free-free: four blocks; free-wall: the body coupling), nothing
//    beyond h_c, drag 6 pi mu r f(eps) on every free grain's translations, none on walls;
//  - an ordered chain with fluid: the exact finite-chain solution of the damped lattice,
//    4 (kappa + i omega (gamma + c_lub)) sin^2(q/2) = omega^2 m - i omega c_drag;
//  - a channel refuses a drive with another fluid than its own.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/linear/dynamic_matrices.hpp"
#include "sedwave/forward/linear/linear_channel.hpp"
#include "sedwave/forward/linear/long_wavelength.hpp"
#include "sedwave/forward/linear/ordered_chain.hpp"
#include "linear_test_support.hpp"

namespace sedwave::forward::linear {
namespace {

using Complex = std::complex<double>;

using testing::hooke;

// ---- The assembled dashpots of a hand-built packing ------------------------------------------------

Eigen::Vector3d unit(double x, double y, double z) { return Eigen::Vector3d(x, y, z).normalized(); }

dem::Vec3 vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

dem::Grain grain(double radius, const Eigen::Vector3d& at, int body) {
  dem::Grain g;
  g.radius = radius;
  g.mass = radius * radius * radius;
  g.position = vec(at);
  g.body = body;
  return g;
}

/// Pair (i, j) at `gap` (negative: overlapping) along `normal` (from j to i); grain i is placed there.
StaticPair place_pair(std::vector<dem::Grain>& grains, std::int32_t i, std::int32_t j, const Eigen::Vector3d& normal,
                      double gap) {
  const dem::Grain& gj = grains[static_cast<std::size_t>(j)];
  const double distance = grains[static_cast<std::size_t>(i)].radius + gj.radius + gap;
  const Eigen::Vector3d xj(gj.position.x, gj.position.y, gj.position.z);
  grains[static_cast<std::size_t>(i)].position = vec(xj + distance * normal);
  StaticPair p;
  p.i = i;
  p.j = j;
  p.normal = vec(normal);
  p.distance = distance;
  p.overlap = -gap;
  if (gap < 0.0) {  // Hooke kn = 1
    p.force = -gap;
    p.stiffness = 1.0;
  }
  p.dashpot = 1.0;
  return p;
}

class HandBuiltPacking : public ::testing::Test {
 protected:
  // Free grains 0, 1, 2 and a wall grain 3 (body 1): 0-1 a gap of 0.02 (< h_c), 0-2 one of 0.15
  // (> h_c), 1-3 a contact (overlap 1e-3: lubricated at the roughness gap).
  void SetUp() override {
    grains_ = {grain(0.5, Eigen::Vector3d::Zero(), dem::kFreeBody), grain(0.3, Eigen::Vector3d::Zero(), dem::kFreeBody),
               grain(0.4, Eigen::Vector3d::Zero(), dem::kFreeBody), grain(0.5, Eigen::Vector3d(0.0, 0.0, 2.0), 1)};
    n01_ = unit(0.3, -0.2, 0.9);
    n20_ = unit(-1.0, 0.1, 0.2);
    n13_ = unit(0.1, 0.3, -1.0);
    network_.gaps.push_back(place_pair(grains_, 1, 0, n01_, kGap01));
    network_.gaps.push_back(place_pair(grains_, 2, 0, n20_, 0.15));
    // The wall grain goes where it touches grain 1: i = 1, j = 3, normal from 3 to 1.
    const Eigen::Vector3d x1(grains_[1].position.x, grains_[1].position.y, grains_[1].position.z);
    grains_[3].position = vec(x1 - (0.8 - kOverlap13) * n13_);
    network_.contacts.push_back(place_pair(grains_, 1, 3, n13_, -kOverlap13));
    fluid_.viscosity = 0.3;
    fluid_.roughness = 0.004;
    fluid_.cutoff = 0.1;
    fluid_.drag = dem::DragLaw::richardson_zaki;
    fluid_.porosity = 0.4;
  }

  /// Closed forms of dem/fluid.hpp (Jeffrey & Onishi's squeeze film; Stokes drag with Richardson & Zaki).
  [[nodiscard]] double squeeze_film(double r_i, double r_j, double h) const {
    const double r_eff = r_i * r_j / (r_i + r_j);
    return 6.0 * std::numbers::pi * fluid_.viscosity * r_eff * r_eff / std::max(h, fluid_.roughness);
  }
  [[nodiscard]] double drag(double r) const {
    return 6.0 * std::numbers::pi * fluid_.viscosity * r * std::pow(fluid_.porosity, 1.0 - 4.65);
  }

  static constexpr double kGap01 = 0.02, kOverlap13 = 1e-3;
  std::vector<dem::Grain> grains_;
  ContactNetwork network_;
  Eigen::Vector3d n01_, n20_, n13_;
  dem::FluidSpec fluid_;
};

TEST_F(HandBuiltPacking, FluidDashpotsAreTheClosedForms) {
  const DynamicMatrices m = assemble(grains_, network_, 1, hooke(1.0), nullptr, &fluid_);
  ASSERT_EQ(m.dofs_per_node, 3);
  auto node = [&](int g) { return 3 * static_cast<Eigen::Index>(m.node_of_grain[static_cast<std::size_t>(g)]); };
  const Eigen::Matrix3d nn01 = n01_ * n01_.transpose(), nn13 = n13_ * n13_.transpose();
  const double c01 = squeeze_film(0.5, 0.3, kGap01), c13 = squeeze_film(0.3, 0.5, fluid_.roughness);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(9, 9);
  for (int g = 0; g < 3; ++g) {
    expected.block<3, 3>(node(g), node(g)).diagonal().setConstant(drag(grains_[static_cast<std::size_t>(g)].radius));
  }
  expected.block<3, 3>(node(0), node(0)) += c01 * nn01;
  expected.block<3, 3>(node(1), node(1)) += c01 * nn01 + c13 * nn13;
  expected.block<3, 3>(node(0), node(1)) -= c01 * nn01;
  expected.block<3, 3>(node(1), node(0)) -= c01 * nn01;  // and nothing between 0 and 2 (beyond h_c)
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LT((Eigen::MatrixXd(m.fixed_dashpots) - expected).cwiseAbs().maxCoeff(), 1e-15 * scale);

  // The wall's translation drives grain 1 through the film (u_1 - U_wall) and feels it itself.
  Eigen::MatrixXd coupling = Eigen::MatrixXd::Zero(9, 3);
  coupling.block<3, 3>(node(1), 0) = -c13 * nn13;
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_LT((Eigen::MatrixXd(m.bodies[0].fixed_dashpots) - coupling).cwiseAbs().maxCoeff(), 1e-15 * scale);
  EXPECT_LT((m.bodies[0].self_fixed_dashpots - c13 * nn13).cwiseAbs().maxCoeff(), 1e-15 * scale);

  // The fluid touches nothing else; dry, C_t is empty.
  const DynamicMatrices dry = assemble(grains_, network_, 1, hooke(1.0));
  EXPECT_EQ(dry.fixed_dashpots.nonZeros(), 0);
  EXPECT_EQ(Eigen::MatrixXd(m.stiffness), Eigen::MatrixXd(dry.stiffness));
  EXPECT_EQ(Eigen::MatrixXd(m.dashpots), Eigen::MatrixXd(dry.dashpots));
  EXPECT_EQ(m.mass, dry.mass);
}

TEST_F(HandBuiltPacking, EachFluidForceCanBeSwitchedOff) {
  dem::FluidSpec film = fluid_;
  film.drag = dem::DragLaw::none;
  const DynamicMatrices lubricated = assemble(grains_, network_, 1, hooke(1.0), nullptr, &film);
  auto node = [&](int g) { return 3 * static_cast<Eigen::Index>(lubricated.node_of_grain[static_cast<std::size_t>(g)]); };
  const Eigen::MatrixXd ct = Eigen::MatrixXd(lubricated.fixed_dashpots);
  EXPECT_EQ(ct(node(2), node(2)), 0.0);  // grain 2: no film within h_c, no drag
  EXPECT_GT(ct(node(0), node(0)), 0.0);

  dem::FluidSpec stokes = fluid_;
  stokes.lubrication = false;
  stokes.drag = dem::DragLaw::stokes;
  const DynamicMatrices dragged = assemble(grains_, network_, 1, hooke(1.0), nullptr, &stokes);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(9, 9);
  for (int g = 0; g < 3; ++g) {
    const double r = grains_[static_cast<std::size_t>(g)].radius;
    expected.block<3, 3>(node(g), node(g)).diagonal().setConstant(6.0 * std::numbers::pi * stokes.viscosity * r);
  }
  EXPECT_LT((Eigen::MatrixXd(dragged.fixed_dashpots) - expected).cwiseAbs().maxCoeff(), 1e-15 * expected.maxCoeff());
  EXPECT_EQ(dragged.bodies[0].fixed_dashpots.nonZeros(), 0);  // walls: no drag
}

// ---- An ordered chain in a fluid -------------------------------------------------------------------

/// The fluid in the scenes' dimensionless groups (d = 1, m = 1, kappa = 1 for the unit chain).
dem::FluidSpec chain_fluid() {
  dem::FluidSpec f;
  f.viscosity = 0.01;
  f.roughness = 0.02;
  f.cutoff = 0.1;
  f.drag = dem::DragLaw::stokes;
  return f;
}

channel::DriveSettings frozen_end_drive(double omega_hat, double gamma_hat, const std::optional<dem::FluidSpec>& f) {
  channel::DriveSettings d;
  d.omega_hat = omega_hat;
  d.gamma_hat = gamma_hat;
  d.far_end = channel::FarEnd::absorbing;
  d.absorbing_strength = 0.0;  // no drag: the far wall is a frozen, perfectly reflecting end
  d.fluid = f;
  return d;
}

class FluidChain : public ::testing::TestWithParam<std::pair<double, double>> {};

// Grains 1..n of unit diameter and mass between the driven wall (grain 0, u_0 = 1) and a frozen one
// (u_{n+1} = 0), neighbours overlapping by 1e-3: every neighbour pair carries the squeeze film at the
// roughness gap, c_lub = 6 pi mu (1/4)^2 / h_r, and every grain the drag c_drag = 6 pi mu / 2; next
// neighbours are a diameter apart, beyond h_c. Grain i's equation,
//   (-omega^2 m + i omega c_drag) u_i + (kappa + i omega (gamma + c_lub)) (2 u_i - u_{i-1} - u_{i+1}) = 0,
// is solved by u_i = sin((n + 1 - i) q) / sin((n + 1) q) with
//   4 (kappa + i omega (gamma + c_lub)) sin^2(q / 2) = omega^2 m - i omega c_drag,
// a ratio even in q, so either root serves.
TEST_P(FluidChain, MatchesTheExactDampedLatticeSolution) {
  const auto [omega_hat, gamma_hat] = GetParam();
  const int n = 40;
  const dem::FluidSpec fluid = chain_fluid();
  const LinearChannel engine(ordered_chain(n, 0.999), hooke(1.0), {}, fluid);
  const Eigen::VectorXcd u = engine.displacement(frozen_end_drive(omega_hat, gamma_hat, fluid));
  ASSERT_EQ(engine.matrices().grain_of_node.size(), static_cast<std::size_t>(n));

  const double mu = fluid.viscosity, c_lub = 6.0 * std::numbers::pi * mu * 0.0625 / fluid.roughness;
  const double c_drag = 6.0 * std::numbers::pi * mu * 0.5;
  const Complex s(1.0, omega_hat * (gamma_hat + c_lub));
  const Complex q = 2.0 * std::asin(std::sqrt(Complex(omega_hat * omega_hat, -omega_hat * c_drag) / (4.0 * s)));
  double worst = 0.0, change = 0.0;
  const Eigen::VectorXcd dry = LinearChannel(ordered_chain(n, 0.999), hooke(1.0))
                                   .displacement(frozen_end_drive(omega_hat, gamma_hat, std::nullopt));
  for (int i = 1; i <= n; ++i) {
    const Complex exact = std::sin(static_cast<double>(n + 1 - i) * q) / std::sin(static_cast<double>(n + 1) * q);
    worst = std::max(worst, std::abs(u(3 * (i - 1) + 2) - exact));
    change = std::max(change, std::abs(u(3 * (i - 1) + 2) - dry(3 * (i - 1) + 2)));
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(change, 1e-2);  // premise: the fluid matters
}

INSTANTIATE_TEST_SUITE_P(Frequencies, FluidChain,
                         ::testing::Values(std::pair{0.05, 0.0}, std::pair{0.3, 0.2}, std::pair{1.0, 0.05},
                                           std::pair{1.5, 1.0}));

// The fluid's drag and squeeze films in the lattice's dispersion relation far from the walls: the
// field's two-wave fit recovers q per spacing.
TEST(FluidChainDispersion, TwoWaveFitRecoversTheDampedWavenumber) {
  const int n = 60;
  const double omega_hat = 0.4, gamma_hat = 0.0;
  const dem::FluidSpec fluid = chain_fluid();
  const LinearChannel engine(ordered_chain(n, 0.999), hooke(1.0), {}, fluid);
  const Eigen::VectorXcd u = engine.displacement(frozen_end_drive(omega_hat, gamma_hat, fluid));
  std::vector<Complex> field;
  for (int i = 0; i < n; ++i) field.push_back(u(3 * i + 2));
  const channel::TwoWaveFit waves = channel::fit_two_waves(0.999, field);
  const double mu = fluid.viscosity, c_lub = 6.0 * std::numbers::pi * mu * 0.0625 / fluid.roughness;
  const double c_drag = 3.0 * std::numbers::pi * mu;
  const Complex s(1.0, omega_hat * (gamma_hat + c_lub));
  // The root of exp(-i q i) travelling away from the driven wall and decaying: Re q > 0, Im q < 0.
  Complex q = 2.0 * std::asin(std::sqrt(Complex(omega_hat * omega_hat, -omega_hat * c_drag) / (4.0 * s)));
  if (q.real() < 0.0) q = -q;
  ASSERT_LT(q.imag(), 0.0);
  EXPECT_NEAR(waves.k * 0.999, q.real(), 1e-8);
  EXPECT_NEAR(waves.alpha * 0.999, -q.imag(), 1e-8);
}

// Films that reach further than any contact (a cut-off beyond a diameter joins next neighbours of
// the chain): the slab solver's slabs must be thick enough for them, and it must still equal a
// general sparse LU of the same system.
TEST(FluidChainDispersion, FilmsLongerThanContactsAreSolvedExactly) {
  dem::FluidSpec fluid = chain_fluid();
  fluid.cutoff = 1.5;
  const LinearChannel engine(ordered_chain(30, 0.999), hooke(1.0), {}, fluid);
  const DynamicMatrices& m = engine.matrices();
  const double next_film = 6.0 * std::numbers::pi * fluid.viscosity * 0.0625 / 0.998;
  EXPECT_NEAR(m.fixed_dashpots.coeff(2, 8), -next_film, 1e-12 * next_film);  // grains 1 and 3, along z
  const double omega = 0.6, gamma = 0.1;
  const Eigen::VectorXd none;
  const Eigen::VectorXcd rhs = Eigen::VectorXcd::Random(m.unknowns());
  Eigen::SparseMatrix<Complex> z = m.stiffness.cast<Complex>() + Complex(0.0, omega * gamma) * m.dashpots.cast<Complex>() +
                                   Complex(0.0, omega) * m.fixed_dashpots.cast<Complex>();
  for (Eigen::Index i = 0; i < m.unknowns(); ++i) z.coeffRef(i, i) += -omega * omega * m.mass(i);
  Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(z);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXcd reference = lu.solve(rhs);
  EXPECT_LT((engine.solver().solve(omega, gamma, none, rhs) - reference).norm(), 1e-10 * reference.norm());
}

// ---- Refusals ----------------------------------------------------------------------------------------

TEST(FluidChannel, RefusesADriveWithAnotherFluid) {
  const dem::FluidSpec fluid = chain_fluid();
  const LinearChannel wet(ordered_chain(10, 0.999), hooke(1.0), {}, fluid);
  const LinearChannel dry(ordered_chain(10, 0.999), hooke(1.0));
  EXPECT_EQ(wet.fluid()->viscosity, fluid.viscosity);
  EXPECT_FALSE(dry.fluid().has_value());
  auto refused = [](const LinearChannel& c, const channel::DriveSettings& d) {
    int count = 0;
    for (const std::function<void()>& solve : std::vector<std::function<void()>>{
             [&] { (void)c.displacement(d); }, [&] { (void)c.respond(d); }, [&] { (void)c.respond_equivalent(d); },
             [&] { (void)c.integrate(d, 0.01, 10, 5); }}) {
      try {
        solve();
      } catch (const std::invalid_argument& e) {
        count += std::string(e.what()).find("fluid") != std::string::npos ? 1 : 0;
      }
    }
    return count;
  };
  EXPECT_EQ(refused(wet, frozen_end_drive(0.5, 0.1, std::nullopt)), 4);
  EXPECT_EQ(refused(dry, frozen_end_drive(0.5, 0.1, fluid)), 4);
  EXPECT_EQ(refused(wet, frozen_end_drive(0.5, 0.1, fluid)), 0);
  EXPECT_EQ(refused(dry, frozen_end_drive(0.5, 0.1, std::nullopt)), 0);
  // Any field that differs.
  const std::vector<std::function<void(dem::FluidSpec&)>> changes{
      [](dem::FluidSpec& f) { f.viscosity *= 2.0; },     [](dem::FluidSpec& f) { f.density = 1.0; },
      [](dem::FluidSpec& f) { f.roughness *= 0.5; },     [](dem::FluidSpec& f) { f.cutoff *= 2.0; },
      [](dem::FluidSpec& f) { f.lubrication = false; }, [](dem::FluidSpec& f) { f.drag = dem::DragLaw::none; },
      [](dem::FluidSpec& f) { f.porosity = 0.3; }};
  for (std::size_t k = 0; k < changes.size(); ++k) {
    dem::FluidSpec other = fluid;
    changes[k](other);
    EXPECT_EQ(refused(wet, frozen_end_drive(0.5, 0.1, other)), 4) << "change " << k;
  }
  // An unusable fluid, and the long-wavelength limit (whose dashpots must all scale with gamma).
  dem::FluidSpec bad = fluid;
  bad.cutoff = 0.5 * bad.roughness;
  EXPECT_THROW((void)LinearChannel(ordered_chain(10, 0.999), hooke(1.0), {}, bad), std::invalid_argument);
  EXPECT_THROW((void)long_wavelength_limit(wet, 0.1, channel::DriveAxis::longitudinal), std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::forward::linear
