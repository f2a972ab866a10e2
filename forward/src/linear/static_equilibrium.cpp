#include "sedwave/forward/linear/static_equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/SparseCholesky>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/linear/dynamic_matrices.hpp"
#include "sedwave/forward/linear/slab_solver.hpp"

namespace sedwave::forward::linear {
namespace {

constexpr double kLongestStep = 0.1;  ///< relative displacement across a contact per step, in mean radii

/// Forces and energy of one configuration.
struct State {
  ContactNetwork network;         ///< contacts, and gaps narrow enough to close in one step
  std::vector<dem::Vec3> force;   ///< total contact force per grain
  double contact_energy = 0.0;
  double energy = 0.0;            ///< contacts + F (height of the loaded wall above where it started)
  double wall_force = 0.0;        ///< grains on the loaded wall, along +z
  double residual_ratio = 0.0;    ///< max |F| on a free grain / mean contact force
};

State evaluate(std::span<const dem::Grain> grains, const dem::Box& box, const dem::ContactSpec& contact,
               double gap_search, const LoadedWall* wall, double wall_lift) {
  State s;
  s.network = channel::find_contacts(grains, box, contact, gap_search);
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

/// A step: the free grains' displacements (in node order) and the loaded wall's lift.
struct Step {
  Eigen::VectorXd displacement;
  double lift = 0.0;
};

/// Displacement of grain g in a step (a free grain's own, the loaded wall's lift, or none).
Eigen::Vector3d displacement_of(std::int32_t g, std::span<const dem::Grain> grains, const DynamicMatrices& m,
                                const Step& step, const LoadedWall* wall) {
  const std::int32_t node = m.node_of_grain[static_cast<std::size_t>(g)];
  if (node >= 0) return step.displacement.segment<3>(static_cast<Eigen::Index>(3 * node));
  if (wall && grains[static_cast<std::size_t>(g)].body == wall->body) return {0.0, 0.0, step.lift};
  return Eigen::Vector3d::Zero();
}

/// Change of a pair's overlap in a step, to first order.
double overlap_change(const StaticPair& p, std::span<const dem::Grain> grains, const DynamicMatrices& m,
                      const Step& step, const LoadedWall* wall) {
  const Eigen::Vector3d n(p.normal.x, p.normal.y, p.normal.z);  // from j to i
  return -n.dot(displacement_of(p.i, grains, m, step, wall) - displacement_of(p.j, grains, m, step, wall));
}

/// The pairs (contacts, then gaps, in network order) that a step's quadratic model holds touching,
/// and the model's forces at the start of the step: the true forces, less those of the contacts it
/// lets go, plus the (tensile) spring forces of the gaps it holds closed.
struct ActiveSet {
  std::vector<bool> touching;
  std::vector<double> stiffness;  ///< per pair: tangent stiffness of a contact, of the law at zero overlap for a gap
  std::vector<dem::Vec3> force;   ///< per grain
  double wall_force = 0.0;
};

ActiveSet contacts_only(const State& s, const dem::ContactSpec& contact) {
  ActiveSet a;
  const std::size_t n_contacts = s.network.contacts.size(), n_pairs = n_contacts + s.network.gaps.size();
  a.touching.assign(n_pairs, false);
  std::fill_n(a.touching.begin(), n_contacts, true);
  a.stiffness.resize(n_pairs);
  for (std::size_t q = 0; q < n_contacts; ++q) a.stiffness[q] = s.network.contacts[q].stiffness;
  // A Hooke spring keeps its stiffness down to zero overlap; a Hertz contact has none there, so its
  // gaps never enter the model (nor need to: its energy has no kink at contact).
  const double at_contact = dem::stiffness_at_contact(dem::undamped_contact_model(contact));
  std::fill(a.stiffness.begin() + static_cast<std::ptrdiff_t>(n_contacts), a.stiffness.end(), at_contact);
  a.force = s.force;
  a.wall_force = s.wall_force;
  return a;
}

/// Sets which pairs touch and updates the model forces to match.
void set_touching(ActiveSet& a, const State& s, std::span<const dem::Grain> grains, const LoadedWall* wall,
                  const std::vector<bool>& touching) {
  const std::size_t n_contacts = s.network.contacts.size();
  for (std::size_t q = 0; q < touching.size(); ++q) {
    if (touching[q] == a.touching[q]) continue;
    const bool contact = q < n_contacts;
    const StaticPair& p = contact ? s.network.contacts[q] : s.network.gaps[q - n_contacts];
    // Force on i of the pair's model spring at the start of the step: its true force for a
    // contact, stiffness x overlap (< 0, tensile) for a gap held closed.
    const double f = contact ? p.force : a.stiffness[q] * p.overlap;
    const double sign = touching[q] ? 1.0 : -1.0;
    const dem::Vec3 fi = (sign * f) * p.normal;
    a.force[static_cast<std::size_t>(p.i)] += fi;
    a.force[static_cast<std::size_t>(p.j)] -= fi;
    if (wall && grains[static_cast<std::size_t>(p.i)].body == wall->body) a.wall_force += fi.z;
    if (wall && grains[static_cast<std::size_t>(p.j)].body == wall->body) a.wall_force -= fi.z;
  }
  a.touching = touching;
}

/// Solves (K + shift M) X = B for a step: by slab elimination along an open column (O(N)); by sparse
/// Cholesky with a fill-reducing ordering in a z-periodic cell, where the wrap-around couples the
/// first slab to the last and the block-tridiagonal structure is lost. Periodic cells are the small
/// building blocks of long channels (channel/periodic_cell.hpp), so the general solver is cheap there.
class ShiftedSolver {
 public:
  ShiftedSolver(const DynamicMatrices& m, std::span<const dem::Grain> grains, const dem::Box& box) : m_(m) {
    if (!box.periodic[2]) slabs_.emplace(m, node_heights(grains, m));
  }

  /// nullopt when K + shift M is not positive definite.
  [[nodiscard]] std::optional<Eigen::MatrixXd> solve(double shift, const Eigen::MatrixXd& rhs) const {
    if (slabs_) return slabs_->solve_shifted(shift, rhs);
    Eigen::SparseMatrix<double> a = m_.stiffness;
    for (Eigen::Index k = 0; k < a.rows(); ++k) a.coeffRef(k, k) += shift * m_.mass(k);
    const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> cholesky(a);
    if (cholesky.info() != Eigen::Success) return std::nullopt;
    return Eigen::MatrixXd(cholesky.solve(rhs));
  }

 private:
  const DynamicMatrices& m_;
  std::optional<SlabSolver> slabs_;
};

/// Solves (K + shift M) du = F of the model, bordered by the loaded wall's row; nullopt when that
/// matrix is not positive definite (then the step need not go downhill).
std::optional<Step> newton_step(const ActiveSet& a, const DynamicMatrices& m, const ShiftedSolver& solver,
                                const LoadedWall* wall, double wall_mass, double shift) {
  const Eigen::Index n = m.unknowns();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, wall ? 2 : 1);
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    const dem::Vec3& f = a.force[static_cast<std::size_t>(m.grain_of_node[node])];
    rhs.block<3, 1>(static_cast<Eigen::Index>(3 * node), 0) = Eigen::Vector3d(f.x, f.y, f.z);
  }
  if (!wall) {
    const std::optional<Eigen::MatrixXd> x = solver.solve(shift, rhs);
    if (!x) return std::nullopt;
    return Step{x->col(0), 0.0};
  }
  // Bordered system [K b; b^T c] [du; dZ] = [F; F_wall - F]. It is positive definite when K is and
  // the wall's pivot (a Schur complement) is positive.
  const BodyCoupling& coupling = m.bodies[static_cast<std::size_t>(wall->body - 1)];
  rhs.col(1) = Eigen::VectorXd(coupling.stiffness.col(2));
  const std::optional<Eigen::MatrixXd> x = solver.solve(shift, rhs);
  if (!x) return std::nullopt;
  const Eigen::VectorXd border = rhs.col(1);
  const BorderedSolution<double> s = eliminate_border<double>(
      *x, border, coupling.self_stiffness(2, 2) + shift * wall_mass, a.wall_force - wall->force);
  if (!(s.pivot > 0.0)) return std::nullopt;
  return Step{s.u, s.w};
}

/// Rate of change of the true energy along the step (minus the work of the true forces).
double slope(const State& s, const DynamicMatrices& m, const Step& step, const LoadedWall* wall) {
  double work = wall ? (s.wall_force - wall->force) * step.lift : 0.0;
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    const dem::Vec3& f = s.force[static_cast<std::size_t>(m.grain_of_node[node])];
    work += Eigen::Vector3d(f.x, f.y, f.z).dot(step.displacement.segment<3>(static_cast<Eigen::Index>(3 * node)));
  }
  return -work;
}

/// The largest relative displacement across a contact, or of the loaded wall, in a step: the trust
/// region. A uniform translation or a long-wavelength strain, which Newton must take in one step,
/// costs nothing; contacts sliding past or into each other do.
double relative_reach(const ContactNetwork& network, std::span<const dem::Grain> grains, const DynamicMatrices& m,
                      const Step& step, const LoadedWall* wall) {
  double reach = std::abs(step.lift);  // the wall may have nothing to touch yet
  for (const StaticPair& p : network.contacts) {
    reach = std::max(reach, (displacement_of(p.i, grains, m, step, wall) - displacement_of(p.j, grains, m, step, wall)).norm());
  }
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

/// The relaxation's working state: the packing, its present forces, and the running report.
class Relaxation {
 public:
  Relaxation(std::vector<dem::Grain>& grains, const dem::Box& box, const dem::ContactSpec& contact, int n_bodies,
             const LoadedWall* wall, const StaticEquilibriumSettings& settings)
      : grains_(grains), box_(box), contact_(contact), n_bodies_(n_bodies), wall_(wall), settings_(settings) {
    double free_mass = 0.0, free_radius = 0.0;
    std::size_t n_free = 0;
    for (const dem::Grain& g : grains) {
      if (g.body == dem::kFreeBody) {
        free_mass += g.mass;
        free_radius += g.radius;
        ++n_free;
      } else if (wall && g.body == wall->body) {
        wall_mass_ += g.mass;
      }
    }
    mean_mass_ = n_free > 0 ? free_mass / static_cast<double>(n_free) : 1.0;
    longest_step_ = kLongestStep * (n_free > 0 ? free_radius / static_cast<double>(n_free) : 0.5);
    // Only gaps of a law stiff at zero overlap (Hooke) enter the step's model (contacts_only); Hertz
    // ones need not be searched.
    gap_search_ = dem::stiffness_at_contact(dem::undamped_contact_model(contact)) > 0.0 ? longest_step_ : 0.0;
    current_ = evaluate(grains_, box_, contact_, gap_search_, wall_, lift_);
    start_energy_ = current_.energy;
  }

  StaticEquilibriumReport run() {
    while (!converged(current_, wall_, settings_) && report_.iterations < settings_.max_iterations &&
           !current_.network.contacts.empty() && shift_ <= kStalled) {
      std::optional<Direction> d = direction();
      if (!d) break;
      // The active-set step stands on a model that may have guessed the touching pairs wrong; it
      // gets a few halvings only before the plain step (always downhill) takes over.
      double t = line_search(d->matrices, d->step, d->changed ? kActiveSetHalvings : kHalvings);
      if (t == 0.0 && d->changed) t = line_search(d->matrices, d->plain, kHalvings);
      if (t == 0.0) shift_ *= kGrow;  // no progress along either direction: lean towards the gradient
      else if (t == 1.0) shift_ = std::max(kSmallest, shift_ * kShrink);
    }
    report_.residual_ratio = current_.residual_ratio;
    report_.wall_force = current_.wall_force;
    report_.energy_drop = start_energy_ - current_.energy;
    report_.converged = converged(current_, wall_, settings_);
    return report_;
  }

 private:
  // The shift mu of K + mu M, in units of the mean contact stiffness per mean grain mass: as small
  // as keeps the matrix positive definite (so every step goes downhill), shrinking after every full
  // step. A floor on mu would be fatal in a long column: its longest compression mode has a
  // stiffness per mass of order (d / L)^2 (3e-6 at L = 900 d), and a shift above that turns Newton
  // into a gradient step for exactly the modes Newton is there for.
  static constexpr double kSmallest = 1e-12, kGrow = 10.0, kShrink = 0.1, kStalled = 1e4;
  static constexpr double kArmijo = 1e-4;      // sufficient decrease, a fraction of the slope's promise
  static constexpr int kHalvings = 30;         // line search steps before a direction is given up
  static constexpr int kActiveSetHalvings = 6;
  static constexpr int kActiveSetRounds = 8;   // model solves per step while the touching pairs settle

  struct Direction {
    DynamicMatrices matrices;  ///< of the last model solved (node order depends on the grains only)
    Step step;                 ///< with the settled active set
    Step plain;                ///< with the present contacts
    bool changed = false;      ///< the active set differs from the present contacts
  };

  /// The step of the quadratic model. The energy is piecewise quadratic: a Hooke contact keeps its
  /// stiffness down to zero overlap and then loses it (a kink). Newton with the present contacts
  /// overshoots wherever a step opens a contact or closes a gap, and the next step undoes it. So the
  /// model holds touching the pairs its own solution overlaps: solve, update the set, solve again,
  /// until the set stops changing (a primal-dual active-set iteration).
  std::optional<Direction> direction() {
    ActiveSet active = contacts_only(current_, contact_);
    std::optional<Direction> d;
    for (int round = 0; round < kActiveSetRounds; ++round) {
      std::optional<DynamicMatrices> m;
      std::optional<Step> step = model_step(active, m);
      if (!step) return std::nullopt;
      ++report_.directions;
      if (!d) {
        d = Direction{std::move(*m), *step, *step, false};
      } else {
        d->matrices = std::move(*m);
        d->step = *step;
      }
      std::vector<bool> touching(active.touching.size());
      const std::size_t n_contacts = current_.network.contacts.size();
      for (std::size_t q = 0; q < touching.size(); ++q) {
        const StaticPair& p = q < n_contacts ? current_.network.contacts[q] : current_.network.gaps[q - n_contacts];
        touching[q] = active.stiffness[q] > 0.0 && p.overlap + overlap_change(p, grains_, d->matrices, *step, wall_) > 0.0;
      }
      if (touching == active.touching) break;
      set_touching(active, current_, grains_, wall_, touching);
      d->changed = true;
    }
    return d;
  }

  /// Solves one model. Its Hessian is K with the pre-stress part where that is positive definite
  /// (Newton proper), else without it. The pre-stress (-f/r across each contact) is what makes K
  /// indefinite: a straight compressed chain buckles sideways, a packing away from its minimum has
  /// soft spots (in a W = 3 column, transverse modes of a few hundred grains). Without it K is
  /// positive semi-definite, its step always goes downhill and keeps the long-wavelength modes
  /// exact; it converges linearly, at about the ratio of pre-stress to contact stiffness.
  std::optional<Step> model_step(const ActiveSet& active, std::optional<DynamicMatrices>& m) {
    PairLinearisation pairs;
    for (std::size_t q = 0; q < active.touching.size(); ++q) {
      pairs.stiffness.push_back(active.touching[q] ? active.stiffness[q] : 0.0);
      pairs.dashpot.push_back(0.0);
    }
    const double stiffness_per_mass = current_.network.mean_stiffness / mean_mass_;
    auto matrices = [&](bool prestress) {
      ContactNetwork model = current_.network;
      for (std::size_t q = 0; q < model.contacts.size(); ++q) {
        if (!prestress || !active.touching[q]) model.contacts[q].force = 0.0;
      }
      return assemble(grains_, model, n_bodies_, contact_, &pairs);
    };
    m = matrices(true);
    std::optional<Step> step = newton_step(active, *m, ShiftedSolver(*m, grains_, box_), wall_, wall_mass_,
                                           shift_ * stiffness_per_mass);
    if (step) return step;
    m = matrices(false);
    const ShiftedSolver solver(*m, grains_, box_);
    step = newton_step(active, *m, solver, wall_, wall_mass_, shift_ * stiffness_per_mass);
    while (!step && shift_ <= kStalled) {  // floppy grains: a larger shift regularises them
      shift_ *= kGrow;
      step = newton_step(active, *m, solver, wall_, wall_mass_, shift_ * stiffness_per_mass);
    }
    return step;
  }

  /// Backtracking line search on the true energy, from the full step (or the trust region's share
  /// of it). Moves the packing and returns the step fraction taken, or 0 for none.
  double line_search(const DynamicMatrices& m, const Step& direction, int halvings) {
    const double full_slope = slope(current_, m, direction, wall_);
    if (!(full_slope < 0.0)) return 0.0;
    double t = std::min(1.0, longest_step_ / relative_reach(current_.network, grains_, m, direction, wall_));
    for (int h = 0; h < halvings && report_.iterations < settings_.max_iterations; ++h, t *= 0.5) {
      ++report_.iterations;
      const Step scaled{t * direction.displacement, t * direction.lift};
      std::vector<dem::Grain> trial = moved(grains_, m, scaled, box_, wall_);
      State next = evaluate(trial, box_, contact_, gap_search_, wall_, lift_ + scaled.lift);
      // Near the minimum the energy change sinks below round-off; the residual then decides.
      const double round_off = 1e-12 * std::abs(current_.contact_energy);
      const bool downhill = next.energy <= current_.energy + kArmijo * t * full_slope - round_off ||
                            (std::abs(next.energy - current_.energy) <= round_off &&
                             next.residual_ratio < current_.residual_ratio);
      if (downhill && std::isfinite(next.energy)) {
        grains_ = std::move(trial);
        lift_ += scaled.lift;
        current_ = std::move(next);
        ++report_.accepted;
        return t;
      }
    }
    return 0.0;
  }

  std::vector<dem::Grain>& grains_;
  const dem::Box& box_;
  const dem::ContactSpec& contact_;
  int n_bodies_;
  const LoadedWall* wall_;
  const StaticEquilibriumSettings& settings_;
  double wall_mass_ = 0.0;
  double mean_mass_ = 1.0;
  // Trust region: no two touching grains move further than this relative to each other in one
  // step, so a step never carries grains through each other (the pair energy is bounded). Gaps
  // narrower than it can close within a step, so the model watches them.
  double longest_step_ = 0.0;
  double gap_search_ = 0.0;  ///< gaps this narrow can close within a step
  double shift_ = kSmallest;
  double lift_ = 0.0;  ///< of the loaded wall, from where it started
  State current_;
  double start_energy_ = 0.0;
  StaticEquilibriumReport report_;
};

}  // namespace

StaticEquilibriumReport relax_to_equilibrium(std::vector<dem::Grain>& grains, const dem::Box& box,
                                             const dem::ContactSpec& contact, int n_bodies, const LoadedWall* wall,
                                             const StaticEquilibriumSettings& settings) {
  if (dem::rotates(dem::undamped_contact_model(contact))) {
    throw std::invalid_argument("static equilibrium: only frictionless packings (normal laws alone) are relaxed");
  }
  if (wall && (wall->body < 1 || wall->body > n_bodies || !(wall->force > 0.0))) {
    throw std::invalid_argument("static equilibrium: the loaded wall needs a rigid body and a positive force");
  }
  return Relaxation(grains, box, contact, n_bodies, wall, settings).run();
}

}  // namespace sedwave::forward::linear
