#include "sedwave/forward/linear/static_equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/linear/dynamic_matrices.hpp"
#include "sedwave/forward/linear/slab_solver.hpp"

namespace sedwave::forward::linear {
namespace {

constexpr double kLongestStep = 0.1;  ///< relative displacement across a contact per step, in mean radii

/// Forces and energy of one configuration.
struct State {
  ContactNetwork network;
  std::vector<dem::Vec3> force;   ///< total contact force per grain
  double contact_energy = 0.0;
  double energy = 0.0;            ///< contacts + F (height of the loaded wall above where it started)
  double wall_force = 0.0;        ///< grains on the loaded wall, along +z
  double residual_ratio = 0.0;    ///< max |F| on a free grain / mean contact force
};

State evaluate(std::span<const dem::Grain> grains, const dem::Box& box, const dem::ContactSpec& contact,
               const LoadedWall* wall, double wall_lift) {
  State s;
  s.network = channel::find_contacts(grains, box, contact);
  s.force.assign(grains.size(), dem::Vec3{});
  double force_sum = 0.0;
  for (const StaticPair& p : s.network.contacts) {
    const dem::Vec3 f = p.force * p.normal;  // on i; -f on j
    s.force[static_cast<std::size_t>(p.i)] += f;
    s.force[static_cast<std::size_t>(p.j)] -= f;
    s.contact_energy += p.energy;
    force_sum += p.force;
  }
  double largest = 0.0;
  for (std::size_t g = 0; g < grains.size(); ++g) {
    if (grains[g].body == dem::kFreeBody) largest = std::max(largest, dem::norm(s.force[g]));
    else if (wall && grains[g].body == wall->body) s.wall_force += s.force[g].z;
  }
  const double mean_force = s.network.contacts.empty() ? 0.0 : force_sum / static_cast<double>(s.network.contacts.size());
  s.residual_ratio = mean_force > 0.0 ? largest / mean_force : std::numeric_limits<double>::infinity();
  s.energy = s.contact_energy + (wall ? wall->force * wall_lift : 0.0);
  return s;
}

bool converged(const State& s, const LoadedWall* wall, const StaticEquilibriumSettings& settings) {
  if (!(s.residual_ratio < settings.residual_force_tolerance)) return false;
  return !wall || std::abs(s.wall_force / wall->force - 1.0) < settings.wall_force_tolerance;
}

/// A damped Newton step: the free grains' displacements (in node order) and the wall's lift.
struct Step {
  Eigen::VectorXd displacement;
  double lift = 0.0;
};

Step newton_step(const State& s, const DynamicMatrices& m, const SlabSolver& solver, const LoadedWall* wall,
                 double wall_mass, double shift) {
  const Eigen::Index n = m.unknowns();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, wall ? 2 : 1);
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    const dem::Vec3& f = s.force[static_cast<std::size_t>(m.grain_of_node[node])];
    rhs.block<3, 1>(static_cast<Eigen::Index>(3 * node), 0) = Eigen::Vector3d(f.x, f.y, f.z);
  }
  if (!wall) return {solver.solve_shifted(shift, rhs).col(0), 0.0};
  // Bordered system [K b; b^T c] [du; dZ] = [F; F_wall - F]: eliminate the wall's row.
  const BodyCoupling& coupling = m.bodies[static_cast<std::size_t>(wall->body - 1)];
  rhs.col(1) = Eigen::VectorXd(coupling.stiffness.col(2));
  const Eigen::MatrixXd x = solver.solve_shifted(shift, rhs);
  const double wall_residual = s.wall_force - wall->force;
  const double pivot = coupling.self_stiffness(2, 2) + shift * wall_mass - rhs.col(1).dot(x.col(1));
  const double lift = (wall_residual - rhs.col(1).dot(x.col(0))) / pivot;
  return {x.col(0) - lift * x.col(1), lift};
}

/// The largest relative displacement across a contact, or of the loaded wall, in a step: the trust
/// region. A uniform translation or a long-wavelength strain, which Newton must take in one step,
/// costs nothing; contacts sliding past or into each other do.
double relative_reach(const ContactNetwork& network, std::span<const dem::Grain> grains, const DynamicMatrices& m,
                      const Step& step, const LoadedWall* wall) {
  auto displacement = [&](std::int32_t g) -> Eigen::Vector3d {
    const std::int32_t node = m.node_of_grain[static_cast<std::size_t>(g)];
    if (node >= 0) return step.displacement.segment<3>(static_cast<Eigen::Index>(3 * node));
    if (wall && grains[static_cast<std::size_t>(g)].body == wall->body) return {0.0, 0.0, step.lift};
    return Eigen::Vector3d::Zero();
  };
  double reach = std::abs(step.lift);  // the wall may have nothing to touch yet
  for (const StaticPair& p : network.contacts) reach = std::max(reach, (displacement(p.i) - displacement(p.j)).norm());
  return reach;
}

std::vector<dem::Grain> moved(std::span<const dem::Grain> grains, const DynamicMatrices& m, const Step& step,
                              const dem::Box& box, const LoadedWall* wall) {
  std::vector<dem::Grain> out(grains.begin(), grains.end());
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    dem::Grain& g = out[static_cast<std::size_t>(m.grain_of_node[node])];
    const auto row = static_cast<Eigen::Index>(3 * node);
    g.position += dem::Vec3{step.displacement(row), step.displacement(row + 1), step.displacement(row + 2)};
    box.wrap(g.position);
  }
  if (wall) {
    for (dem::Grain& g : out) {
      if (g.body == wall->body) g.position.z += step.lift;
    }
  }
  return out;
}

}  // namespace

StaticEquilibriumReport relax_to_equilibrium(std::vector<dem::Grain>& grains, const dem::Box& box,
                                             const dem::ContactSpec& contact, int n_bodies, const LoadedWall* wall,
                                             const StaticEquilibriumSettings& settings) {
  if (contact.tangential != dem::TangentialLawKind::none || contact.rolling != dem::RollingLawKind::none) {
    throw std::invalid_argument("static equilibrium: only frictionless packings (normal laws alone) are relaxed");
  }
  if (wall && (wall->body < 1 || wall->body > n_bodies || !(wall->force > 0.0))) {
    throw std::invalid_argument("static equilibrium: the loaded wall needs a rigid body and a positive force");
  }
  double free_mass = 0.0, free_radius = 0.0, wall_mass = 0.0;
  std::size_t n_free = 0;
  for (const dem::Grain& g : grains) {
    if (g.body == dem::kFreeBody) {
      free_mass += g.mass;
      free_radius += g.radius;
      ++n_free;
    } else if (wall && g.body == wall->body) {
      wall_mass += g.mass;
    }
  }
  const double mean_mass = n_free > 0 ? free_mass / static_cast<double>(n_free) : 1.0;
  // Trust region: no two touching grains move further than this relative to each other in one step,
  // so a step never carries grains through each other (the pair energy is bounded).
  const double longest_step = kLongestStep * (n_free > 0 ? free_radius / static_cast<double>(n_free) : 0.5);

  StaticEquilibriumReport report;
  double lift = 0.0;
  State current = evaluate(grains, box, contact, wall, lift);
  const double start_energy = current.energy;
  // Levenberg-Marquardt shift in units of the mean contact stiffness per mean grain mass.
  // A shift beyond kStalled means no step along any direction lowers the energy: a contact at the
  // edge of opening (Hooke keeps its full stiffness down to zero overlap, a kink in the energy)
  // flips in and out. The caller then finishes with a method that does not need derivatives.
  constexpr double kSmallest = 1e-10, kFirst = 1e-4, kGrow = 10.0, kShrink = 0.1, kStalled = 1e4;
  double lambda = kFirst;
  while (!converged(current, wall, settings) && report.iterations < settings.max_iterations &&
         !current.network.contacts.empty() && lambda <= kStalled) {
    const DynamicMatrices m = assemble(grains, current.network, n_bodies, contact);
    const SlabSolver solver(m, node_heights(grains, m));
    const double stiffness_per_mass = current.network.mean_stiffness / mean_mass;
    // Retry from the same configuration with a larger shift until the energy falls.
    while (report.iterations < settings.max_iterations && lambda <= kStalled) {
      ++report.iterations;
      const Step step = newton_step(current, m, solver, wall, wall_mass, lambda * stiffness_per_mass);
      if (!(relative_reach(current.network, grains, m, step, wall) <= longest_step)) {
        lambda = std::max(kFirst, lambda * kGrow);
        continue;
      }
      std::vector<dem::Grain> trial = moved(grains, m, step, box, wall);
      State next = evaluate(trial, box, contact, wall, lift + step.lift);
      // Near the minimum the energy change sinks below round-off; the residual then decides.
      const double round_off = 1e-12 * std::abs(current.contact_energy);
      const bool downhill = next.energy < current.energy - round_off ||
                            (next.energy <= current.energy + round_off && next.residual_ratio < current.residual_ratio);
      if (downhill && std::isfinite(next.energy)) {
        grains = std::move(trial);
        lift += step.lift;
        current = std::move(next);
        ++report.accepted;
        lambda = std::max(kSmallest, lambda * kShrink);
        break;
      }
      lambda = std::max(kFirst, lambda * kGrow);
    }
  }
  report.residual_ratio = current.residual_ratio;
  report.wall_force = current.wall_force;
  report.energy_drop = start_energy - current.energy;
  report.converged = converged(current, wall, settings);
  return report;
}

}  // namespace sedwave::forward::linear
