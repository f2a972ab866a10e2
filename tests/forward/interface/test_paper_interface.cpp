// The pieces of Wang, Zhang & Vakakis (2021) beside sedwave's own: the paper's grain-plate contact
// (eqs. 19a,b: flat rigid layers at the plate's nodes, E* = E_b/(1 - nu_b^2), R* = r, no dashpot,
// Coulomb-tanh friction, everything on one node), checked against Hertz's rigid-wall closed forms
// (Johnson 1985, sec. 11.1) and Coulomb's sliding impact; and the pulse on the plate's edge that
// drives its monolithic scenario (appendix 2), checked against the impulse-momentum theorem; and the
// paper's scheme (appendix 1: Newmark for the plate, RK4 for the grains, the forces iterated),
// checked against sedwave's velocity Verlet on the same system.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#include <stdexcept>
#include <string>

#include "hertz_time.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;
using sedwave::forward::plate::PlateEdges;
using sedwave::forward::plate::PlateMaterial;

using sedwave::test::hertz_time_factor;

const PlateEdges clamped_below{EdgeCondition::free, EdgeCondition::clamped, EdgeCondition::free, EdgeCondition::free};
constexpr double strike = 0.5;  // [m/s]

struct Bounce {
  double contact_time = 0.0;
  double max_overlap = 0.0;
  double peak_force = 0.0;      // on the plate, the largest sampled
  double largest_plate_u = 0.0; // over every degree of freedom and step
  double final_vx = 0.0, final_vy = 0.0;
};

// A steel bead 10 um above the node at x = 10 mm of a 4 x 2 mesh (5 mm elements), struck down at
// `strike` m/s with tangential speed vx; runs until it leaves the plate.
Bounce bounce(const PlateMaterial& material, PlateContactModel model, bool clamp_node, double vx = 0.0,
              double friction = 0.0) {
  ElasticPlate plate(material, {4, 2, 20e-3, 10e-3}, clamped_below);
  if (clamp_node) plate.fix(plate.node(2, 2), 0), plate.fix(plate.node(2, 2), 1);
  auto grains = chain(1, 1e-5);
  grains[0].x = 10e-3;
  grains[0].vy = -strike;
  grains[0].vx = vx;
  InterfaceContacts contacts;
  contacts.plate_contact = model;
  contacts.friction = friction;
  contacts.tanh_velocity_scale = 1e4;  // tanh(k_s slip) = 1 to 1e-9 while the bead slides
  GranularPlate run(grains, steel, plate, contacts, StepControl{0.01});
  Bounce b;
  double t_start = -1.0, t_end = -1.0, previous = bead_radius - run.grains()[0].y, t_previous = 0.0;
  for (int step = 0; step < 10'000'000 && t_end < 0.0; ++step) {
    run.step();
    const double now = bead_radius - (run.grains()[0].y - run.plate_displacement()[2 * plate.node(2, 2) + 1]);
    if (previous <= 0.0 && now > 0.0) t_start = t_previous + (run.time() - t_previous) * (-previous) / (now - previous);
    if (previous > 0.0 && now <= 0.0) t_end = t_previous + (run.time() - t_previous) * previous / (previous - now);
    b.max_overlap = std::max(b.max_overlap, now);
    b.peak_force = std::max(b.peak_force, run.plate_normal_force());
    for (const double u : run.plate_displacement()) b.largest_plate_u = std::max(b.largest_plate_u, std::abs(u));
    previous = now;
    t_previous = run.time();
  }
  b.contact_time = t_end - t_start;
  b.final_vx = run.grains()[0].vx;
  b.final_vy = run.grains()[0].vy;
  return b;
}

// Johnson eqs. 11.23-11.24 for a bead of mass m and radius r on a rigid wall of modulus e_star.
struct RigidWall {
  double max_overlap, contact_time, peak_force;
};
RigidWall rigid_wall(double e_star) {
  const double r = bead_radius, m = chain(1)[0].mass;
  const double delta = std::pow(15.0 * m * strike * strike / (16.0 * e_star * std::sqrt(r)), 0.4);
  return {delta, hertz_time_factor() * delta / strike, (4.0 / 3.0) * e_star * std::sqrt(r) * delta * std::sqrt(delta)};
}

const double paper_modulus = steel.youngs_modulus / (1.0 - steel.poisson_ratio * steel.poisson_ratio);

TEST(RigidLayers, ModulusIsTheGrainsAlone) {
  EXPECT_DOUBLE_EQ(grain_plate_modulus(steel, aluminium, PlateContactModel::rigid_layers), paper_modulus);
  EXPECT_DOUBLE_EQ(grain_plate_modulus(steel, aluminium, PlateContactModel::interpolated),
                   sedwave::forward::hertz_effective_modulus(steel.youngs_modulus, steel.poisson_ratio,
                                                            aluminium.youngs_modulus, aluminium.poisson_ratio));
}

// The node under the bead held: its layer is a rigid wall, so the bounce is Hertz's against a wall of
// the bead's own E/(1 - nu^2), whatever the plate's material (aluminium here), and no other node
// moves: the force acts on that node alone.
TEST(RigidLayers, HeldNodeIsARigidWallOfTheBeadsModulus) {
  const Bounce b = bounce(aluminium, PlateContactModel::rigid_layers, true);
  const RigidWall wall = rigid_wall(paper_modulus);
  EXPECT_NEAR(b.max_overlap / wall.max_overlap, 1.0, 1e-4);
  EXPECT_NEAR(b.contact_time / wall.contact_time, 1.0, 1e-4);
  EXPECT_NEAR(b.peak_force / wall.peak_force, 1.0, 1e-4);
  EXPECT_EQ(b.largest_plate_u, 0.0);
  EXPECT_NEAR(b.final_vy / strike, 1.0, 1e-6);  // no dashpot on this contact
  // The interpolated contact on the same held node sees the plate's compliance in E*: t ~ E*^(-2/5).
  const Bounce soft = bounce(aluminium, PlateContactModel::interpolated, true);
  const double ratio = std::pow(paper_modulus / grain_plate_modulus(steel, aluminium, PlateContactModel::interpolated), 0.4);
  EXPECT_NEAR(soft.contact_time / b.contact_time / ratio, 1.0, 1e-4);
}

// A plate 1000 times stiffer than steel, the node free: its layer barely yields, so the bounce
// approaches the rigid wall's (the node's motion is the residual).
TEST(RigidLayers, VeryStiffPlateApproachesTheRigidWall) {
  const PlateMaterial stiff{200e12, 0.3, 7850.0, 5e-3};
  const Bounce b = bounce(stiff, PlateContactModel::rigid_layers, false);
  const RigidWall wall = rigid_wall(paper_modulus);
  EXPECT_NEAR(b.max_overlap / wall.max_overlap, 1.0, 2e-3);
  EXPECT_NEAR(b.contact_time / wall.contact_time, 1.0, 2e-3);
  EXPECT_NEAR(b.peak_force / wall.peak_force, 1.0, 2e-3);
  EXPECT_GT(b.largest_plate_u, 0.0);
}

// Sliding throughout on a held layer: Coulomb's impact, the tangential impulse mu times the normal
// one (2 m v), and the bead's spin from its torque r F_t: Delta v_x = -2 mu v.
TEST(RigidLayers, SlidingBounceLosesMuTimesTheNormalImpulse) {
  const double mu = 0.1, vx = 1.0;  // the slip falls by 7/2 * 2 mu v = 0.35 m/s: still sliding
  const Bounce b = bounce(aluminium, PlateContactModel::rigid_layers, true, vx, mu);
  EXPECT_NEAR(b.final_vy / strike, 1.0, 1e-6);
  EXPECT_NEAR((b.final_vx - vx) / (-2.0 * mu * strike), 1.0, 1e-4);
  EXPECT_EQ(b.largest_plate_u, 0.0);
}

TEST(RigidLayers, RefusesAGrainBetweenNodes) {
  ElasticPlate plate(aluminium, {4, 2, 20e-3, 10e-3}, clamped_below);
  auto grains = chain(1, 1e-5);
  grains[0].x = 11.3e-3;
  InterfaceContacts contacts;
  contacts.plate_contact = PlateContactModel::rigid_layers;
  try {
    GranularPlate run(grains, steel, plate, contacts, StepControl{});
    FAIL() << "a grain between nodes was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("grain 0 at x = 0.0113 m lies between the nodes at 0.01 and 0.015 m"),
              std::string::npos)
        << e.what();
  }
  // The same grain lifted beyond the neighbour list's reach cannot touch the plate: accepted.
  grains[0].y = 3.0 * bead_radius;
  EXPECT_NO_THROW(GranularPlate(grains, steel, plate, contacts, StepControl{}));
}

// A free plate (every edge free: it may move as a whole) under a rectangular pulse on its top edge,
// stepped with a fixed step that does not divide the pulse's duration: the momentum it gains is the
// pulse's impulse, sum F tau, to round-off, and the energy books close (the pulse's work is the
// plate's energy).
TEST(PlatePulse, DeliversItsImpulseWhateverTheStep) {
  const ElasticPlate plate = free_plate();
  const double tau = 1e-6;
  double total = 0.0;
  const PlatePulse pulse = top_edge_pulse(plate, tau, total);
  GranularPlate run({}, steel, plate, InterfaceContacts{}, StepControl{0.1, 1.0, tau / 37.3});
  run.set_plate_pulse(pulse);
  run.advance_to(2.0 * tau);
  double momentum = 0.0;
  for (int n = 0; n < plate.node_count(); ++n)
    momentum += plate.mass()[static_cast<std::size_t>(2 * n + 1)] * run.plate_velocity()[static_cast<std::size_t>(2 * n + 1)];
  EXPECT_NEAR(momentum / (total * tau), 1.0, 1e-12);
  const Energies e = run.energies();
  EXPECT_GT(e.drive_work, 0.0);
  EXPECT_NEAR(e.balance() / e.drive_work, 0.0, 1e-3);
}

// Three beads standing on an absorbing plate through the paper's contact, the top one struck at
// 1 m/s with friction and rotation; `scheme` and tolerance theta. What reached the plate by 60 us
// (its energy now plus what left through its edges) and the force on it every 0.5 us.
struct Transmission {
  double energy = 0.0;
  std::vector<double> force;
  long steps = 0, iterations = 0, factorisations = 0;
  int most_iterations = 0;
  double balance = 0.0;  // |balance - initial| / initial at the end
};
Transmission transmit(Scheme scheme, double theta) {
  ElasticPlate plate(aluminium, {12, 6, 30e-3, 15e-3},
                     PlateEdges{EdgeCondition::free, EdgeCondition::absorbing, EdgeCondition::absorbing,
                                EdgeCondition::absorbing});
  auto grains = chain(3, 0.0);
  for (auto& g : grains) g.x = 15e-3;  // over the middle node
  grains[2].vy = -1.0;
  grains[2].vx = 0.2;  // obliquely: friction and spin take part
  InterfaceContacts contacts;
  contacts.plate_contact = PlateContactModel::rigid_layers;
  contacts.friction = 0.3;
  contacts.tanh_velocity_scale = 100.0;
  StepControl control{theta};
  control.scheme = scheme;
  GranularPlate run(grains, steel, plate, contacts, control);
  const double initial = run.energies().mechanical();
  Transmission t;
  for (int k = 1; k <= 120; ++k) {
    run.advance_to(0.5e-6 * k);
    t.force.push_back(run.plate_normal_force());
  }
  const Energies e = run.energies();
  t.energy = e.plate_kinetic + e.plate_strain + e.boundary_work;
  t.steps = run.steps();
  t.iterations = run.iterations();
  t.most_iterations = run.most_iterations();
  t.factorisations = run.factorisations();
  t.balance = std::abs(e.balance() - initial) / initial;
  return t;
}

// Two integrations of one system must agree as their steps shrink: transmitted energy and the force
// history within 1e-3 at theta = 0.05, each balance closed, the iteration converging in a few rounds.
TEST(NewmarkRk4, AgreesWithVelocityVerletOnTheSameSystem) {
  const Transmission verlet = transmit(Scheme::velocity_verlet, 0.05);
  const Transmission paper = transmit(Scheme::newmark_rk4, 0.05);
  ASSERT_GT(verlet.energy, 0.0);
  EXPECT_NEAR(paper.energy / verlet.energy, 1.0, 1e-3);
  double peak = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < verlet.force.size(); ++k) {
    peak = std::max(peak, verlet.force[k]);
    worst = std::max(worst, std::abs(paper.force[k] - verlet.force[k]));
  }
  EXPECT_GT(peak, 0.0);
  EXPECT_LT(worst / peak, 1e-3);
  EXPECT_LT(verlet.balance, 1e-5);
  EXPECT_LT(paper.balance, 1e-5);
  EXPECT_EQ(verlet.iterations, 0);
  EXPECT_GT(paper.iterations, paper.steps);  // at least one iteration beyond the first in some step
  EXPECT_LT(paper.most_iterations, 30);
  EXPECT_LT(paper.factorisations, paper.steps / 10);  // the step ladder reuses the factorisation
  std::printf("transmitted %.9g J (verlet) %.9g J (newmark_rk4); force %.3g of its peak; steps %ld, %ld; "
              "iterations %ld (most %d), factorisations %ld; balances %.2g, %.2g\n",
              verlet.energy, paper.energy, worst / peak, verlet.steps, paper.steps, paper.iterations,
              paper.most_iterations, paper.factorisations, verlet.balance, paper.balance);
}

// A bead 130 times lighter than the node under it (78 kg/m^3 on a 2 x 1 mesh): the paper's
// criterion, which neglects the granule's sensitivity, allows a step at which this run blows up
// (bench/interface/paper_step_bound.py: at half of it); with the bead's inverse mass added the
// adaptive step at theta = 0.5 keeps it stable: the bead rebounds and the balance closes to 5e-2.
TEST(NewmarkRk4, LightBeadOnACoarseMeshStaysStable) {
  ElasticPlate plate(aluminium, {2, 1, 20e-3, 10e-3}, clamped_below);
  HexPacking light = steel_beads(1, 1);
  light.density = 78.0;
  light.x_offset = 7.5e-3;  // the centre over the middle node
  light.lift = 1e-6;
  auto grains = make_hex_packing(light);
  grains[0].vy = -1.0;
  InterfaceContacts contacts;
  contacts.plate_contact = PlateContactModel::rigid_layers;
  StepControl control{0.5};
  control.scheme = Scheme::newmark_rk4;
  GranularPlate run(grains, steel, plate, contacts, control);
  const double initial = run.energies().mechanical();
  double worst = 0.0;
  while (run.time() < 3e-5) {
    run.step_towards(3e-5);
    worst = std::max(worst, std::abs(run.energies().balance() - initial) / initial);
  }
  EXPECT_GT(run.grains()[0].vy, 0.0);
  EXPECT_LT(worst, 5e-2);
}

}  // namespace
