// The in-plane plate alone: wave speeds, dispersion against the lumped-mass central-difference closed
// form, its order in the element size, and the Lysmer-Kuhlemeyer edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/plate/elastic_plate.hpp"

namespace {

using sedwave::forward::interface::GrainMaterial;
using sedwave::forward::interface::GranularPlate;
using sedwave::forward::interface::InterfaceContacts;
using sedwave::forward::interface::StepControl;
using namespace sedwave::forward::plate;

// Aluminium.
const PlateMaterial aluminium{70e9, 0.33, 2700.0, 5e-3};

// A strip one element tall in which every node keeps component `held` at zero: the other component
// then depends on x only, and the strip is a 1D chain with modulus E/(1 - nu^2) (held = y, a
// dilatational wave) or G (held = x, a shear wave).
ElasticPlate strip(int elements, double length, int held, PlateEdges edges) {
  ElasticPlate plate(aluminium, {elements, 1, length, length / elements}, edges);
  for (int node = 0; node < plate.node_count(); ++node) plate.fix(node, held);
  return plate;
}

GranularPlate plate_only(ElasticPlate plate, double tolerance = 0.5) {
  return GranularPlate({}, GrainMaterial{200e9, 0.3}, std::move(plate), InterfaceContacts{}, StepControl{tolerance});
}

struct Mode {
  double omega;  // measured
  double dt;     // the (constant) step the run took
};

// Standing wave sin(pi x / L) between ends held at zero; the frequency from the zero crossings of
// the midpoint displacement over ~8 periods.
Mode standing_wave(int elements, int moving) {
  const double length = 1.0;
  const PlateEdges free_edges{EdgeCondition::free, EdgeCondition::free, EdgeCondition::free, EdgeCondition::free};
  ElasticPlate plate = strip(elements, length, 1 - moving, free_edges);
  for (const int j : {0, 1}) {
    plate.fix(plate.node(0, j), moving);
    plate.fix(plate.node(elements, j), moving);
  }
  const int probe = plate.node(elements / 2, 0);
  auto run = plate_only(plate);
  auto& u = run.plate_displacement_mutable();
  for (int node = 0; node < run.plate()->node_count(); ++node)
    u[static_cast<std::size_t>(2 * node + moving)] = 1e-6 * std::sin(std::numbers::pi * run.plate()->node_x(node) / length);
  run.refresh_forces();
  const double c = moving == 0 ? dilatational_speed(aluminium) : shear_speed(aluminium);
  const double period = 2.0 * length / c;
  std::vector<double> crossings;
  double previous = u[static_cast<std::size_t>(2 * probe + moving)];
  double t_previous = 0.0;
  double dt = 0.0;
  while (run.time() < 8.3 * period) {
    dt = run.step();
    const double now = run.plate_displacement()[static_cast<std::size_t>(2 * probe + moving)];
    if ((previous > 0.0) != (now > 0.0)) crossings.push_back(t_previous + dt * previous / (previous - now));
    previous = now;
    t_previous = run.time();
  }
  const double half_period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  return {std::numbers::pi / half_period, dt};
}

// Lumped-mass linear elements and central differences: omega_h = (2c/h) sin(kh/2) in space,
// sin(omega dt/2) = (dt/2) omega_h in time (Hughes 2000, sec. 9.1; the spring-mass chain).
double discrete_frequency(double c, double k, double h, double dt) {
  const double omega_h = 2.0 * c / h * std::sin(0.5 * k * h);
  return 2.0 / dt * std::asin(0.5 * dt * omega_h);
}

TEST(Plate, WaveSpeedsArePlaneStress) {
  // E/(rho (1 - nu^2)) and E/(2 rho (1 + nu)) for aluminium: 5394 and 3226 m/s.
  EXPECT_NEAR(dilatational_speed(aluminium), std::sqrt(70e9 / (2700.0 * (1.0 - 0.33 * 0.33))), 1e-9);
  EXPECT_NEAR(shear_speed(aluminium), std::sqrt(70e9 / (2.0 * 2700.0 * 1.33)), 1e-9);
  for (const int moving : {0, 1}) {
    const double c = moving == 0 ? dilatational_speed(aluminium) : shear_speed(aluminium);
    const double k = std::numbers::pi;
    const int elements = 64;
    const Mode m = standing_wave(elements, moving);
    // The measured frequency is the discrete closed form's ...
    EXPECT_NEAR(m.omega / discrete_frequency(c, k, 1.0 / elements, m.dt), 1.0, 1e-5) << "component " << moving;
    // ... and the phase speed is the continuum's to O((kh)^2).
    EXPECT_NEAR(m.omega / k / c, 1.0, 2e-4) << "component " << moving;
  }
}

TEST(Plate, DispersionErrorFallsAsTheSquareOfTheElementSize) {
  for (const int moving : {0, 1}) {
    const double c = moving == 0 ? dilatational_speed(aluminium) : shear_speed(aluminium);
    const double k = std::numbers::pi;
    const double coarse = std::abs(standing_wave(8, moving).omega / (c * k) - 1.0);
    const double fine = std::abs(standing_wave(16, moving).omega / (c * k) - 1.0);
    const double order = std::log2(coarse / fine);
    EXPECT_NEAR(order, 2.0, 0.05) << "component " << moving << ": errors " << coarse << ", " << fine;
  }
}

// Patch test (Zienkiewicz & Taylor, vol. 1, ch. 9): bilinear elements reproduce a linear displacement
// field exactly, so K u vanishes at interior nodes and, on the edges, equals the uniform stress's
// traction times the thickness times each node's share of the edge (half at the ends).
TEST(Plate, LinearDisplacementLoadsOnlyTheEdges) {
  const PlateEdges free_edges{EdgeCondition::free, EdgeCondition::free, EdgeCondition::free, EdgeCondition::free};
  const ElasticPlate plate(aluminium, {7, 5, 0.07, 0.03}, free_edges);  // 10 mm x 6 mm elements
  const double exx = 1e-4, eyy = -3e-5, dux_dy = 2e-5, duy_dx = 5e-5;
  std::vector<double> u(static_cast<std::size_t>(plate.dof_count())), f(u.size(), 0.0);
  for (int n = 0; n < plate.node_count(); ++n) {
    u[static_cast<std::size_t>(2 * n)] = exx * plate.node_x(n) + dux_dy * plate.node_y(n);
    u[static_cast<std::size_t>(2 * n + 1)] = duy_dx * plate.node_x(n) + eyy * plate.node_y(n);
  }
  plate.add_elastic_forces(u, f);
  const double nu = aluminium.poisson_ratio, e = aluminium.youngs_modulus / (1.0 - nu * nu), t = aluminium.thickness;
  const double sxx = e * (exx + nu * eyy), syy = e * (eyy + nu * exx), sxy = e * 0.5 * (1.0 - nu) * (dux_dy + duy_dx);
  const int nx = plate.mesh().elements_x, ny = plate.mesh().elements_y;
  const double a = plate.element_width(), b = plate.element_height();
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double along_x = (i == 0 || i == nx ? 0.5 : 1.0) * a * t, along_y = (j == 0 || j == ny ? 0.5 : 1.0) * b * t;
      double fx = 0.0, fy = 0.0;  // K u: the load that holds the field
      if (i == 0) fx -= sxx * along_y, fy -= sxy * along_y;
      if (i == nx) fx += sxx * along_y, fy += sxy * along_y;
      if (j == 0) fx -= sxy * along_x, fy -= syy * along_x;
      if (j == ny) fx += sxy * along_x, fy += syy * along_x;
      const auto n = static_cast<std::size_t>(plate.node(i, j));
      EXPECT_NEAR(-f[2 * n], fx, 1e-9 * sxx * b * t) << "node " << i << ", " << j;
      EXPECT_NEAR(-f[2 * n + 1], fy, 1e-9 * sxx * b * t) << "node " << i << ", " << j;
    }
}

// The forces of an arbitrary field are the element matrices' products summed over the elements
// (the assembly written here from element_stiffness() and its node order), on elements wider than
// tall and on square ones at nu = 0; elastic_forces writes them over whatever f held; and
// add_top_row_forces adds (sign 1) or takes away (sign -1) the top row of elements' alone, touching
// no other entry.
TEST(Plate, ForcesAreTheSumOfElementProducts) {
  const PlateMaterial stiff_no_poisson{200e9, 0.0, 7850.0, 1e-3};
  for (const auto& plate : {ElasticPlate(aluminium, {6, 4, 0.06, 0.02}, PlateEdges{}),
                            ElasticPlate(stiff_no_poisson, {5, 7, 0.05, 0.07}, PlateEdges{})}) {
    std::vector<double> u(static_cast<std::size_t>(plate.dof_count())), f(u.size(), 0.0), assembled(u.size(), 0.0);
    for (std::size_t d = 0; d < u.size(); ++d) u[d] = 1e-6 * std::sin(1.7 * static_cast<double>(d * d % 97));
    plate.add_elastic_forces(u, f);
    std::vector<double> written(u.size(), std::numeric_limits<double>::quiet_NaN());
    plate.elastic_forces(u, written);
    const auto& k = plate.element_stiffness();
    const int top_row = plate.mesh().elements_y - 1;
    std::vector<double> top(u.size(), 0.0);
    for (int j = 0; j < plate.mesh().elements_y; ++j)
      for (int i = 0; i < plate.mesh().elements_x; ++i) {
        const int nodes[4] = {plate.node(i, j), plate.node(i + 1, j), plate.node(i + 1, j + 1), plate.node(i, j + 1)};
        for (int r = 0; r < 8; ++r)
          for (int c = 0; c < 8; ++c) {
            const double product = k(r, c) * u[static_cast<std::size_t>(2 * nodes[c / 2] + c % 2)];
            assembled[static_cast<std::size_t>(2 * nodes[r / 2] + r % 2)] -= product;
            if (j == top_row) top[static_cast<std::size_t>(2 * nodes[r / 2] + r % 2)] -= product;
          }
      }
    double largest = 0.0;
    for (const double v : assembled) largest = std::max(largest, std::abs(v));
    std::vector<double> added(u.size(), 1.0), taken(u.size(), 1.0);
    plate.add_top_row_forces(u, added);
    plate.add_top_row_forces(u, taken, -1.0);
    for (std::size_t d = 0; d < u.size(); ++d) {
      EXPECT_NEAR(f[d], assembled[d], 1e-12 * largest) << "dof " << d;
      EXPECT_EQ(written[d], f[d]) << "dof " << d;
      EXPECT_NEAR(added[d] - 1.0, top[d], 1e-12 * largest) << "dof " << d;
      EXPECT_NEAR(1.0 - taken[d], top[d], 1e-12 * largest) << "dof " << d;
      if (d < static_cast<std::size_t>(2 * plate.node(0, top_row))) {  // below the two top rows of nodes
        EXPECT_EQ(added[d], 1.0) << "dof " << d;
        EXPECT_EQ(taken[d], 1.0) << "dof " << d;
      }
    }
    EXPECT_THROW(plate.add_top_row_forces(u, added, 0.5), std::invalid_argument);
  }
}

TEST(Plate, ElementBoundBoundsTheMeshFrequency) {
  // The 1D chain's highest frequency 2c/h must lie below Irons' element bound, which a clamped
  // square mesh's highest mode (found by power iteration) must not exceed either.
  ElasticPlate plate(aluminium, {10, 6, 0.1, 0.06}, PlateEdges{});
  EXPECT_GT(plate.max_frequency_bound(), 2.0 * dilatational_speed(aluminium) / plate.element_width());
  std::vector<double> x(static_cast<std::size_t>(plate.dof_count()));
  for (std::size_t d = 0; d < x.size(); ++d) x[d] = (d % 7 == 0 ? 1.0 : -0.3) * (plate.fixed()[d] ? 0.0 : 1.0);
  double lambda = 0.0;
  for (int it = 0; it < 3000; ++it) {
    std::vector<double> f(x.size(), 0.0);
    plate.add_elastic_forces(x, f);
    double norm = 0.0, rayleigh = 0.0;
    for (std::size_t d = 0; d < x.size(); ++d) {
      f[d] = plate.fixed()[d] ? 0.0 : -f[d] / plate.mass()[d];
      rayleigh += x[d] * f[d];
      norm += f[d] * f[d];
    }
    double xx = 0.0;
    for (const double v : x) xx += v * v;
    lambda = rayleigh / xx;
    for (std::size_t d = 0; d < x.size(); ++d) x[d] = f[d] / std::sqrt(norm);
  }
  EXPECT_LE(std::sqrt(lambda), plate.max_frequency_bound());
  EXPECT_GT(std::sqrt(lambda), 0.7 * plate.max_frequency_bound());  // and the bound is not loose
}

// A right-going Gaussian pulse in a strip meets the right edge; returns the energy left in the strip
// and the balance error (mechanical + absorbed - initial) relative to the initial energy.
struct Reflection {
  double left;
  double balance_error;
};
Reflection reflect(EdgeCondition right, int moving, double tolerance) {
  const int elements = 400;
  const double length = 1.0, width = 0.04, start = 0.5;
  const PlateEdges edges{EdgeCondition::free, EdgeCondition::free, EdgeCondition::free, right};
  auto run = plate_only(strip(elements, length, 1 - moving, edges), tolerance);
  const double c = moving == 0 ? dilatational_speed(aluminium) : shear_speed(aluminium);
  auto& u = run.plate_displacement_mutable();
  auto& v = run.plate_velocity_mutable();
  for (int node = 0; node < run.plate()->node_count(); ++node) {
    const double s = (run.plate()->node_x(node) - start) / width;
    u[static_cast<std::size_t>(2 * node + moving)] = 1e-6 * std::exp(-s * s);
    v[static_cast<std::size_t>(2 * node + moving)] = 1e-6 * c * 2.0 * s / width * std::exp(-s * s);  // u(x - ct)
  }
  run.refresh_forces();
  const double initial = run.energies().mechanical();
  run.advance_to((length - start + 5.0 * width) / c);
  const auto e = run.energies();
  return {e.mechanical() / initial, (e.balance() - initial) / initial};
}

TEST(Plate, AbsorbingEdgeTakesANormallyIncidentPulse) {
  for (const int moving : {0, 1}) {
    const Reflection free_edge = reflect(EdgeCondition::free, moving, 0.5);
    EXPECT_NEAR(free_edge.left, 1.0, 1e-6) << "a free edge reflects everything";
    const Reflection absorbing = reflect(EdgeCondition::absorbing, moving, 0.5);
    EXPECT_LT(absorbing.left, 1e-4) << "component " << moving;
    // The dashpots' work closes the balance up to central differences' energy error, O((omega dt)^2)
    // (3e-4 at tolerance 0.5): at 0.03 below 1e-6.
    const Reflection fine = reflect(EdgeCondition::absorbing, moving, 0.03);
    EXPECT_LT(std::abs(fine.balance_error), 1e-6) << "component " << moving;
    EXPECT_LT(fine.left, 1e-4);
  }
}

}  // namespace
