#include "sedwave/forward/linear/linear_channel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/linear/equivalent_linearisation.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward::linear {
namespace {

using Complex = std::complex<double>;

int axis_index(channel::DriveAxis axis) { return axis == channel::DriveAxis::longitudinal ? 2 : 0; }

/// [a b; b^T self]: a symmetric matrix bordered by one more unknown.
Eigen::SparseMatrix<double> bordered(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b, double self) {
  const Eigen::Index n = a.rows();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(a.nonZeros() + 2 * n + 1));
  for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (b(i) == 0.0) continue;
    t.emplace_back(i, n, b(i));
    t.emplace_back(n, i, b(i));
  }
  t.emplace_back(n, n, self);
  Eigen::SparseMatrix<double> m(n + 1, n + 1);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

/// A checked fluid in the packing's units (none for a dry channel). Checked after the conversion,
/// which resolves a porosity of 0 to the packing's.
std::optional<dem::FluidSpec> in_packing_units(const std::optional<dem::FluidSpec>& fluid,
                                               const channel::PackingUnits& units) {
  if (!fluid) return std::nullopt;
  dem::FluidSpec f = channel::fluid_in_packing_units(*fluid, units);
  if (const std::string why = f.problem(); !why.empty()) throw std::invalid_argument("linear engine: fluid " + why);
  return f;
}

/// Gaps up to the user's search distance and, with a fluid, its lubrication cut-off [d].
double gap_search(const LinearSettings& settings, const std::optional<dem::FluidSpec>& fluid) {
  return std::max(settings.gap_search, fluid ? fluid->interaction_gap() : 0.0);
}

void check_drive(const channel::DriveSettings& d) {
  if (!(d.omega_hat > 0.0) || !(d.gamma_hat >= 0.0) || !(d.amplitude > 0.0)) {
    throw std::invalid_argument("linear engine: omega_hat and amplitude must be positive, gamma_hat non-negative");
  }
  if (d.far_end != channel::FarEnd::absorbing) {
    throw std::invalid_argument(
        "linear engine: the far end must be absorbing (in a steady state a frozen end reflects the whole wave)");
  }
}

const channel::PreparedChannel& open_along_z(const channel::PreparedChannel& packing) {
  if (packing.box.periodic[2]) {
    throw std::invalid_argument("linear engine: channels must be open along z (a periodic cell is tiled first: "
                                "channel/periodic_cell.hpp)");
  }
  return packing;
}

}  // namespace

LinearChannel::LinearChannel(const channel::PreparedChannel& packing, const dem::ContactSpec& contact,
                             LinearSettings settings, std::optional<dem::FluidSpec> fluid)
    : grains_(open_along_z(packing).grains),
      cross_section_(packing.box.length(0) * packing.box.length(1)),
      contact_(contact),
      model_(dem::make_contact_model(contact)),
      settings_(settings),
      units_(channel::packing_units(MPI_COMM_SELF, packing, contact)),
      fluid_(std::move(fluid)),
      packing_fluid_(in_packing_units(fluid_, units_)),
      network_(channel::find_contacts(grains_, packing.box, contact, gap_search(settings, fluid_) * units_.diameter)),
      matrices_(assemble(grains_, network_, 2, contact, nullptr, packing_fluid())),
      solver_(matrices_, node_heights(grains_, matrices_)) {
}

void LinearChannel::check(const channel::DriveSettings& d) const {
  check_drive(d);
  if (d.fluid != fluid_) {
    throw std::invalid_argument(std::string("linear engine: the drive's pore fluid differs from the one the channel "
                                            "was assembled with (") +
                                (fluid_ ? "a fluid" : "dry") + "); build the LinearChannel with the drive's fluid");
  }
}

Eigen::VectorXd LinearChannel::sponge(const channel::DriveSettings& d, double omega) const {
  // The time-domain engine's absorbing layer, on every free grain's translations.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(matrices_.unknowns());
  for (std::size_t n = 0; n < matrices_.grain_of_node.size(); ++n) {
    const double z = grains_[static_cast<std::size_t>(matrices_.grain_of_node[n])].position.z;
    c.segment<3>(static_cast<Eigen::Index>(matrices_.dofs_per_node * n))
        .setConstant(channel::absorbing_drag(d, units_, omega, z));
  }
  return c;
}

Eigen::VectorXcd LinearChannel::displacement(const channel::DriveSettings& d) const {
  check(d);
  return solve(matrices_, solver_, d);
}

Eigen::VectorXcd LinearChannel::solve(const DynamicMatrices& m, const SlabSolver& solver,
                                      const channel::DriveSettings& d) const {
  const double omega = d.omega_hat / units_.time();
  const double gamma = d.gamma_hat * units_.damping_scale;
  // A body's translation along `axis` pulls the free grains with (K_b + i omega (gamma C1_b + C_t,b)) e_axis.
  auto coupling = [&](const BodyCoupling& b, int axis) -> Eigen::VectorXcd {
    return b.stiffness.col(axis).cast<Complex>() + Complex(0.0, omega * gamma) * b.dashpots.col(axis).cast<Complex>() +
           Complex(0.0, omega) * b.fixed_dashpots.col(axis).cast<Complex>();
  };
  const Eigen::VectorXcd drive = -coupling(m.bodies[channel::kLowerWallBody - 1], axis_index(d.axis));
  const Eigen::VectorXd drag = sponge(d, omega);
  if (d.far_wall == channel::FarWall::frozen) return solver.solve(omega, gamma, drag, drive);

  // A loaded far wall's z translation w borders the grains' system A u = f:
  //   [A b; b^T a] [u; w] = [f; 0],
  // b its coupling column, a its own dynamic stiffness. Both columns go through one elimination;
  // the slabs' band stays as it is.
  const BodyCoupling& top = m.bodies[channel::kUpperWallBody - 1];
  Eigen::MatrixXcd rhs(m.unknowns(), 2);
  rhs.col(0) = drive;
  rhs.col(1) = coupling(top, 2);
  const Eigen::MatrixXcd x = solver.solve(omega, gamma, drag, rhs);
  const Complex a = top.self_stiffness(2, 2) +
                    Complex(0.0, omega) * (gamma * top.self_dashpots(2, 2) + top.self_fixed_dashpots(2, 2)) -
                    omega * omega * channel::loaded_wall_mass(d, units_, grains_);
  const Eigen::VectorXcd border = rhs.col(1);
  const BorderedSolution<Complex> s = eliminate_border<Complex>(x, border, a, Complex(0.0));
  Eigen::VectorXcd u(m.unknowns() + 1);
  u << s.u, s.w;
  return u;
}

Eigen::Matrix<std::complex<double>, 6, 1> LinearChannel::grain_motion(const Eigen::VectorXcd& u,
                                                                       const channel::DriveSettings& d,
                                                                       std::int32_t grain) const {
  Eigen::Matrix<Complex, 6, 1> motion = Eigen::Matrix<Complex, 6, 1>::Zero();
  const std::int32_t node = matrices_.node_of_grain[static_cast<std::size_t>(grain)];
  if (node >= 0) {
    const int dofs = matrices_.dofs_per_node;
    motion.head(dofs) = u.segment(dofs * static_cast<Eigen::Index>(node), dofs);
  } else if (grains_[static_cast<std::size_t>(grain)].body == channel::kLowerWallBody) {
    motion(axis_index(d.axis)) = 1.0;  // unit motion of the driven wall
  } else if (d.far_wall == channel::FarWall::loaded) {
    motion(2) = u(matrices_.unknowns());  // the loaded far wall's unknown, after the grains'
  }
  return motion;
}

std::complex<double> LinearChannel::normal_motion(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                                  const StaticPair& p) const {
  const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
  return n.cast<Complex>().dot((grain_motion(u, d, p.i) - grain_motion(u, d, p.j)).head<3>());
}

double LinearChannel::sliding_onset(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                    const StaticPair& p) const {
  const std::optional<dem::TangentialBlock> sticking = tangential_block(p);
  if (!sticking) return std::numeric_limits<double>::infinity();
  const double omega = d.omega_hat / units_.time();
  const double gamma = d.gamma_hat * units_.damping_scale;
  // Per unit wall amplitude: the tangential force and the normal force, spring and dashpot (the
  // overlap shrinks as n . (u_i - u_j) grows).
  const Eigen::Vector3cd tangential = tangential_force(u, d, p);
  const Complex normal = -(p.stiffness + Complex(0.0, omega * gamma * p.dashpot)) * normal_motion(u, d, p);
  // At phase theta the contact sticks while A |Re(F_t e^{i theta})| <= mu (F_0 + A Re(F_n e^{i theta})),
  // linear in A at each phase: the onset is mu F_0 / max over theta of (|Re F_t e^{i theta}| - mu Re F_n e^{i theta}),
  // taken over 256 phases (the maximum of a smooth periodic function: error ~ (2 pi / 256)^2 / 8).
  const double mu = sticking->friction;
  double worst = 0.0;
  constexpr int kPhases = 256;
  for (int k = 0; k < kPhases; ++k) {
    const Complex turn = std::polar(1.0, 2.0 * std::numbers::pi * k / kPhases);
    worst = std::max(worst, (tangential * turn).real().norm() - mu * (normal * turn).real());
  }
  return worst > 0.0 ? mu * p.force / worst : std::numeric_limits<double>::infinity();
}

std::optional<dem::TangentialBlock> LinearChannel::tangential_block(const StaticPair& p) const {
  return dem::tangential_block(model_, p.overlap, grains_[static_cast<std::size_t>(p.i)].radius,
                               grains_[static_cast<std::size_t>(p.j)].radius);
}

Eigen::Vector3cd LinearChannel::tangential_force(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                                const StaticPair& p) const {
  const double omega = d.omega_hat / units_.time();
  const SlipOperators t = slip_operators(p);
  const Eigen::Vector3cd slip =
      t.i.cast<Complex>() * grain_motion(u, d, p.i) + t.j.cast<Complex>() * grain_motion(u, d, p.j);
  const dem::TangentialBlock sticking = *tangential_block(p);
  return -(sticking.stiffness + Complex(0.0, omega * sticking.damping_per_mass * p.effective_mass)) * slip;
}

Eigen::Vector3cd LinearChannel::contact_force(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                              const StaticPair& p) const {
  const double omega = d.omega_hat / units_.time();
  const double gamma = d.gamma_hat * units_.damping_scale;
  const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);
  const Eigen::Matrix3d nn = n * n.transpose();
  const Eigen::Matrix3cd normal =
      (p.stiffness * nn - (p.force / p.distance) * (Eigen::Matrix3d::Identity() - nn)).cast<Complex>() +
      Complex(0.0, omega * gamma * p.dashpot) * nn.cast<Complex>();
  Eigen::Vector3cd f = -normal * (grain_motion(u, d, p.i) - grain_motion(u, d, p.j)).head<3>();
  if (matrices_.dofs_per_node == 6) f += tangential_force(u, d, p);
  return f;
}

StateChanges LinearChannel::state_changes(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                          double amplitude) const {
  return state_changes(u, d, std::span(&amplitude, 1)).front();
}

std::vector<StateChanges> LinearChannel::state_changes(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                                       std::span<const double> amplitudes) const {
  // A pair's normal motion and sliding onset per unit amplitude do not depend on the amplitude.
  std::vector<double> contact_motion, onset, gap_motion;
  for (const StaticPair& p : network_.contacts) {
    contact_motion.push_back(std::abs(normal_motion(u, d, p)));
    onset.push_back(sliding_onset(u, d, p));
  }
  for (const StaticPair& p : network_.gaps) gap_motion.push_back(std::abs(normal_motion(u, d, p)));
  std::vector<StateChanges> changes;
  for (const double amplitude : amplitudes) {
    const double scale = amplitude * units_.diameter;
    StateChanges s;
    s.amplitude = amplitude;
    s.contacts = static_cast<std::int64_t>(network_.contacts.size());
    s.gaps = static_cast<std::int64_t>(network_.gaps.size());
    for (std::size_t k = 0; k < network_.contacts.size(); ++k) {
      if (scale * contact_motion[k] > network_.contacts[k].overlap) {
        ++s.opening;
      } else if (scale > onset[k]) {
        ++s.sliding;
      }
    }
    for (std::size_t k = 0; k < network_.gaps.size(); ++k) {
      s.closing += scale * gap_motion[k] > -network_.gaps[k].overlap ? 1 : 0;
    }
    changes.push_back(s);
  }
  return changes;
}

LinearResult LinearChannel::respond(const channel::DriveSettings& d) const {
  const auto started = std::chrono::steady_clock::now();
  LinearResult r = measure(displacement(d), d, true);
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

PairLinearisation LinearChannel::equivalent_pairs(const Eigen::VectorXcd& u, const channel::DriveSettings& d) const {
  const double scale = d.amplitude * units_.diameter;
  PairLinearisation pairs;
  auto add = [&](const StaticPair& p) {
    const double r_i = grains_[static_cast<std::size_t>(p.i)].radius, r_j = grains_[static_cast<std::size_t>(p.j)].radius;
    const auto force = [&](double delta) {
      return dem::static_normal_force(model_, delta, r_i, r_j);
    };
    const EquivalentContact e = equivalent_contact(force, p.overlap, scale * std::abs(normal_motion(u, d, p)), p.stiffness);
    pairs.stiffness.push_back(e.stiffness);
    pairs.dashpot.push_back(e.dashpot);
  };
  for (const StaticPair& p : network_.contacts) add(p);
  for (const StaticPair& p : network_.gaps) add(p);
  return pairs;
}

LinearResult LinearChannel::respond_equivalent(const channel::DriveSettings& d, int max_iterations,
                                               double tolerance) const {
  const auto started = std::chrono::steady_clock::now();
  Eigen::VectorXcd u = displacement(d);
  const std::vector<double> z = node_heights(grains_, matrices_);
  PairLinearisation pairs;
  double change = 1.0;
  int iterations = 0;
  while (iterations < max_iterations && change > tolerance) {
    PairLinearisation next = equivalent_pairs(u, d);
    if (iterations > 0) {
      // Under-relaxed: a clapping contact's stiffness and its amplitude feed back on each other.
      for (std::size_t q = 0; q < next.stiffness.size(); ++q) {
        next.stiffness[q] = 0.5 * (next.stiffness[q] + pairs.stiffness[q]);
        next.dashpot[q] = 0.5 * (next.dashpot[q] + pairs.dashpot[q]);
      }
    }
    pairs = std::move(next);
    // The fluid's dashpots stay those of the static state: drag and the squeeze film are linear in
    // the velocities, and where a contact claps or a gap closes the film keeps its static gap's
    // coefficient rather than a cycle average (the film between the asperities of a contact acts at
    // the roughness gap whether or not the contact carries load; FluidSpec's regularisation).
    const DynamicMatrices m = assemble(grains_, network_, 2, contact_, &pairs, packing_fluid());
    const Eigen::VectorXcd updated = solve(m, SlabSolver(m, z), d);
    change = (updated - u).norm() / u.norm();
    u = updated;
    ++iterations;
  }
  LinearResult r = measure(u, d, false);
  r.iterations = iterations;
  if (change > tolerance) {
    r.warning += (r.warning.empty() ? "" : "; ") + std::string("equivalent linearisation did not converge (change ") +
                 std::to_string(change) + " after " + std::to_string(iterations) + " iterations)";
  }
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

LinearResult LinearChannel::measure(const Eigen::VectorXcd& u, const channel::DriveSettings& d, bool refuse) const {
  const int axis = axis_index(d.axis);

  LinearResult r;
  r.omega_hat = d.omega_hat;
  r.gamma_hat = d.gamma_hat;
  r.amplitude = d.amplitude;
  const channel::LayerGrid grid(units_, d.layer_thickness);
  r.layer_grains.assign(static_cast<std::size_t>(grid.count), 0);
  r.layer_field.assign(static_cast<std::size_t>(grid.count), Complex(0.0));
  for (std::size_t n = 0; n < matrices_.grain_of_node.size(); ++n) {
    const dem::Grain& g = grains_[static_cast<std::size_t>(matrices_.grain_of_node[n])];
    if (g.group != channel::kFlowGroup) continue;
    const auto layer = static_cast<std::size_t>(grid.index(g.position.z));
    r.layer_field[layer] += u(static_cast<Eigen::Index>(matrices_.dofs_per_node * n) + axis);
    ++r.layer_grains[layer];
  }
  for (int k = 0; k < grid.count; ++k) {
    const auto layer = static_cast<std::size_t>(k);
    if (r.layer_grains[layer] > 0) r.layer_field[layer] /= static_cast<double>(r.layer_grains[layer]);
  }
  r.layer_z = grid.centres();

  const auto [first, fitted_end] = channel::fitted_layers(d, r.layer_z);
  // Where a long channel attenuates the wave by more than 10^250 (say 10^4 d at alpha_hat = 0.14),
  // the deeper layers' field underflows to zero and has no phase: the fit stops before them.
  double peak = 0.0;
  for (std::size_t k = first; k < fitted_end; ++k) peak = std::max(peak, std::abs(r.layer_field[k]));
  std::size_t last = first;
  while (last < fitted_end && std::abs(r.layer_field[last]) > 1e-250 * peak) ++last;
  std::vector<double> amplitudes{d.amplitude};
  for (double a = 1e-7; a < 2e-2; a *= 10.0) amplitudes.push_back(a);
  const std::vector<StateChanges> counted = state_changes(u, d, amplitudes);
  r.state_changes = counted.front();
  r.amplitude_ladder.assign(counted.begin() + 1, counted.end());
  if (last < first + 4) {
    r.problem = "channel too short: fewer than 4 layers between the near field and the absorbing layer";
  } else {
    std::vector<channel::LockIn> probes;
    for (std::size_t k = first; k < last; ++k) {
      channel::LockIn l;
      l.amplitude = std::abs(r.layer_field[k]);
      l.phase = -std::arg(r.layer_field[k]);  // x(t) = Re(U e^{i omega t}) = |U| cos(omega t - phase)
      probes.push_back(l);
    }
    r.layers_used = static_cast<int>(probes.size());
    const std::span<const double> z(r.layer_z.data() + first, last - first);
    const double expected_k = d.omega_hat / LatticeModel().evaluate(d.omega_hat, d.gamma_hat).c_hat;
    r.fit = channel::fit_attenuation_and_wavenumber(z, probes, d.omega_hat, expected_k, channel::ProbeWeights::uniform);
    r.waves = channel::fit_two_waves(d.layer_thickness, std::span(r.layer_field.data() + first, last - first),
                                     r.fit.k, r.fit.alpha);
    r.problem = channel::resolution_problem(r.fit, z.back() - z.front(), channel::absorbing_length(d, units_));
  }
  const double changed = r.state_changes.fraction();
  const std::string sliding =
      dem::has_tangential(model_)
          ? ", " + std::to_string(r.state_changes.sliding) + " slide"
          : std::string();
  const std::string changes = std::to_string(r.state_changes.opening) + " of " +
                              std::to_string(r.state_changes.contacts) + " contacts open" + sliding + " and " +
                              std::to_string(r.state_changes.closing) + " gaps close at A = " +
                              std::to_string(d.amplitude) + " d";
  if (refuse && changed > settings_.refuse_state_changes && r.problem.empty()) {
    r.problem = "linear response not valid: " + changes + "; use the time-domain engine";
  } else if (changed > settings_.warn_state_changes) {
    r.warning = (refuse ? "linear response doubtful: " : "contacts clap (equivalent linearisation): ") + changes;
  }
  return r;
}

std::vector<std::vector<double>> LinearChannel::integrate(const channel::DriveSettings& d, double time_step,
                                                         std::int64_t steps, std::int64_t steps_per_sample) const {
  check(d);
  const double t0 = units_.time();
  const double dt = time_step * t0;
  const double omega = d.omega_hat / t0;
  const double amplitude = d.amplitude * units_.diameter;
  const double gamma = d.gamma_hat * units_.damping_scale;
  const auto wall = static_cast<std::size_t>(channel::kLowerWallBody - 1);
  const int axis = axis_index(d.axis);
  // All dashpots in one matrix: one product per step in the loop below.
  // The grains' K, or a bordered copy of it with a loaded far wall.
  Eigen::SparseMatrix<double> bordered_stiffness;
  const Eigen::SparseMatrix<double>* stiffness = &matrices_.stiffness;
  Eigen::SparseMatrix<double> c = gamma * matrices_.dashpots + matrices_.fixed_dashpots;
  const BodyCoupling& body = matrices_.bodies[wall];
  Eigen::VectorXd wall_k = body.stiffness.col(axis);
  Eigen::VectorXd wall_c = gamma * body.dashpots.col(axis) + body.fixed_dashpots.col(axis);
  Eigen::VectorXd mass = matrices_.mass;
  Eigen::VectorXd sponge_drag = sponge(d, omega);
  if (d.far_wall == channel::FarWall::loaded) {
    // The loaded far wall's z translation is one more unknown, after the grains' (as displacement()).
    const BodyCoupling& top = matrices_.bodies[channel::kUpperWallBody - 1];
    bordered_stiffness = bordered(matrices_.stiffness, top.stiffness.col(2), top.self_stiffness(2, 2));
    stiffness = &bordered_stiffness;
    c = bordered(c, gamma * top.dashpots.col(2) + top.fixed_dashpots.col(2),
                 gamma * top.self_dashpots(2, 2) + top.self_fixed_dashpots(2, 2));
    const Eigen::Index n = mass.size();
    for (Eigen::VectorXd* v : {&wall_k, &wall_c, &mass, &sponge_drag}) v->conservativeResize(n + 1);
    wall_k(n) = wall_c(n) = sponge_drag(n) = 0.0;  // the two walls never touch; no drag on the wall
    mass(n) = channel::loaded_wall_mass(d, units_, grains_);
  }
  const Eigen::VectorXd inverse_mass = mass.cwiseInverse();
  const Eigen::VectorXd drag = (-(sponge_drag.array() * inverse_mass.array()) * dt).exp();

  // Layers as the time-domain engine forms them: flow grains only, fixed membership.
  const channel::LayerGrid grid(units_, d.layer_thickness);
  std::vector<int> layer_of_node(matrices_.grain_of_node.size(), -1);
  std::vector<int> count(static_cast<std::size_t>(grid.count), 0);
  for (std::size_t n = 0; n < layer_of_node.size(); ++n) {
    const dem::Grain& g = grains_[static_cast<std::size_t>(matrices_.grain_of_node[n])];
    if (g.group != channel::kFlowGroup) continue;
    layer_of_node[n] = grid.index(g.position.z);
    ++count[static_cast<std::size_t>(layer_of_node[n])];
  }
  std::vector<std::vector<double>> record(static_cast<std::size_t>(grid.count));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(mass.size()), v = u;
  auto sample = [&]() {
    std::vector<double> sum(record.size(), 0.0);
    for (std::size_t n = 0; n < layer_of_node.size(); ++n) {
      if (layer_of_node[n] >= 0) {
        sum[static_cast<std::size_t>(layer_of_node[n])] += u(static_cast<Eigen::Index>(matrices_.dofs_per_node * n) + axis);
      }
    }
    for (std::size_t k = 0; k < record.size(); ++k) {
      record[k].push_back(count[k] > 0 ? sum[k] / count[k] / units_.diameter : 0.0);
    }
  };
  // The wall as the engine moves it: on its path at the end of each step, with the step's mean
  // velocity (dem::RigidBody), which is what the dashpots see, as they see free grains' half-step
  // velocities.
  auto wall_path = [&](double t) { return amplitude * std::sin(omega * t); };
  auto force = [&](double t) -> Eigen::VectorXd {
    const double w = wall_path(t), w_dot = t > 0.0 ? (w - wall_path(t - dt)) / dt : 0.0;  // at rest at t = 0
    return -(*stiffness * u) - c * v - wall_k * w - wall_c * w_dot;
  };
  // The engine's velocity Verlet: the dashpot sees the half-step velocity, as in the DEM force loop.
  sample();
  Eigen::VectorXd f = force(0.0);
  for (std::int64_t step = 1; step <= steps; ++step) {
    v += (0.5 * dt) * inverse_mass.cwiseProduct(f);
    u += dt * v;
    f = force(static_cast<double>(step) * dt);
    v += (0.5 * dt) * inverse_mass.cwiseProduct(f);
    v = v.cwiseProduct(drag);
    if (step % steps_per_sample == 0) sample();
  }
  return record;
}

}  // namespace sedwave::forward::linear
