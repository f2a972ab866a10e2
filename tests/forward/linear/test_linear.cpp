// The linear-response engine against closed forms and against the DEM engine itself:
//  - an ordered chain: the exact finite-chain solution at every grain, and the lattice theory's
//    complex wavenumber from the field, to 1e-10;
//  - a prepared 3D packing: K and C1 equal finite-difference Jacobians of the DEM engine's forces;
//    the slab solver equals a general sparse LU; the power the wall injects equals the power the
//    dashpots and the absorbing layer dissipate (energy balance of the steady state).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <optional>
#include <complex>
#include <iostream>
#include <memory>
#include <numbers>
#include <tuple>
#include <unordered_map>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/linear/equivalent_linearisation.hpp"
#include "sedwave/forward/linear/linear_channel.hpp"
#include "sedwave/forward/linear/long_wavelength.hpp"
#include "sedwave/forward/linear/ordered_chain.hpp"
#include "linear_test_support.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/linear/newton_stage.hpp"

namespace sedwave::forward::linear {
namespace {

using Complex = std::complex<double>;

using testing::hooke;

// ---- Ordered chain ----------------------------------------------------------------------------------

channel::PreparedChannel chain(int n, double spacing) { return ordered_chain(n, spacing); }

channel::DriveSettings frozen_end_drive(double omega_hat, double gamma_hat) {
  channel::DriveSettings d;
  d.omega_hat = omega_hat;
  d.gamma_hat = gamma_hat;
  d.far_end = channel::FarEnd::absorbing;
  d.absorbing_strength = 0.0;  // no drag: the far wall is a frozen, perfectly reflecting end
  return d;
}

class OrderedChain : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(OrderedChain, MatchesTheExactLatticeSolution) {
  const auto [omega_hat, gamma_hat] = GetParam();
  const int n = 40;
  const double spacing = 1.0 - 1e-3;
  const LinearChannel engine(chain(n, spacing), hooke(1.0));
  const Eigen::VectorXcd u = engine.displacement(frozen_end_drive(omega_hat, gamma_hat));

  // Grain i of the chain (wall = 0, far wall = n + 1): u_i = sin((n + 1 - i) q) / sin((n + 1) q) with
  // 4 (kappa + i omega gamma) sin^2(q/2) = omega^2 m, i.e. the lattice theory's k~ under our
  // exp(+i omega t) convention: q = conj(k~).
  const Complex q = std::conj(lattice_wavenumber(omega_hat, gamma_hat).k);
  ASSERT_EQ(engine.matrices().grain_of_node.size(), static_cast<std::size_t>(n));
  double worst = 0.0;
  for (int i = 1; i <= n; ++i) {
    const Complex exact = std::sin(static_cast<double>(n + 1 - i) * q) / std::sin(static_cast<double>(n + 1) * q);
    worst = std::max(worst, std::abs(u(3 * (i - 1) + 2) - exact));
    EXPECT_EQ(u(3 * (i - 1)), Complex(0.0));  // a longitudinal drive moves nothing sideways
  }
  EXPECT_LT(worst, 1e-10);

  // The two-wave fit of the grain field recovers the lattice wavenumber (per spacing) and the
  // reflection: total at the frozen wall, one spacing beyond the last grain.
  std::vector<Complex> field;
  for (int i = 0; i < n; ++i) field.push_back(u(3 * i + 2));
  const channel::TwoWaveFit waves = channel::fit_two_waves(spacing, field);
  const ComplexWavenumber exact = lattice_wavenumber(omega_hat, gamma_hat);
  EXPECT_NEAR(waves.k * spacing, exact.k.real(), 1e-10);
  EXPECT_NEAR(waves.alpha * spacing, exact.k.imag(), 1e-10);
  EXPECT_NEAR(waves.reflection / std::exp(-2.0 * exact.k.imag()), 1.0, 1e-5);
}

// A loaded far wall (mass M, free along z under its static load) instead of a frozen one: grains
// 0 (driven wall) .. n + 1 (loaded wall) carry u_i = a e^{-iqi} + b e^{iqi} (the same lattice waves),
// with u_0 = 1 and the wall's own equation -omega^2 M u_{n+1} = s (u_n - u_{n+1}), s = kappa + i omega
// gamma. The wall is the linear engine's extra unknown; a very heavy one is the frozen end.
TEST_P(OrderedChain, WithALoadedFarWallMatchesTheExactLatticeSolution) {
  const auto [omega_hat, gamma_hat] = GetParam();
  const int n = 40;
  const LinearChannel engine(chain(n, 1.0 - 1e-3), hooke(1.0));
  channel::DriveSettings d = frozen_end_drive(omega_hat, gamma_hat);
  d.far_wall = channel::FarWall::loaded;
  d.far_wall_mass = 3.0;
  const Eigen::VectorXcd u = engine.displacement(d);
  ASSERT_EQ(u.size(), 3 * n + 1);

  const Complex q = std::conj(lattice_wavenumber(omega_hat, gamma_hat).k);
  const Complex s(1.0, omega_hat * gamma_hat), wall = s - omega_hat * omega_hat * d.far_wall_mass;
  auto wave = [](Complex sign_q, int i) { return std::exp(Complex(0.0, -1.0) * sign_q * static_cast<double>(i)); };
  const Complex p = wall * wave(q, n + 1) - s * wave(q, n), r = wall * wave(-q, n + 1) - s * wave(-q, n);
  const Complex a = r / (r - p), b = -p / (r - p);
  double worst = 0.0;
  for (int i = 1; i <= n; ++i) worst = std::max(worst, std::abs(u(3 * (i - 1) + 2) - (a * wave(q, i) + b * wave(-q, i))));
  const Complex exact_wall = a * wave(q, n + 1) + b * wave(-q, n + 1);
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(std::abs(u(3 * n) - exact_wall), 1e-10);
  EXPECT_GT(std::abs(exact_wall), 0.1 * std::abs(u(3 * (n - 1) + 2)));  // premise: the wall moves with the wave

  // Its grain moves with it, and a very heavy wall is the frozen end.
  EXPECT_EQ(engine.grain_motion(u, d, n + 1)(2), u(3 * n));
  d.far_wall_mass = 1e14;
  const Eigen::VectorXcd heavy = engine.displacement(d);
  const Eigen::VectorXcd frozen = engine.displacement(frozen_end_drive(omega_hat, gamma_hat));
  EXPECT_LT((heavy.head(3 * n) - frozen).norm(), 1e-9 * frozen.norm());
}

TEST(OrderedChainSponge, AbsorbingLayerOfTwoWavelengthsReflectsUnderOnePercent) {
  // Undamped chain: every bit of the backward wave comes from the absorbing layer, and the field
  // before it is exactly two lattice waves, so the two-wave fit measures the layer's reflection.
  const int n = 400;
  const LinearChannel engine(chain(n, 0.999), hooke(1.0));
  channel::DriveSettings d = frozen_end_drive(0.5, 0.0);
  d.absorbing_strength = 1.0;
  d.absorbing_fraction = 0.25;  // 100 grains, about 8 wavelengths at omega_hat = 0.5
  const Eigen::VectorXcd u = engine.displacement(d);
  std::vector<Complex> field;
  for (int i = 0; i < 250; ++i) field.push_back(u(3 * i + 2));
  const channel::TwoWaveFit waves = channel::fit_two_waves(0.999, field);
  EXPECT_LT(waves.reflection, 0.01);
  EXPECT_NEAR(waves.k * 0.999, lattice_wavenumber(0.5, 0.0).k.real(), 1e-9);
}

TEST(OrderedChainSponge, LayersTheResolutionRuleAcceptsReflectUnderOnePercent) {
  // The rule of resolution_problem against the exact chain: layers from a quarter to 2.5
  // wavelengths, from undamped to overdamped contacts. Every layer the rule accepts reflects < 1 %,
  // and the rule does accept the short layers of strongly damped media (it is not just "2.5 lambda").
  int accepted_below_rule = 0;
  for (const auto& [omega_hat, gamma_hat] :
       {std::pair{0.01, 100.0}, std::pair{0.05, 10.0}, std::pair{0.1, 1.0}, std::pair{0.5, 0.0}}) {
    const ComplexWavenumber exact = lattice_wavenumber(omega_hat, gamma_hat);
    const double spacing = 0.999;
    const double wavelength = 2.0 * std::numbers::pi / exact.k.real() * spacing;
    for (const double layers : {0.25, 0.5, 1.0, 1.5, 2.5}) {
      const int n_layer = static_cast<int>(layers * wavelength / spacing) + 1;
      const int n = n_layer + std::max(200, static_cast<int>(wavelength / spacing));
      const LinearChannel engine(chain(n, spacing), hooke(1.0));
      channel::DriveSettings d = frozen_end_drive(omega_hat, gamma_hat);
      d.absorbing_strength = 1.0;
      d.absorbing_fraction = static_cast<double>(n_layer) / (n + 1);  // of the column, wall to wall
      const Eigen::VectorXcd u = engine.displacement(d);
      std::vector<Complex> field;
      for (int i = 20; i < n - n_layer; ++i) field.push_back(u(3 * i + 2));
      const double k = exact.k.real() / spacing, alpha = exact.k.imag() / spacing;
      const channel::TwoWaveFit waves = channel::fit_two_waves(spacing, field, k, alpha);
      channel::PropagationFit fit;
      fit.k = k;
      fit.alpha = alpha;
      const double layer_length = n_layer * spacing;
      if (!channel::resolution_problem(fit, 10.0 * wavelength, layer_length).empty()) continue;
      EXPECT_LT(waves.reflection, 0.01) << "omega_hat " << omega_hat << ", gamma_hat " << gamma_hat << ", layer of "
                                        << layers << " wavelengths";
      if (layers < channel::kAbsorbingWavelengths) ++accepted_below_rule;
    }
  }
  EXPECT_GE(accepted_below_rule, 2);  // gamma_hat 100: layers of 1 and 1.5 wavelengths
}

// The long-wavelength limit of an ordered chain (spacing a) is the 1D continuum theory:
// c_complex = a sqrt(1 + i x) in units d sqrt(kappa/m), whatever the wall contacts do, because the
// strain is measured away from them. The density divides the mass by the column between the walls'
// surfaces, (n + 1) a - 1 rather than n a: 2.5e-5 more here, hence the tolerance.
TEST(LongWavelength, OrderedChainIsTheContinuumTheory) {
  const double a = 1.0 - 1e-3;
  const LinearChannel engine(chain(40, a), hooke(1.0));
  const ContinuumModel continuum;
  for (const double x : {0.0, 0.01, 0.3, 1.0, 10.0, 1e3}) {
    const LongWavelengthLimit l = long_wavelength_limit(engine, x, channel::DriveAxis::longitudinal);
    EXPECT_NEAR(std::abs(l.modulus / l.density / (a * a * Complex(1.0, x)) - 1.0), 0.0, 3e-5) << "x = " << x;
    // The continuum theory (spacing d) at any omega_hat with gamma_hat = x / omega_hat.
    const double w = 1e-4;
    const DispersionPoint p = continuum.evaluate(w, x / w);
    EXPECT_NEAR(l.c_hat / a, p.c_hat, 3e-5 * p.c_hat) << "x = " << x;
    EXPECT_NEAR(l.alpha_over_omega * a, p.alpha_hat / w, 3e-5 * p.alpha_hat / w + 1e-12) << "x = " << x;
    EXPECT_LT(l.non_affinity, 1e-6);
  }
  EXPECT_THROW((void)long_wavelength_limit(engine, -1.0, channel::DriveAxis::longitudinal), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Frequencies, OrderedChain,
                         ::testing::Values(std::pair{0.05, 0.0}, std::pair{0.3, 0.2}, std::pair{1.0, 0.05},
                                           std::pair{1.5, 1.0}, std::pair{0.01, 100.0}));

// ---- A prepared 3D packing ------------------------------------------------------------------------

class Packing : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    channel::ChannelGeometry g;
    g.n_grains = 200;
    g.seed = 7;
    channel::PreparationSettings p;
    p.pressure = 10.0;
    packing_ = std::make_unique<channel::PreparedChannel>(
        channel::prepare_channel(MPI_COMM_SELF, channel::generate_channel(g), hooke(kKn), g.width, p,
            forward::linear::newton_stage()));
  }
  static void TearDownTestSuite() { packing_.reset(); }
  static constexpr double kKn = 726.0;
  /// Hooke with sticking tangential springs and Coulomb friction (as LAMMPS gran/hooke/history).
  static dem::ContactSpec frictional_hooke() {
    dem::ContactSpec c = hooke(kKn);
    c.tangential = "spring_history";
    c["kt"] = 2.0 / 7.0 * kKn;
    c["gamma_t"] = 5.0;
    c["friction"] = 0.5;
    return c;
  }
  static std::unique_ptr<channel::PreparedChannel> packing_;
};
std::unique_ptr<channel::PreparedChannel> Packing::packing_;

/// The DEM's forces on the linear engine's nodes (walls frozen), with grains moved in place: the
/// finite-difference steps lie far below the Verlet skin, so the neighbour list built at rest stays
/// valid, and no list is built again and no engine set up again between evaluations. Periodic
/// ghosts read their source grain's position and velocity, so they follow the moved grain.
class DemForces {
 public:
  DemForces(const channel::PreparedChannel& p, const dem::ContactSpec& contact)
      : engine_(MPI_COMM_SELF, settings(p, contact), p.grains,
                {dem::RigidBody("lower", dem::Frozen{}), dem::RigidBody("upper", dem::Frozen{})}) {
    const dem::GrainArrays& g = engine_.grains();
    for (std::size_t i = 0; i < engine_.n_local(); ++i) index_of_[g.id[i]] = i;
  }

  double& position(std::int64_t id, int axis) { return engine_.grains().position[index_of_.at(id)][axis]; }
  double& velocity(std::int64_t id, int axis) { return engine_.grains().velocity[index_of_.at(id)][axis]; }

  /// Forces on the nodes of `m` (node n is grain m.grain_of_node[n] of `grains`).
  Eigen::VectorXd at_nodes(const std::vector<dem::Grain>& grains, const DynamicMatrices& m) {
    engine_.compute_forces();
    const dem::GrainArrays& g = engine_.grains();
    Eigen::VectorXd f(m.unknowns());
    for (std::size_t n = 0; n < m.grain_of_node.size(); ++n) {
      const std::int64_t id = grains[static_cast<std::size_t>(m.grain_of_node[n])].id;
      const std::size_t i = index_of_.at(id);
      // A rebuild would have reordered the grains and invalidated the in-place moves.
      EXPECT_EQ(g.id[i], id) << "the engine rebuilt its list during a finite-difference step";
      const dem::Vec3 v = g.force[i];
      f.segment<3>(static_cast<Eigen::Index>(3 * n)) << v.x, v.y, v.z;
    }
    return f;
  }

 private:
  static dem::EngineSettings settings(const channel::PreparedChannel& p, const dem::ContactSpec& contact) {
    dem::EngineSettings s;
    s.box = p.box;
    s.contact = contact;
    return s;
  }
  dem::Engine engine_;
  std::unordered_map<std::int64_t, std::size_t> index_of_;
};

/// Largest deviations of K and C1 from finite-difference Jacobians of the DEM forces, relative to
/// the largest entries of K and C1. `damped` carries a damping coefficient `coefficient`.
std::pair<double, double> jacobian_errors(const channel::PreparedChannel& packing, const dem::ContactSpec& elastic,
                                          const dem::ContactSpec& damped, double coefficient) {
  const LinearChannel engine(packing, elastic);
  const DynamicMatrices& m = engine.matrices();
  const Eigen::MatrixXd k = Eigen::MatrixXd(m.stiffness);
  const Eigen::MatrixXd c = Eigen::MatrixXd(m.dashpots);
  // Steps far below the smallest overlap and gap, so no contact changes state.
  double smallest = 1.0;
  for (const StaticPair& p : engine.network().contacts) smallest = std::min(smallest, p.overlap);
  for (const StaticPair& p : engine.network().gaps) smallest = std::min(smallest, -p.overlap);
  const double h = std::min(1e-7, 0.01 * smallest);
  double worst_k = 0.0, worst_c = 0.0;
  DemForces elastic_forces(packing, elastic), damped_forces(packing, damped);
  const Eigen::VectorXd at_rest = damped_forces.at_nodes(packing.grains, m);
  for (Eigen::Index col = 0; col < m.unknowns(); ++col) {
    const std::int64_t id = packing.grains[static_cast<std::size_t>(m.grain_of_node[static_cast<std::size_t>(col / 3)])].id;
    const int axis = static_cast<int>(col % 3);
    double& x = elastic_forces.position(id, axis);
    const double x0 = x;
    x = x0 + h;
    const Eigen::VectorXd plus = elastic_forces.at_nodes(packing.grains, m);
    x = x0 - h;
    const Eigen::VectorXd minus = elastic_forces.at_nodes(packing.grains, m);
    x = x0;
    worst_k = std::max(worst_k, ((plus - minus) / (2.0 * h) + k.col(col)).cwiseAbs().maxCoeff());
    // The dashpot force is linear in the velocity: a one-sided difference is exact.
    damped_forces.velocity(id, axis) = 1.0;
    const Eigen::VectorXd moving = damped_forces.at_nodes(packing.grains, m);
    damped_forces.velocity(id, axis) = 0.0;
    worst_c = std::max(worst_c, ((moving - at_rest) / coefficient + c.col(col)).cwiseAbs().maxCoeff());
  }
  return {worst_k / k.cwiseAbs().maxCoeff(), worst_c / c.cwiseAbs().maxCoeff()};
}

TEST_F(Packing, StiffnessAndDashpotsAreTheJacobiansOfTheDemForces) {
  ASSERT_TRUE(packing_->report.converged);
  dem::ContactSpec damped = hooke(kKn);
  damped.erase("restitution");
  damped["gamma"] = 3.0;  // a constant dashpot, as the driven runs use
  const auto [k_error, c_error] = jacobian_errors(*packing_, hooke(kKn), damped, 3.0);
  EXPECT_LT(k_error, 1e-6);
  EXPECT_LT(c_error, 1e-9);
}

/// Largest difference between two sets of layer records, and the largest value of the first.
std::pair<double, double> record_difference(const std::vector<std::vector<double>>& a,
                                            const std::vector<std::vector<double>>& b) {
  double peak = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t s = 0; s < a[k].size() && s < b[k].size(); ++s) {
      peak = std::max(peak, std::abs(a[k][s]));
      worst = std::max(worst, std::abs(a[k][s] - b[k][s]));
    }
  }
  return {worst, peak};
}

/// A short driven run at a tiny amplitude, for comparing trajectories of the two engines.
channel::DriveSettings tiny_drive() {
  channel::DriveSettings d;
  d.omega_hat = 0.8;
  d.gamma_hat = 0.2;
  d.amplitude = 1e-6;
  d.periods = 4.0;
  d.far_end = channel::FarEnd::absorbing;
  return d;
}

class HertzPacking : public ::testing::Test {
 protected:
  static dem::ContactSpec hertz() {
    dem::ContactSpec c;
    c.normal = "hertz";
    c["effective_modulus"] = 5e4;
    c["restitution"] = 0.9;
    return c;
  }
  /// The first packing (seeds 9, 10, ...) with no pair within 1e-5 d of touching (every contact
  /// overlaps by more, every gap is wider) and none that the tiny drive opens or closes. A relaxed frictionless packing can hold contacts at the
  /// very edge of opening (about one packing in two here has one below 1e-8 d), and gaps at the
  /// edge of closing; those clap at any drive amplitude, so comparisons that assume nothing claps
  /// must start from a packing without them. Which seed qualifies depends on the preparation's
  /// round-off, so the fixture searches instead of naming one; it starts at the first seed that
  /// qualified when it was written (seed 8 holds a pair that claps), as each try is a preparation.
  static void SetUpTestSuite() {
    channel::ChannelGeometry g;
    g.n_grains = 150;
    for (g.seed = 9; g.seed < 17; ++g.seed) {
      packing_ = std::make_unique<channel::PreparedChannel>(channel::prepare_channel(
          MPI_COMM_SELF, channel::generate_channel(g), hertz(), g.width, channel::PreparationSettings{},
              forward::linear::newton_stage()));
      if (smallest_overlap(*packing_) > kSmallestOverlap && !claps_under_tiny_drive(*packing_)) return;
    }
  }
  /// Whether the steady response to tiny_drive(), at 3x its amplitude (a drive started from rest
  /// overshoots), opens or closes any pair. Relative motions can exceed the wall's: in one
  /// preparation with every pair 8e-5 d from clapping, the DEM and the linear equations parted by
  /// 1.4e-2 of the peak at A = 1e-6 d and by 8e-5 at 1e-7 d.
  static bool claps_under_tiny_drive(const channel::PreparedChannel& p) {
    const LinearChannel engine(p, hertz());
    const channel::DriveSettings d = tiny_drive();
    const StateChanges s = engine.state_changes(engine.displacement(d), d, 3.0 * d.amplitude);
    return s.opening + s.closing > 0;
  }
  static void TearDownTestSuite() { packing_.reset(); }
  static constexpr double kSmallestOverlap = 1e-5;
  /// How close the packing's nearest pair is to clapping [d]: the smallest |overlap| of its
  /// contacts and of its gaps narrower than kSmallestOverlap.
  static double smallest_overlap(const channel::PreparedChannel& p) {
    double smallest = INFINITY;
    for (const StaticPair& c : channel::find_contacts(p.grains, p.box, hertz(), kSmallestOverlap).contacts) {
      smallest = std::min(smallest, std::abs(c.overlap));
    }
    return smallest;
  }
  static std::unique_ptr<channel::PreparedChannel> packing_;
};
std::unique_ptr<channel::PreparedChannel> HertzPacking::packing_;


TEST_F(HertzPacking, StiffnessAndDashpotsAreTheJacobiansOfTheDemForces) {
  ASSERT_TRUE(packing_->report.converged);
  dem::ContactSpec elastic = hertz(), damped = hertz();
  elastic.erase("restitution");
  damped.erase("restitution");
  damped["gamma"] = 0.7;  // Tsuji alpha
  ASSERT_GT(smallest_overlap(*packing_), kSmallestOverlap);  // premise: no contact at the edge of opening
  const auto [k_error, c_error] = jacobian_errors(*packing_, elastic, damped, 0.7);
  // Hertz is curved (F ~ delta^1.5): the central difference is good to O(h^2 / delta^2).
  EXPECT_LT(k_error, 1e-5);
  EXPECT_LT(c_error, 1e-9);
}

TEST_F(HertzPacking, IntegratedLinearEquationsFollowTheDemAtTinyAmplitude) {
  ASSERT_GT(smallest_overlap(*packing_), 10 * tiny_drive().amplitude);  // premise: nothing claps
  // The driven DEM run (Hertz: kappa = mean tangent stiffness, Tsuji dashpot) and the linearised
  // equations integrated with the same scheme and time step. At A = 1e-6 d the records differ by the
  // nonlinearity, O(A / overlap), and an absolute floor of ~1e-10 d (round-off and the prepared
  // packing's 1e-9 residual forces). How far above that depends on the preparation, whose round-off
  // picks the packing: 1.2e-4, 6.7e-4 and 5.4e-4 of the peak on three preparations chosen by the
  // overlap premise alone; 1.2e-4 and 1.4e-4 on two chosen also by the clapping premise (a third,
  // which it rejected, read 1.4e-2). A wrong K, C or drive would be O(1).
  const channel::DriveSettings d = tiny_drive();
  const channel::AcousticResult dem = channel::run_acoustic(MPI_COMM_SELF, *packing_, hertz(), d);
  const LinearChannel engine(*packing_, hertz());
  EXPECT_NEAR(dem.kappa, engine.network().mean_stiffness, 1e-12 * dem.kappa);
  const auto per_sample = static_cast<std::int64_t>(std::llround(dem.sample_dt / dem.time_step));
  const auto lin = engine.integrate(d, dem.time_step, dem.steps, per_sample);
  ASSERT_EQ(lin.size(), dem.displacement.size());
  const auto [worst, peak] = record_difference(dem.displacement, lin);
  std::cout << "Hertz, A = 1e-6 d: largest difference / peak = " << worst / peak << " (smallest overlap "
            << smallest_overlap(*packing_) << " d)\n";
  EXPECT_GT(peak, 0.1 * d.amplitude);
  EXPECT_LT(worst, 2e-3 * peak);
}

TEST_F(Packing, FrictionalContactsRotateAndFollowTheDem) {
  // Sticking tangential springs (spring_history, as LAMMPS gran/hooke/history) and rotations:
  // 6 unknowns per grain. The driven DEM with friction and the linearised equations, integrated
  // alike, agree at a tiny amplitude (no contact slides: 1.0e-6 of the peak at A = 1e-6 d), and
  // friction changes the response (by 0.50 of the peak). Both see the wall with its mean velocity
  // over each step; with its end-of-step velocity (LAMMPS fix move) the DEM's tangential spring
  // histories led the wall's path by half a step, and the records differed by 1e-3 (9e-3 driven
  // transversely).
  const dem::ContactSpec frictional = frictional_hooke();
  const channel::DriveSettings d = tiny_drive();
  const channel::AcousticResult dem = channel::run_acoustic(MPI_COMM_SELF, *packing_, frictional, d);
  const LinearChannel engine(*packing_, frictional);
  ASSERT_EQ(engine.matrices().dofs_per_node, 6);
  const auto per_sample = static_cast<std::int64_t>(std::llround(dem.sample_dt / dem.time_step));
  const auto [worst, peak] = record_difference(dem.displacement, engine.integrate(d, dem.time_step, dem.steps, per_sample));
  const channel::AcousticResult frictionless = channel::run_acoustic(MPI_COMM_SELF, *packing_, hooke(kKn), d);
  const auto [effect, unused] = record_difference(dem.displacement, frictionless.displacement);
  std::cout << "friction: linear vs DEM " << worst / peak << " of the peak; friction changes the records by "
            << effect / peak << "\n";
  EXPECT_LT(worst, 1e-4 * peak);
  EXPECT_GT(effect, 50.0 * worst);
}

// The far wall free along z under its static load (dem::ConstantForce in the DEM, one more unknown
// in the linear engine), with friction so that the wall's tangential springs and dashpots count
// too. Without drag in the absorbing layer the wave reaches the wall and comes back within the run.
TEST_F(Packing, LoadedFarWallFollowsTheDem) {
  const dem::ContactSpec frictional = frictional_hooke();
  channel::DriveSettings d = tiny_drive();
  d.periods = 10.0;
  d.absorbing_strength = 0.0;
  d.far_wall = channel::FarWall::loaded;
  d.far_wall_mass = 2.0;
  const channel::AcousticResult dem = channel::run_acoustic(MPI_COMM_SELF, *packing_, frictional, d);
  const LinearChannel engine(*packing_, frictional);
  const auto per_sample = static_cast<std::int64_t>(std::llround(dem.sample_dt / dem.time_step));
  const auto [worst, peak] = record_difference(dem.displacement, engine.integrate(d, dem.time_step, dem.steps, per_sample));
  channel::DriveSettings frozen = d;
  frozen.far_wall = channel::FarWall::frozen;
  const auto [effect, unused] =
      record_difference(dem.displacement, channel::run_acoustic(MPI_COMM_SELF, *packing_, frictional, frozen).displacement);
  std::cout << "loaded far wall: linear vs DEM " << worst / peak << " of the peak; loading the wall changes the records by "
            << effect / peak << "\n";
  EXPECT_LT(worst, 1e-4 * peak);
  EXPECT_GT(effect, 50.0 * worst);
}

// Sliding: the linear engine counts the contacts whose tangential force (spring and dashpot) would
// reach mu times the normal force during the cycle. Checked against the frictional DEM run twice,
// with mu and with a mu no force reaches: the two runs are identical until some contact hits its
// Coulomb limit. A transverse drive shears the contacts, and a small mu (0.01) makes them slide
// well before any gap closes (a closing gap makes a contact with no normal force, which slides at
// once; the premise below checks it). The DEM run (4 periods from rest) first slides near where
// the steady-state count says: not below half of it (a drive started from rest beats with the free
// response, so a contact's start-up force can exceed its steady amplitude, up to twice), and by
// 1.25x.
TEST_F(Packing, PredictedSlidingOnsetIsWhereTheDemFirstSlides) {
  dem::ContactSpec frictional = frictional_hooke();
  frictional["friction"] = 0.01;
  dem::ContactSpec sticking = frictional;
  sticking["friction"] = 1e9;
  channel::DriveSettings d = tiny_drive();
  d.axis = channel::DriveAxis::transverse;
  const LinearChannel engine(*packing_, frictional);
  const Eigen::VectorXcd u = engine.displacement(d);
  double low = 1e-12, high = 1.0;  // the first sliding contact: bisection in log A
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(low * high);
    (engine.state_changes(u, d, mid).sliding > 0 ? high : low) = mid;
  }
  const double onset = high;
  ASSERT_EQ(engine.state_changes(u, d, 1.25 * onset).closing, 0);  // premise: nothing but sliding
  auto slip_effect = [&](double amplitude) {  // how much the Coulomb limit changes the run
    channel::DriveSettings a = d;
    a.amplitude = amplitude;
    const auto [worst, peak] = record_difference(channel::run_acoustic(MPI_COMM_SELF, *packing_, frictional, a).displacement,
                                                 channel::run_acoustic(MPI_COMM_SELF, *packing_, sticking, a).displacement);
    return worst / peak;
  };
  // Measured on two preparations of this packing (they differ by the DEM's round-off): identical at
  // 0.8x the predicted onset, 5e-4 of the peak apart at 1x, 3.6e-3 at 1.25x; identical up to 0.6x,
  // 1.1e-3 apart at 0.7x, 1.1e-2 at 1.25x (start-up overshoot).
  const double below = slip_effect(0.5 * onset), above = slip_effect(1.25 * onset);
  std::cout << "first contact predicted to slide at A = " << onset << " d (" << engine.state_changes(u, d, 1.25 * onset).sliding
            << " at 1.25x); the Coulomb limit changes the DEM run by " << below << " of the peak at 0.5x the onset, "
            << above << " at 1.25x\n";
  EXPECT_EQ(below, 0.0);
  EXPECT_GT(above, 1e-6);
}

// The slab solver against a sparse LU: a damped drive, and an almost undamped one above the band
// edge, where -omega^2 M dominates, the slab blocks are indefinite and their LU must pivot.
TEST_F(Packing, SlabSolverEqualsSparseLu) {
  const LinearChannel engine(*packing_, hooke(kKn));
  const DynamicMatrices& m = engine.matrices();
  for (const auto& [omega_scale, gamma, extra_scale] : {std::tuple{0.7, 2.0, 5.0}, std::tuple{2.6, 0.0, 1e-3}}) {
    const double omega = omega_scale * std::sqrt(kKn);
    Eigen::VectorXd extra = Eigen::VectorXd::LinSpaced(m.unknowns(), 0.0, extra_scale);
    Eigen::VectorXcd rhs = Eigen::VectorXcd::Random(m.unknowns());
    const Eigen::VectorXcd slab = engine.solver().solve(omega, gamma, extra, rhs);
    Eigen::SparseMatrix<Complex> z =
        m.stiffness.cast<Complex>() + Complex(0.0, omega * gamma) * m.dashpots.cast<Complex>();
    for (Eigen::Index i = 0; i < m.unknowns(); ++i) z.coeffRef(i, i) += Complex(-omega * omega * m.mass(i), omega * extra(i));
    Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(z);
    ASSERT_EQ(lu.info(), Eigen::Success);
    const Eigen::VectorXcd reference = lu.solve(rhs);
    EXPECT_LT((slab - reference).norm(), 1e-10 * reference.norm()) << "omega " << omega << ", gamma " << gamma;
  }
  EXPECT_GT(engine.solver().slabs(), 3u);
}

/// A pore fluid for the packing, in the scenes' dimensionless groups: squeeze films across gaps up to
/// 0.05 d, five times the default gap search.
dem::FluidSpec packing_fluid() {
  dem::FluidSpec f;
  f.viscosity = 0.05;
  f.roughness = 0.005;
  f.cutoff = 0.05;
  return f;
}

bool identical(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr());
}

// A fluid adds dashpots to C_t and nothing else: K, C1, M and the walls' springs and unit dashpots are
// bit for bit those of the dry packing, although the fluid's wider gap search lists more gaps.
TEST_F(Packing, FluidOnlyAddsFixedDashpots) {
  const LinearChannel dry(*packing_, hooke(kKn));
  const LinearChannel wet(*packing_, hooke(kKn), {}, packing_fluid());
  const DynamicMatrices &a = dry.matrices(), &b = wet.matrices();
  EXPECT_TRUE(identical(a.stiffness, b.stiffness));
  EXPECT_TRUE(identical(a.dashpots, b.dashpots));
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.fixed_dashpots.nonZeros(), 0);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_TRUE(identical(a.bodies[k].stiffness, b.bodies[k].stiffness));
    EXPECT_TRUE(identical(a.bodies[k].dashpots, b.bodies[k].dashpots));
    EXPECT_EQ(a.bodies[k].self_stiffness, b.bodies[k].self_stiffness);
    EXPECT_EQ(a.bodies[k].self_dashpots, b.bodies[k].self_dashpots);
    EXPECT_GT(b.bodies[k].self_fixed_dashpots.norm(), 0.0);  // films between the wall and its grains
  }
  EXPECT_EQ(dry.network().contacts.size(), wet.network().contacts.size());
  EXPECT_GT(wet.network().gaps.size(), dry.network().gaps.size());
  double widest = 0.0;
  for (const StaticPair& p : wet.network().gaps) widest = std::max(widest, -p.overlap);
  EXPECT_GT(widest, LinearSettings{}.gap_search * wet.units().diameter);
  EXPECT_LT(widest, packing_fluid().cutoff * wet.units().diameter);
  const Eigen::SparseMatrix<double> transposed = b.fixed_dashpots.transpose();
  EXPECT_EQ((b.fixed_dashpots - transposed).norm(), 0.0);
}

// The slab solver with the fluid's C_t (3 unknowns per grain, films across gaps that K does not
// couple) against a general sparse LU of the same system.
TEST_F(Packing, SlabSolverEqualsSparseLuWithAFluid) {
  const LinearChannel engine(*packing_, hooke(kKn), {}, packing_fluid());
  const DynamicMatrices& m = engine.matrices();
  ASSERT_EQ(m.dofs_per_node, 3);
  const double omega = 0.7 * std::sqrt(kKn), gamma = 0.5;
  const Eigen::VectorXd extra = Eigen::VectorXd::LinSpaced(m.unknowns(), 0.0, 2.0);
  const Eigen::VectorXcd rhs = Eigen::VectorXcd::Random(m.unknowns());
  const Eigen::VectorXcd slab = engine.solver().solve(omega, gamma, extra, rhs);
  Eigen::SparseMatrix<Complex> z = m.stiffness.cast<Complex>() + Complex(0.0, omega * gamma) * m.dashpots.cast<Complex>() +
                                   Complex(0.0, omega) * m.fixed_dashpots.cast<Complex>();
  for (Eigen::Index i = 0; i < m.unknowns(); ++i) z.coeffRef(i, i) += Complex(-omega * omega * m.mass(i), omega * extra(i));
  Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(z);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXcd reference = lu.solve(rhs);
  EXPECT_LT((slab - reference).norm(), 1e-10 * reference.norm());
  // premise: the fluid changes the solution
  const Eigen::VectorXcd dry = LinearChannel(*packing_, hooke(kKn)).solver().solve(omega, gamma, extra, rhs);
  EXPECT_GT((slab - dry).norm(), 1e-3 * reference.norm());
}

// The static solve (block Cholesky, for the relaxation's Newton steps) against a sparse LU, and its
// refusal of a matrix that is not positive definite: a negative mass shift pushes the rattlers' and
// the softest modes' eigenvalues below zero.
TEST_F(Packing, ShiftedStaticSolveEqualsSparseLuAndRefusesIndefiniteMatrices) {
  const LinearChannel engine(*packing_, hooke(kKn));
  const DynamicMatrices& m = engine.matrices();
  const double shift = 1e-2 * kKn;
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(m.unknowns(), 2);
  const std::optional<Eigen::MatrixXd> slab = engine.solver().solve_shifted(shift, rhs);
  ASSERT_TRUE(slab.has_value());
  Eigen::SparseMatrix<double> z = m.stiffness;
  for (Eigen::Index i = 0; i < m.unknowns(); ++i) z.coeffRef(i, i) += shift * m.mass(i);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(z);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::MatrixXd reference = lu.solve(rhs);
  EXPECT_LT((*slab - reference).norm(), 1e-10 * reference.norm());
  EXPECT_FALSE(engine.solver().solve_shifted(-1e-2 * kKn, rhs).has_value());
}

class PackingPower : public Packing, public ::testing::WithParamInterface<channel::FarWall> {};

TEST_P(PackingPower, InjectedByTheWallIsDissipated) {
  // Steady state: the time-averaged power the wall puts in equals what the contact dashpots and the
  // absorbing layer take out. A conservation law the solve must satisfy, whatever the packing. A
  // loaded far wall (a weak absorbing layer lets the wave reach it) does no net work over a cycle,
  // but its contacts' dashpots dissipate with its motion: a wrong row for it breaks the balance.
  // Weak damping lets the wave reach the far wall whatever the preparation's round-off made of the
  // packing: at gamma_hat = 0.3 the wall moved 2e-4 and 6e-4 of the largest motion in two
  // preparations, too little for the premise below; at 0.03 it moves 8e-3.
  const LinearChannel engine(*packing_, hooke(kKn));
  channel::DriveSettings d;
  d.omega_hat = 0.8;
  d.gamma_hat = 0.03;
  d.far_end = channel::FarEnd::absorbing;
  d.far_wall = GetParam();
  d.absorbing_strength = 0.05;
  d.far_wall_mass = 2.0;
  const Eigen::VectorXcd u = engine.displacement(d);
  if (d.far_wall == channel::FarWall::loaded) {
    channel::DriveSettings frozen = d;
    frozen.far_wall = channel::FarWall::frozen;
    // premise: the wall moves, and its motion changes the field
    std::cout << "the far wall moves " << std::abs(u(u.size() - 1)) / u.head(u.size() - 1).cwiseAbs().maxCoeff()
              << " of the largest grain motion\n";
    EXPECT_GT(std::abs(u(u.size() - 1)), 1e-3 * u.head(u.size() - 1).cwiseAbs().maxCoeff());
    EXPECT_GT((u.head(u.size() - 1) - engine.displacement(frozen)).norm(), 1e-3 * u.norm());
  }
  const channel::PackingUnits& units = engine.units();
  const double omega = d.omega_hat / units.time();
  const double gamma = d.gamma_hat * units.damping_scale;
  const DynamicMatrices& m = engine.matrices();
  double injected = 0.0, dissipated = 0.0;
  for (const StaticPair& p : engine.network().contacts) {
    const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
    const Eigen::Vector3cd rel = (engine.grain_motion(u, d, p.i) - engine.grain_motion(u, d, p.j)).head<3>();
    dissipated += 0.5 * omega * omega * gamma * p.dashpot * std::norm(n.cast<Complex>().dot(rel));
    // Force of the driven wall on its partner, times the wall velocity i omega e_z, time-averaged.
    const bool i_wall = engine.grains()[static_cast<std::size_t>(p.i)].body == channel::kLowerWallBody;
    const bool j_wall = engine.grains()[static_cast<std::size_t>(p.j)].body == channel::kLowerWallBody;
    if (i_wall == j_wall) continue;
    const Eigen::Vector3cd on_i = engine.contact_force(u, d, p);
    const Eigen::Vector3cd on_wall = i_wall ? on_i : Eigen::Vector3cd(-on_i);
    injected += 0.5 * std::real(std::conj(Complex(0.0, omega)) * -on_wall(2));
  }
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    const double z = engine.grains()[static_cast<std::size_t>(m.grain_of_node[node])].position.z;
    dissipated += 0.5 * omega * omega * channel::absorbing_drag(d, units, omega, z) *
                  u.segment<3>(static_cast<Eigen::Index>(3 * node)).squaredNorm();
  }
  EXPECT_GT(injected, 0.0);
  EXPECT_NEAR(dissipated / injected, 1.0, 1e-9);
}
INSTANTIATE_TEST_SUITE_P(FarWalls, PackingPower, ::testing::Values(channel::FarWall::frozen, channel::FarWall::loaded),
                         [](const auto& wall) { return wall.param == channel::FarWall::loaded ? "Loaded" : "Frozen"; });

TEST_F(Packing, ContactsOpenInProportionToTheAmplitude) {
  const LinearChannel engine(*packing_, hooke(kKn));
  channel::DriveSettings d;
  d.far_end = channel::FarEnd::absorbing;
  const Eigen::VectorXcd u = engine.displacement(d);
  std::int64_t previous = -1;
  for (double a : {1e-8, 1e-6, 1e-4, 1e-2}) {
    const StateChanges s = engine.state_changes(u, d, a);
    EXPECT_GE(s.opening + s.closing, previous);
    previous = s.opening + s.closing;
  }
  EXPECT_EQ(engine.state_changes(u, d, 1e-14).opening, 0);
  EXPECT_GT(engine.state_changes(u, d, 1e-1).opening, 0);
}

TEST(EquivalentContact, HookeMatchesTheDescribingFunction) {
  const auto hooke_force = [](double delta) { return 3.0 * delta; };
  auto closed_form = [](double overlap, double a) {
    const double theta = std::acos(std::clamp(-overlap / a, -1.0, 1.0));
    return 3.0 * (theta - std::sin(theta) * std::cos(theta)) / std::numbers::pi;
  };
  EXPECT_NEAR(equivalent_contact(hooke_force, 1.0, 0.5, 3.0).stiffness, 3.0, 1e-12);  // never opens
  EXPECT_NEAR(equivalent_contact(hooke_force, 1.0, 2.0, 3.0).stiffness, closed_form(1.0, 2.0), 1e-10);  // claps
  EXPECT_NEAR(equivalent_contact(hooke_force, -1.0, 2.0, 3.0).stiffness, closed_form(-1.0, 2.0), 1e-10);  // gap closes
  EXPECT_NEAR(equivalent_contact(hooke_force, 1.0, 2.0, 3.0).dashpot, closed_form(1.0, 2.0) / 3.0, 1e-14);
  EXPECT_EQ(equivalent_contact(hooke_force, -1.0, 0.5, 3.0).stiffness, 0.0);  // gap stays open
}

TEST(EquivalentContact, HertzTendsToTheTangentStiffness) {
  const auto hertz_force = [](double delta) { return std::pow(delta, 1.5); };
  const double tangent = 1.5 * std::sqrt(0.01);
  EXPECT_NEAR(equivalent_contact(hertz_force, 0.01, 1e-5, tangent).stiffness / tangent, 1.0, 1e-6);
  // Clapping softens it, but far less abruptly than Hooke's: at a = 2 delta0 it keeps most of it.
  EXPECT_LT(equivalent_contact(hertz_force, 0.01, 0.02, tangent).stiffness, 1.5 * tangent);
}

TEST_F(Packing, EquivalentLinearisationEqualsPlainWhereNothingClaps) {
  const LinearChannel engine(*packing_, hooke(kKn));
  channel::DriveSettings d;
  d.far_end = channel::FarEnd::absorbing;
  d.omega_hat = 1.2;
  d.amplitude = 1e-9;
  const LinearResult plain = engine.respond(d), equivalent = engine.respond_equivalent(d);
  ASSERT_EQ(plain.state_changes.opening + plain.state_changes.closing, 0);
  EXPECT_NEAR(equivalent.fit.alpha, plain.fit.alpha, 1e-9);
  EXPECT_NEAR(equivalent.fit.c, plain.fit.c, 1e-9);
  // At a large amplitude contacts clap and the equivalent field moves away from the plain one
  // (softer where opening contacts dominate, stiffer where closing gaps do: packing-dependent).
  d.amplitude = 3e-3;
  const LinearResult clapping = engine.respond_equivalent(d);
  EXPECT_GT(clapping.state_changes.opening, 0);
  EXPECT_GT(clapping.iterations, 1);
  EXPECT_GT(std::abs(clapping.fit.c / plain.fit.c - 1.0), 1e-3);
}

TEST(LinearEngine, RefusesAFrozenFarEnd) {
  const LinearChannel engine(chain(10, 0.999), hooke(1.0));
  channel::DriveSettings d;
  d.far_end = channel::FarEnd::frozen;
  EXPECT_THROW((void)engine.respond(d), std::invalid_argument);
}

TEST(LinearEngine, FitStopsWhereTheFieldUnderflows) {
  // A chain 4000 long at omega_hat = 1, gamma_hat = 1 (alpha_hat 0.35 per spacing): the field falls
  // by e^-980 before the absorbing layer and underflows to zero on the way. The fit keeps the
  // layers that still carry a field and finds the lattice's attenuation.
  const LinearChannel engine(chain(4000, 0.999), hooke(1.0));
  channel::DriveSettings d;
  d.omega_hat = 1.0;
  d.gamma_hat = 1.0;
  d.far_end = channel::FarEnd::absorbing;
  const LinearResult r = engine.respond(d);
  ASSERT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_LT(r.layers_used, 2500);
  EXPECT_NEAR(r.fit.alpha * 0.999 / lattice_wavenumber(1.0, 1.0).k.imag(), 1.0, 1e-3);  // per d, not per spacing
}

}  // namespace
}  // namespace sedwave::forward::linear
