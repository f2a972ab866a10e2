// The DEM engine's contact laws on the interface's grain-grain contacts: a Hooke pair against its
// closed-form restitution and contact time, and a packing with tangential history springs and
// rolling resistance against its energy balance.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/units.hpp"
#include "steel_beads.hpp"

namespace {

using namespace sedwave::forward::interface;
using namespace sedwave::forward::interface::test;
using sedwave::forward::dem::ContactSpec;
using sedwave::forward::plate::EdgeCondition;
using sedwave::forward::plate::ElasticPlate;
using sedwave::forward::plate::PlateEdges;

TEST(GrainContactLaws, AHookePairReboundsWithItsRestitutionAfterItsCollisionTime) {
  // m_eff x'' = -kn x - gamma x': restitution e_n exactly (the dashpot is not clipped), contact time
  // pi / (omega0 sqrt(1 - zeta^2)) (units.hpp's mapping, Hooke's closed form).
  const double kn = 1e7, e_n = 0.7, v = 0.5;
  ContactSpec spec;
  spec.normal = "hooke";
  spec["kn"] = kn;
  spec["restitution"] = e_n;
  InterfaceContacts contacts;
  contacts.grain_contact = spec;
  auto grains = chain(2);
  grains[0].y -= 1e-6;
  grains[0].vy = 0.5 * v;
  grains[1].vy = -0.5 * v;
  GranularPlate run(grains, steel, std::nullopt, contacts, StepControl{0.002});
  const auto overlap = [&] {
    const auto& g = run.grains();
    return g[0].radius + g[1].radius - std::hypot(g[1].x - g[0].x, g[1].y - g[0].y);
  };
  double t_start = -1.0, t_end = -1.0, previous = overlap(), t_previous = 0.0;
  for (int step = 0; step < 1'000'000 && t_end < 0.0; ++step) {
    run.step();
    const double now = overlap();
    if (previous <= 0.0 && now > 0.0) t_start = t_previous + (run.time() - t_previous) * (-previous) / (now - previous);
    if (previous > 0.0 && now <= 0.0) t_end = t_previous + (run.time() - t_previous) * previous / (previous - now);
    previous = now;
    t_previous = run.time();
  }
  const double m_eff = 0.5 * grains[0].mass;
  const double zeta = sedwave::forward::damping_ratio_from_restitution(e_n);
  const double t_col = std::numbers::pi / (std::sqrt(kn / m_eff) * std::sqrt(1.0 - zeta * zeta));
  EXPECT_NEAR((t_end - t_start) / t_col, 1.0, 1e-3);
  const auto& g = run.grains();
  EXPECT_NEAR((g[0].vy - g[1].vy) / v, -e_n, 1e-4);
}

// A 3 x 4 packing on a small plate (struck_packing), with the DEM's
// history spring (kt) and constant-torque rolling resistance between grains: the springs store
// energy that friction's work must not count as dissipated.
TEST(GrainContactLaws, HistorySpringsAndRollingResistanceKeepTheEnergyBalance) {
  const auto grains = struck_packing();
  InterfaceContacts contacts;
  contacts.friction = 0.3;
  contacts.tanh_velocity_scale = 1e2;  // the grain-plate contact's
  contacts.grain_contact = history_and_rolling(contacts);
  ElasticPlate plate(aluminium, {8, 3, 24e-3, 9e-3},
                     PlateEdges{EdgeCondition::free, EdgeCondition::clamped, EdgeCondition::free, EdgeCondition::free});
  GranularPlate run(grains, steel, plate, contacts, StepControl{0.05});
  const double input = run.energies().mechanical();
  double worst = 0.0;
  while (run.time() < 1e-4) {
    run.step(1e-4 - run.time());
    const auto e = run.energies();
    worst = std::max(worst, std::abs(e.balance() - input) / input);
    EXPECT_GE(e.friction_work, -1e-9 * input);
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(run.energies().friction_work, 1e-3 * input);
  EXPECT_GT(run.energies().grain_rotation, 0.0);
}

}  // namespace
