// Long channels from a periodic cell (channel/periodic_cell.hpp): the cell's pressure is its contact
// virial, the virial is the energy's derivative under strain, and a stack of copies of a cell in
// equilibrium is in equilibrium itself, with the cell's load on its walls.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <map>

#include "hooke_contact.hpp"
#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/channel/contacts.hpp"
#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/forward/linear/newton_stage.hpp"

namespace sedwave::forward::channel {
namespace {

using testing::hooke_contact;

ChannelGeometry cell_geometry(int grains) {
  ChannelGeometry g;
  g.n_grains = grains;
  g.periodic = true;
  return g;
}

PreparationSettings cell_preparation() {
  PreparationSettings p;
  p.pressure = 10.0;
  p.compression = Compression::affine;
  return p;
}

/// One prepared cell for the whole suite (about a second).
const PreparedChannel& prepared_cell() {
  static const PreparedChannel cell = [] {
    const ChannelGeometry g = cell_geometry(300);
    return prepare_channel(MPI_COMM_WORLD, generate_channel(g), hooke_contact(), g.width, cell_preparation(),
        forward::linear::newton_stage());
  }();
  return cell;
}

dem::EngineSettings engine_settings(const dem::Box& box) {
  dem::EngineSettings s;
  s.box = box;
  s.contact = hooke_contact();
  return s;
}

TEST(PeriodicCell, LooseCellIsPeriodicWithoutOverlapsAcrossItsEnds) {
  const ChannelGeometry g = cell_geometry(400);
  const ChannelConfiguration c = generate_channel(g);
  ASSERT_EQ(c.grains.size(), 400U);  // no walls
  ASSERT_TRUE(c.box.periodic[2]);
  const double length = c.box.length(2);
  for (std::size_t i = 0; i < c.grains.size(); ++i) {
    EXPECT_GE(c.grains[i].position.z, c.box.lo.z);
    EXPECT_LT(c.grains[i].position.z, c.box.hi.z);
    for (std::size_t j = i + 1; j < c.grains.size(); ++j) {
      dem::Vec3 d = c.grains[i].position - c.grains[j].position;
      d.x -= g.width * std::round(d.x / g.width);
      d.y -= g.width * std::round(d.y / g.width);
      d.z -= length * std::round(d.z / length);  // the images across the periodic end too
      ASSERT_GE(dem::norm(d), c.grains[i].radius + c.grains[j].radius) << i << " " << j;
    }
  }
}

TEST(PeriodicCell, VirialIsMinusTheEnergysDerivativeUnderStrain) {
  // Under an affine strain z -> (1 + e) z every overlap changes by -dz^2/r de, so
  // dE/de = -sum f dz^2 / r = -virial_zz, in or out of equilibrium. A compressed loose cell (not
  // relaxed) checks the strain and the virial together against a central difference.
  const ChannelGeometry g = cell_geometry(300);
  ChannelConfiguration c = generate_channel(g);
  for (dem::Grain& grain : c.grains) grain.position.z *= 0.42;  // packing fraction 0.25 -> 0.6
  c.box.hi.z *= 0.42;
  dem::Engine engine(MPI_COMM_WORLD, engine_settings(c.box), c.grains);
  const double virial = packing_stats(engine, 1.0, g.width).virial_zz;
  ASSERT_GT(virial, 0.0);
  const double h = 1e-6;
  engine.strain_periodic_z(1.0 + h);
  engine.compute_forces();
  const double e_plus = engine.elastic_energy();
  engine.strain_periodic_z((1.0 - h) / (1.0 + h));
  engine.compute_forces();
  const double e_minus = engine.elastic_energy();
  EXPECT_NEAR(-(e_plus - e_minus) / (2.0 * h), virial, 1e-6 * virial);
}

TEST(PeriodicCell, PreparesToEquilibriumAtThePressure) {
  const PreparedChannel& cell = prepared_cell();
  EXPECT_TRUE(cell.report.converged) << describe(cell.report);
  EXPECT_TRUE(cell.box.periodic[2]);
  EXPECT_LT(cell.report.residual_ratio, 1e-9);
  EXPECT_NEAR(cell.report.pressure, 10.0, 0.1);
  EXPECT_GT(cell.report.stats.packing_fraction, 0.6);
  // The serial contact network sees the DEM's contacts, across the periodic end included.
  const ContactNetwork network = find_contacts(cell.grains, cell.box, hooke_contact());
  EXPECT_EQ(static_cast<std::int64_t>(network.contacts.size()), cell.report.stats.contacts);
}

TEST(PeriodicCell, StackedCopiesAreInEquilibriumWithTheCellsLoadOnTheirWalls) {
  const PreparedChannel& cell = prepared_cell();
  const int copies = 3;
  const PreparedChannel channel = tile_periodic_cell(MPI_COMM_WORLD, cell, hooke_contact(), copies, 1.5);
  EXPECT_FALSE(channel.box.periodic[2]);
  ASSERT_EQ(channel.grains.size(), copies * cell.grains.size());
  // Force balance: the upper wall carries what crosses every section of the cell, its virial / L.
  const double carried = cell.report.stats.virial_zz / cell.box.length(2);
  EXPECT_NEAR(channel.report.wall_force, carried, 1e-9 * carried);
  // Every flow grain keeps the cell's contacts, so the residual stays at the cell's, give or take
  // the round-off of heights shifted by up to 2 L ~ 70 d (1e-14 d, 1e-11 kn / 1e-11 of a mean force).
  EXPECT_LT(channel.report.residual_ratio, 1e-9);
  EXPECT_LE(channel.report.residual_ratio, cell.report.residual_ratio + 1e-11);
  const ContactNetwork in_cell = find_contacts(cell.grains, cell.box, hooke_contact());
  const ContactNetwork in_channel = find_contacts(channel.grains, channel.box, hooke_contact());
  std::map<double, int> contacts_by_radius;  // radii identify a cell grain (continuous sizes)
  for (std::size_t k = 0; k < cell.grains.size(); ++k)
    contacts_by_radius[cell.grains[k].radius] = in_cell.contacts_per_grain[k];
  int flow = 0;
  for (std::size_t k = 0; k < channel.grains.size(); ++k) {
    if (channel.grains[k].group != kFlowGroup) continue;
    ++flow;
    ASSERT_EQ(in_channel.contacts_per_grain[k], contacts_by_radius.at(channel.grains[k].radius)) << k;
  }
  EXPECT_GT(flow, 0);
  // Ids: flow grains first, then the walls.
  for (std::size_t k = 0; k < channel.grains.size(); ++k) EXPECT_EQ(channel.grains[k].id, static_cast<std::int64_t>(k) + 1);
  EXPECT_TRUE(std::is_partitioned(channel.grains.begin(), channel.grains.end(),
                                  [](const dem::Grain& g) { return g.group == kFlowGroup; }));
}

TEST(PeriodicCell, TilingRefusesWallsThatCutContacts) {
  const PreparedChannel& cell = prepared_cell();
  EXPECT_THROW((void)tile_periodic_cell(MPI_COMM_WORLD, cell, hooke_contact(), 2, 0.5), std::invalid_argument);
  EXPECT_THROW((void)tile_periodic_cell(MPI_COMM_WORLD, cell, hooke_contact(), 0, 1.5), std::invalid_argument);
  PreparedChannel open = cell;
  open.box.periodic[2] = false;
  EXPECT_THROW((void)tile_periodic_cell(MPI_COMM_WORLD, open, hooke_contact(), 2, 1.5), std::invalid_argument);
}

TEST(PeriodicCell, HasNoWallToLower) {
  const ChannelGeometry g = cell_geometry(100);
  PreparationSettings p = cell_preparation();
  p.compression = Compression::wall;
  EXPECT_THROW((void)prepare_channel(MPI_COMM_WORLD, generate_channel(g), hooke_contact(), g.width, p,
      forward::linear::newton_stage()),
               std::invalid_argument);
}

}  // namespace
}  // namespace sedwave::forward::channel
