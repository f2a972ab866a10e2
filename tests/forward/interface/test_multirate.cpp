// The multirate scheme (run.scheme = "multirate"): the plate beneath its top row of elements on its
// own step, the grains, the contacts and the top row of elements in substeps (granular_plate.hpp).
// Against the single-rate velocity-Verlet scheme: the same step where there is nothing to subcycle,
// the same solution as the steps shrink, and the energy balance's closure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;
using sedwave::forward::plate::PlateEdges;

// test_granular.cpp's small scene: 3 x 4 struck beads on an 8 x 3-element plate, absorbing sides.
GranularPlate small_run(const InterfaceContacts& contacts, Scheme scheme, double tolerance) {
  ElasticPlate plate(aluminium, {8, 3, 24e-3, 9e-3},
                     PlateEdges{EdgeCondition::free, EdgeCondition::clamped, EdgeCondition::absorbing,
                                EdgeCondition::absorbing});
  StepControl control{tolerance};
  control.scheme = scheme;
  return GranularPlate(struck_packing(), steel, plate, contacts, control);
}

std::vector<double> state(const GranularPlate& run) {
  std::vector<double> s;
  for (const auto& g : run.grains()) s.insert(s.end(), {g.x, g.y, g.vx, g.vy, g.spin});
  s.insert(s.end(), run.plate_displacement().begin(), run.plate_displacement().end());
  s.insert(s.end(), run.plate_velocity().begin(), run.plate_velocity().end());
  return s;
}

// Largest difference of the grains' positions and the plate's displacements (as in test_granular.cpp).
double position_distance(const GranularPlate& a, const GranularPlate& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.grains().size(); ++i)
    d = std::max({d, std::abs(a.grains()[i].x - b.grains()[i].x), std::abs(a.grains()[i].y - b.grains()[i].y)});
  for (std::size_t k = 0; k < a.plate_displacement().size(); ++k)
    d = std::max(d, std::abs(a.plate_displacement()[k] - b.plate_displacement()[k]));
  return d;
}

// Energy that has reached the plate: held in it or absorbed by its edges.
double transmitted(const GranularPlate& run) {
  const Energies e = run.energies();
  return e.plate_kinetic + e.plate_strain + e.boundary_work;
}

TEST(Multirate, IsTheVelocityVerletStepWhereNothingIsSubcycled) {
  // Frictionless: the plate's contacts' Hertz limit (which holds the plate's own frequency) is the
  // tightest, within a factor 2 of the plate's, so every outer step is one substep. The schemes
  // then take the same steps with the same forces, summed in another order: round-off apart.
  const InterfaceContacts frictionless{0.0, 1e3, 1.0, true};
  auto single = small_run(frictionless, Scheme::velocity_verlet, 0.1);
  auto multi = small_run(frictionless, Scheme::multirate, 0.1);
  single.advance_to(6e-5);
  multi.advance_to(6e-5);
  ASSERT_EQ(multi.steps(), multi.plate_steps()) << "the scene was to have nothing to subcycle";
  EXPECT_EQ(multi.steps(), single.steps());
  const auto a = state(single), b = state(multi);
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) scale = std::max(scale, std::abs(a[i])), diff = std::max(diff, std::abs(a[i] - b[i]));
  EXPECT_LT(diff, 1e-12 * scale);
  // The books too: the top rows take their slow kick, dashpot and works with the substep's.
  const double input = single.energies().mechanical();
  if (std::getenv("SEDWAVE_VERBOSE"))
    std::printf("state %.3e of its largest value; balances %.3e of the input apart\n", diff / scale,
                std::abs(multi.energies().balance() - single.energies().balance()) / input);
  EXPECT_LT(std::abs(multi.energies().balance() - single.energies().balance()), 1e-12 * input);
}

TEST(Multirate, ConvergesToTheSingleRateSolutionAtSecondOrder) {
  // Friction (k_s = 100 s/m) shortens the grains' steps below the plate's: the plate takes several
  // substeps' worth in one. Against velocity Verlet at a 32 times smaller tolerance, the final
  // positions' error falls at order 2 (measured 2.0, 2.0) and the transmitted energy's at least as
  // fast (2.9, 2.4).
  const InterfaceContacts friction{0.3, 1e2, 1.0, true};
  auto reference = small_run(friction, Scheme::velocity_verlet, 0.2 / 32.0);
  reference.advance_to(6e-5);
  const double reference_energy = transmitted(reference);
  ASSERT_GT(reference_energy, 0.0);
  std::vector<double> errors, energy_errors;
  for (const double tolerance : {0.2, 0.1, 0.05}) {
    auto run = small_run(friction, Scheme::multirate, tolerance);
    run.advance_to(6e-5);
    EXPECT_GT(run.steps(), 2 * run.plate_steps()) << "the plate was to take several substeps in one";
    errors.push_back(position_distance(run, reference));
    energy_errors.push_back(std::abs(transmitted(run) / reference_energy - 1.0));
    if (std::getenv("SEDWAVE_VERBOSE")) {
      auto single = small_run(friction, Scheme::velocity_verlet, tolerance);
      single.advance_to(6e-5);
      std::printf("tolerance %g: multirate %ld steps, %ld plate steps; velocity Verlet %ld steps, position error "
                  "%.3e, transmitted energy %.3e\n", tolerance, run.steps(), run.plate_steps(), single.steps(),
                  position_distance(single, reference), std::abs(transmitted(single) / reference_energy - 1.0));
    }
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    const double energy_order = std::log2(energy_errors[i - 1] / energy_errors[i]);
    if (std::getenv("SEDWAVE_VERBOSE"))
      std::printf("position error %.3e -> %.3e: order %.2f; transmitted energy %.3e -> %.3e: order %.2f\n",
                  errors[i - 1], errors[i], order, energy_errors[i - 1], energy_errors[i], energy_order);
    EXPECT_GT(order, 1.5);
    EXPECT_GT(energy_order, 1.5);
  }
  EXPECT_LT(energy_errors.back(), 1e-4);
}

TEST(Multirate, BalanceClosesWithFrictionDashpotsAndAbsorbingEdges) {
  // test_granular.cpp's balance test (friction, Hertz-Tsuji dashpots, absorbing edges) with the
  // multirate scheme, every outer step checked: the books close to the conservative forces'
  // integration error alone, as single-rate.
  auto run = small_run(InterfaceContacts{0.3, 1e2, 0.8, true}, Scheme::multirate, 0.004);
  const double input = run.energies().mechanical();
  double worst = 0.0, plate_share = 0.0;
  while (run.time() < 1.2e-4) {
    run.step(1.2e-4 - run.time());
    const auto e = run.energies();
    worst = std::max(worst, std::abs(e.balance() - input) / input);
    plate_share = std::max(plate_share, (e.plate_kinetic + e.plate_strain) / input);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(plate_share, 1e-2) << "the plate took part";
  EXPECT_GT(run.steps(), 2 * run.plate_steps()) << "the plate was to take several substeps in one";
  const auto e = run.energies();
  EXPECT_GT(e.friction_work, 1e-4 * input);
  EXPECT_GT(e.dashpot_work, 1e-2 * input);
  EXPECT_GT(e.boundary_work, 0.0);
}

TEST(Multirate, DeliversAPlatePulseAndBooksItAsSingleRate) {
  // test_paper_interface.cpp's pulse on a free plate's top edge (the rows the substeps kick), no
  // beads: every outer step is one substep, the pulse's impulse is delivered whole (momentum =
  // sum F tau) and its work and the balance are velocity Verlet's.
  const ElasticPlate plate = free_plate();
  const double tau = 1e-6;
  double total = 0.0;
  const PlatePulse pulse = top_edge_pulse(plate, tau, total);
  Energies books[2];
  for (const Scheme scheme : {Scheme::velocity_verlet, Scheme::multirate}) {
    StepControl control{0.1};
    control.scheme = scheme;
    GranularPlate run({}, steel, plate, InterfaceContacts{}, control);
    run.set_plate_pulse(pulse);
    run.advance_to(2.0 * tau);
    EXPECT_EQ(run.steps(), run.plate_steps());
    double momentum = 0.0;
    for (int n = 0; n < plate.node_count(); ++n)
      momentum += plate.mass()[static_cast<std::size_t>(2 * n + 1)] * run.plate_velocity()[static_cast<std::size_t>(2 * n + 1)];
    EXPECT_NEAR(momentum / (total * tau), 1.0, 1e-12);
    books[scheme == Scheme::multirate ? 1 : 0] = run.energies();
  }
  EXPECT_GT(books[0].drive_work, 0.0);
  EXPECT_NEAR(books[1].drive_work / books[0].drive_work, 1.0, 1e-12);
  EXPECT_NEAR((books[1].balance() - books[0].balance()) / books[0].drive_work, 0.0, 1e-12);
}

TEST(Multirate, RefusesAFixedStepAndABadPlateTolerance) {
  ElasticPlate plate(aluminium, {8, 3, 24e-3, 9e-3}, PlateEdges{});
  StepControl control{0.1};
  control.scheme = Scheme::multirate;
  control.fixed_step = 1e-9;
  EXPECT_THROW(GranularPlate(struck_packing(), steel, plate, InterfaceContacts{}, control), std::invalid_argument);
  control.fixed_step = 0.0;
  control.plate_tolerance = 0.6;
  EXPECT_THROW(GranularPlate(struck_packing(), steel, plate, InterfaceContacts{}, control), std::invalid_argument);
}

}  // namespace
