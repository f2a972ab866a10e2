#include "sedwave/forward/dem/engine.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

using Clock = std::chrono::steady_clock;

/// Adds the lifetime of a scope to an accumulator.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(Clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  Clock::time_point start_;
};

static_assert(sizeof(Vec3) == 3 * sizeof(double), "a Vec3 is summed over ranks as three doubles");

/// The components of vectors, as one span of doubles for the collectives.
std::span<double> components(std::span<Vec3> v) { return {reinterpret_cast<double*>(v.data()), 3 * v.size()}; }

Vec3 sum_over_ranks(MPI_Comm comm, Vec3 local) {
  parallel::sum(comm, components(std::span(&local, 1)));
  return local;
}

/// Moment of inertia of a solid sphere, inverted: 1 / (2/5 m r^2) = 2.5 (1/m) / r^2.
double inverse_inertia(double inv_mass, double radius) { return 2.5 * inv_mass / (radius * radius); }

/// Restores a stream's formatting (precision, flags) at the end of a scope, so the progress report
/// does not change how the caller prints afterwards.
class FormatGuard {
 public:
  explicit FormatGuard(std::ostream& out) : out_(out), saved_(nullptr) { saved_.copyfmt(out); }
  ~FormatGuard() { out_.copyfmt(saved_); }
  FormatGuard(const FormatGuard&) = delete;
  FormatGuard& operator=(const FormatGuard&) = delete;

 private:
  std::ostream& out_;
  std::ios saved_;
};

std::string format_seconds(double s) {
  std::ostringstream out;
  if (s >= 3600) out << std::fixed << std::setprecision(1) << s / 3600 << " h";
  else if (s >= 60) out << std::fixed << std::setprecision(1) << s / 60 << " min";
  else out << std::fixed << std::setprecision(1) << s << " s";
  return out.str();
}

}  // namespace

Engine::Engine(MPI_Comm comm, EngineSettings settings, std::span<const Grain> grains,
               std::vector<RigidBody> bodies)
    : settings_(std::move(settings)),
      model_(make_contact_model(settings_.contact)),
      domain_(comm, settings_.box),
      grains_(rotates(model_)),
      bodies_(std::move(bodies)) {
  for (const Grain& g : grains) {
    if (g.body < 0 || g.body > static_cast<std::int32_t>(bodies_.size()))
      throw std::invalid_argument("DEM: grain " + std::to_string(g.id) + " refers to a missing rigid body");
    if (!(g.radius > 0.0) || !(g.mass > 0.0))
      throw std::invalid_argument("DEM: grain " + std::to_string(g.id) + " needs positive radius and mass");
    grains_.push_local(g);
  }
  if (settings_.fluid) {
    const std::string why = settings_.fluid->problem();
    if (!why.empty()) throw std::invalid_argument("DEM: fluid " + why);
  }
  update_global_grain_stats();
  ghost_cutoff_ = 2.0 * max_radius_ + skin_ + interaction_gap();

  if (settings_.time_step) {
    const double h = *settings_.time_step;
    if (!(h > 0.0)) throw std::invalid_argument("DEM: time step must be positive");
    if (h > limits_.stable_step) {
      std::ostringstream msg;
      msg << "DEM: time step " << h << " exceeds the stability limit " << limits_.stable_step
          << " of velocity Verlet for this contact model and damping (" << limits_.summary() << ")";
      throw std::invalid_argument(msg.str());
    }
    dt_ = h;
  } else {
    dt_ = limits_.default_step;
  }

  domain_.partition_by_count(grains_, ghost_cutoff_);
  rebuild();
  std::visit([&](const auto& m) { evaluate_forces(m, false, false); }, model_);
}

void Engine::update_global_grain_stats() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double mins[3] = {inf, inf, inf};  // radius, free mass, any mass
  double maxs[1] = {0.0};
  double sums[2] = {0.0, 0.0};       // count, diameters
  for (std::size_t i = 0; i < grains_.n_local(); ++i) {
    mins[0] = std::min(mins[0], grains_.radius[i]);
    if (grains_.body[i] == kFreeBody) mins[1] = std::min(mins[1], grains_.mass[i]);
    mins[2] = std::min(mins[2], grains_.mass[i]);
    maxs[0] = std::max(maxs[0], grains_.radius[i]);
    sums[0] += 1.0;
    sums[1] += 2.0 * grains_.radius[i];
  }
  const MPI_Comm comm = domain_.comm();
  parallel::min(comm, std::span(mins));
  parallel::max(comm, std::span(maxs));
  parallel::sum(comm, std::span(sums));
  if (sums[0] == 0.0) throw std::invalid_argument("DEM: the scene has no grains");
  n_global_ = static_cast<std::int64_t>(sums[0]);
  min_radius_ = mins[0];
  max_radius_ = maxs[0];
  skin_ = settings_.skin > 0.0 ? settings_.skin : 0.1 * sums[1] / sums[0];
  const double lightest = std::isfinite(mins[1]) ? mins[1] : mins[2];
  TimeStepInputs in{lightest, min_radius_, settings_.hertz_reference_overlap, settings_.viscous_damping,
                    0.0, settings_.time_step_fraction};
  if (const auto& fluid = settings_.fluid) {
    // The stiffest fluid dashpots: drag on the smallest grain, lubrication of the lightest pair at
    // the roughness gap (where it is largest).
    in.viscous_damping += fluid->drag_coefficient(min_radius_);
    in.pair_damping = fluid->lubrication_coefficient(fluid->roughness, min_radius_, min_radius_);
  }
  limits_ = std::visit([&](const auto& m) { return dem::time_step_limits(m, in); }, model_);
  const double guard_overlap = settings_.guard.max_overlap_fraction * min_radius_;
  guard_energy_floor_ = static_cast<double>(n_global_) *
                        std::visit([&](const auto& m) {
                          return m.normal.energy(guard_overlap, min_radius_, min_radius_);
                        }, model_);
}

// ---- the step ----------------------------------------------------------------------------------

void Engine::run(std::int64_t n) {
  run_start_ = last_report_ = Clock::now();
  std::visit(
      [&](const auto& model) {
        for (std::int64_t k = 0; k < n; ++k) {
          advance(model);
          if (settings_.progress.enabled) report_progress(k + 1, n, false);
        }
      },
      model_);
  if (settings_.progress.enabled) report_progress(n, n, true);
}

template <class Model>
void Engine::advance(const Model& model) {
  bool moved_too_far = true;
  {
    ScopedTimer t(timings_.integrate);
    moved_too_far = drift_and_half_kick();
    time_ += dt_;
    ++step_;
  }
  // Without a rebuild the ghosts' new positions travel while the pairs among held grains are
  // evaluated (evaluate_forces finishes the exchange).
  bool ghosts_in_flight = false;
  if (rebuild_needed(moved_too_far)) {
    ScopedTimer t(timings_.neighbor);
    rebuild();
  } else {
    ScopedTimer t(timings_.communication);
    domain_.start_ghost_update(grains_);
    ghosts_in_flight = true;
  }
  const std::int64_t interval = settings_.guard.check_interval;
  const bool watch = interval > 0 && step_ % interval == 0;
  OverlapWatch overlap;
  {
    const auto start = Clock::now();
    const double communication_before = timings_.communication;
    overlap = evaluate_forces(model, watch, ghosts_in_flight);
    // Communication inside (reverse forces, wall force sums) is counted as communication only.
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count() -
                           (timings_.communication - communication_before);
    timings_.force += seconds;
    work_since_balance_ += settings_.balance.use_measured_time
                               ? seconds
                               : static_cast<double>(list_.n_pairs() + grains_.n_local());
  }
  {
    ScopedTimer t(timings_.integrate);
    final_half_kick();
  }
  if (watch) guard_check(overlap);
  after_step();
}

// The two halves of velocity Verlet. Plain pointers: through the vectors, GCC reloads every array's
// address after each store (it cannot rule out that a double store changes a vector's pointer).
// The drift also measures each grain's distance from its position at the list's build while the new
// position is in a register: a separate pass (NeighborList::needs_rebuild) would stream every
// position from memory again, which is the scarce resource when all cores of a node run ranks.
bool Engine::drift_and_half_kick() {
  for (RigidBody& b : bodies_) b.begin_step(time_, dt_);
  GrainArrays& g = grains_;
  const std::size_t n = g.n_local();
  const double h = dt_;
  const double half = 0.5 * dt_;
  Vec3* x = g.position.data();
  Vec3* v = g.velocity.data();
  const Vec3* f = g.force.data();
  const double* inv_mass = g.inv_mass.data();
  const std::int32_t* body = g.body.data();
  const std::span<const Vec3> reference = list_.reference_positions();
  const bool compare = list_valid_ && reference.size() == n;
  const Vec3* x_built = reference.data();
  double farthest2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (body[i] == kFreeBody) {
      v[i] += (half * inv_mass[i]) * f[i];
      x[i] += h * v[i];
    } else {
      const RigidBody& b = bodies_[static_cast<std::size_t>(body[i] - 1)];
      x[i] += b.step_displacement();
      v[i] = b.velocity();
    }
    if (compare) farthest2 = std::max(farthest2, norm2(x[i] - x_built[i]));
  }
  if (g.rotation()) half_kick_spins();
  return !compare || farthest2 > list_.stale_displacement2();
}

void Engine::final_half_kick() {
  GrainArrays& g = grains_;
  const std::size_t n = g.n_local();
  const double half = 0.5 * dt_;
  Vec3* v = g.velocity.data();
  const Vec3* f = g.force.data();
  const double* inv_mass = g.inv_mass.data();
  const std::int32_t* body = g.body.data();
  for (std::size_t i = 0; i < n; ++i)
    if (body[i] == kFreeBody) v[i] += (half * inv_mass[i]) * f[i];
  if (g.rotation()) half_kick_spins();
  for (RigidBody& b : bodies_) b.end_step(dt_);
}

void Engine::half_kick_spins() {
  GrainArrays& g = grains_;
  const double half = 0.5 * dt_;
  for (std::size_t i = 0; i < g.n_local(); ++i)
    if (g.body[i] == kFreeBody)
      g.angular_velocity[i] += (half * inverse_inertia(g.inv_mass[i], g.radius[i])) * g.torque[i];
}

bool Engine::rebuild_needed() {
  return rebuild_needed(force_rebuild_ || !list_valid_ || list_.needs_rebuild(grains_));
}

bool Engine::rebuild_needed(bool moved_too_far) {
  const bool needed = force_rebuild_ || !list_valid_ || moved_too_far;
  if (domain_.size() == 1) return needed;
  ScopedTimer t(timings_.communication);
  return parallel::any(domain_.comm(), needed);
}

void Engine::rebuild() {
  const bool history = needs_history(model_);
  std::vector<HistoryEntry> entries;
  if (history) entries = list_valid_ ? extract_history(list_, grains_, history_) : std::move(pending_history_);
  pending_history_.clear();
  grains_.clear_ghosts();
  const std::int64_t balance_every = settings_.balance.every_rebuilds;
  if (domain_.size() > 1 && balance_every > 0 && rebuilds_ > 0 && rebuilds_ % balance_every == 0) {
    domain_.balance(work_since_balance_, grains_, ghost_cutoff_);
    work_since_balance_ = 0.0;
  }
  domain_.migrate(grains_, entries);
  const std::int64_t sort_every = settings_.sort_every_rebuilds;
  if (sort_every > 0 && rebuilds_ % sort_every == 0)
    grains_.permute_local(spatial_order(grains_, 2.0 * max_radius_ + skin_));  // the same order with or without a fluid
  domain_.build_ghosts(grains_, ghost_cutoff_);
  list_.build(grains_, skin_, max_radius_, settings_.newton, domain_.ghost_sources(), interaction_gap());
  if (history) assign_history(list_, grains_, HistoryMap(entries), history_);
  std::visit(
      [&](const auto& model) {
        using Model = std::decay_t<decltype(model)>;
        if (!std::holds_alternative<PairTable<Model>>(pair_table_)) pair_table_.emplace<PairTable<Model>>();
        tabulate_pairs(model, grains_, list_, std::get<PairTable<Model>>(pair_table_));
      },
      model_);
  if (lubricated()) tabulate_films(*settings_.fluid, grains_, list_, films_);
  list_valid_ = true;
  force_rebuild_ = false;
  ++rebuilds_;
}

template <class Model>
OverlapWatch Engine::evaluate_forces(const Model& model, bool watch, bool ghosts_in_flight) {
  GrainArrays& g = grains_;
  const std::size_t n = g.n_local();
  domain_.clear_forces(g);  // remote ghosts too: they collect reactions
  const PairTable<Model>& pairs = std::get<PairTable<Model>>(pair_table_);
  const auto accumulate = [&](PairSubset subset) {
    const auto with = [&](const auto& lubrication) {
      using Lubrication = std::decay_t<decltype(lubrication)>;
      return watch ? accumulate_contact_forces<Model, true, Lubrication>(model, g, list_, pairs, history_, dt_, lubrication, subset)
                   : accumulate_contact_forces<Model, false, Lubrication>(model, g, list_, pairs, history_, dt_, lubrication, subset);
    };
    return lubricated() ? with(LubricationEvaluator(*settings_.fluid, films_)) : with(NoLubrication{});
  };
  OverlapWatch w;
  if (ghosts_in_flight) {
    w = accumulate(PairSubset::kHeld);
    {
      ScopedTimer t(timings_.communication);
      domain_.finish_ghost_update(g);
    }
    const OverlapWatch remote = accumulate(PairSubset::kRemote);
    if (remote.worst_ratio > w.worst_ratio) w = remote;
  } else {
    w = accumulate(PairSubset::kAll);
  }
  // Under newton on the reactions on ghosts travel home while the owned grains take their
  // external forces (which involve no ghost).
  if (list_.newton()) {
    ScopedTimer t(timings_.communication);
    domain_.start_reverse_forces(g);
  }
  const Vec3 gravity = settings_.gravity;
  const double drag = settings_.viscous_damping;
  if (gravity != Vec3{} || drag != 0.0)
    for (std::size_t i = 0; i < n; ++i)
      if (g.body[i] == kFreeBody) g.force[i] += g.mass[i] * gravity - drag * g.velocity[i];
  if (settings_.fluid) apply_fluid_drag_and_buoyancy();
  if (list_.newton()) {
    ScopedTimer t(timings_.communication);
    domain_.finish_reverse_forces(g);
  }
  apply_body_forces();
  return w;
}

void Engine::apply_fluid_drag_and_buoyancy() {
  const FluidSpec& fluid = *settings_.fluid;
  GrainArrays& g = grains_;
  const double drag_per_radius = fluid.drag_coefficient(1.0);  // the drag coefficient is linear in r
  const Vec3 gravity = settings_.gravity;
  for (std::size_t i = 0; i < g.n_local(); ++i)
    if (g.body[i] == kFreeBody)
      g.force[i] += fluid.buoyancy(g.radius[i], gravity) - (drag_per_radius * g.radius[i]) * g.velocity[i];
}

void Engine::apply_body_forces() {
  if (bodies_.empty()) return;
  std::vector<Vec3> totals(bodies_.size());
  for (std::size_t i = 0; i < grains_.n_local(); ++i)
    if (grains_.body[i] != kFreeBody) totals[static_cast<std::size_t>(grains_.body[i] - 1)] += grains_.force[i];
  if (domain_.size() > 1) {
    ScopedTimer t(timings_.communication);
    parallel::sum(domain_.comm(), components(totals));
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) bodies_[b].set_contact_force(totals[b]);
}

void Engine::compute_forces() {
  if (rebuild_needed()) rebuild();
  else domain_.update_ghosts(grains_);
  const std::vector<Vec3> saved = history_;
  std::visit([&](const auto& m) { evaluate_forces(m, false, false); }, model_);
  history_ = saved;
}

void Engine::set_positions(const std::unordered_map<std::int64_t, Vec3>& positions) {
  for (std::size_t i = 0; i < grains_.n_local(); ++i) {
    const auto it = positions.find(grains_.id[i]);
    if (it != positions.end()) grains_.position[i] = it->second;
  }
  force_rebuild_ = true;
  compute_forces();
}

void Engine::strain_periodic_z(double factor) {
  if (!settings_.box.periodic[2]) throw std::logic_error("DEM: only a box periodic along z can be strained");
  if (!(factor > 0.0)) throw std::invalid_argument("DEM: a strain factor must be positive");
  if (domain_.size() > 1 && factor * settings_.box.length(2) < domain_.size() * ghost_cutoff_)
    throw std::runtime_error("DEM: a strained box would be too short for one slab of at least the ghost cutoff per rank");
  const double lo = settings_.box.lo.z;
  const auto strained = [&](double z) { return lo + factor * (z - lo); };
  for (std::size_t i = 0; i < grains_.n_local(); ++i) grains_.position[i].z = strained(grains_.position[i].z);
  settings_.box.hi.z = strained(settings_.box.hi.z);
  domain_.box().hi.z = settings_.box.hi.z;
  std::vector<double> boundaries = domain_.boundaries();
  for (double& b : boundaries) b = strained(b);
  domain_.set_boundaries(std::move(boundaries));
  // The ghosts' periodic shifts are the old box length: they must be rebuilt, not refreshed.
  force_rebuild_ = true;
}

void Engine::add_step_callback(std::int64_t every, StepCallback f) {
  if (every <= 0) throw std::invalid_argument("DEM: callback interval must be positive");
  callbacks_.emplace_back(every, std::move(f));
}

void Engine::after_step() {
  ScopedTimer t(timings_.output);
  for (const auto& [every, f] : callbacks_)
    if (step_ % every == 0) f(*this);
  const CheckpointSettings& c = settings_.checkpoint;
  if (c.every > 0 && !c.path.empty() && step_ % c.every == 0) {
    write_checkpoint(c.path);
    // A restored run rebuilds its lists at the next step; so does this one, which is what makes a
    // restart bit-identical.
    force_rebuild_ = true;
  }
}

// ---- guard ------------------------------------------------------------------------------------

void Engine::guard_check(const OverlapWatch& watch) {
  const GuardSettings& s = settings_.guard;
  std::ostringstream why;
  why.precision(6);
  const auto context = [&] {
    std::ostringstream c;
    c.precision(6);
    c << " at step " << step_ << " (t = " << time_ << "); time step " << dt_ << ", stable time step "
      << limits_.stable_step << ". The last checkpoint is left intact.";
    return c.str();
  };
  if (watch.worst_ratio > s.max_overlap_fraction)
    why << "DEM guard: grains " << watch.id_i << " and " << watch.id_j << " overlap by " << watch.overlap
        << " = " << watch.worst_ratio << " of the smaller radius (limit " << s.max_overlap_fraction << ")"
        << context();
  for (std::size_t i = 0; i < grains_.n_local() && why.tellp() == 0; ++i) {
    const Vec3& x = grains_.position[i];
    const Vec3& v = grains_.velocity[i];
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z))
      why << "DEM guard: grain " << grains_.id[i] << " has a non-finite position or velocity" << context();
  }
  const double ke = kinetic_energy();
  if (why.tellp() == 0 && last_kinetic_energy_ >= 0.0 &&
      ke > s.kinetic_energy_growth * std::max(last_kinetic_energy_, guard_energy_floor_))
    why << "DEM guard: kinetic energy blew up from " << last_kinetic_energy_ << " to " << ke << " within "
        << s.check_interval << " steps" << context();
  last_kinetic_energy_ = ke;

  parallel::throw_first_failure<GuardError>(domain_.comm(), why.str());
}

// ---- observables -------------------------------------------------------------------------------

double Engine::kinetic_energy() const {
  double e = 0.0;
  const GrainArrays& g = grains_;
  for (std::size_t i = 0; i < g.n_local(); ++i) {
    if (g.body[i] != kFreeBody) continue;
    e += 0.5 * g.mass[i] * norm2(g.velocity[i]);
    if (g.rotation()) e += 0.2 * g.mass[i] * g.radius[i] * g.radius[i] * norm2(g.angular_velocity[i]);
  }
  return parallel::sum(domain_.comm(), e);
}

double Engine::elastic_energy() const {
  double e = 0.0;
  const GrainArrays& g = grains_;
  std::visit(
      [&](const auto& model) {
        using Model = std::decay_t<decltype(model)>;
        const auto partners = list_.partners();
        for (std::size_t i = 0; i < list_.n_rows(); ++i)
          for (std::uint32_t k = list_.row_begin(i); k < list_.row_end(i); ++k) {
            const auto j = static_cast<std::size_t>(partners[k]);
            const double overlap = g.radius[i] + g.radius[j] - norm(g.position[i] - (g.position[j] + list_.shift(k)));
            if (overlap <= 0.0) continue;
            // Under newton off a pair with a ghost is also counted by the ghost's owner (or image).
            const double share = k < list_.ghost_begin(i) || list_.newton() ? 1.0 : 0.5;
            Vec3 shear;
            if constexpr (Model::needs_history) shear = history_[k];
            e += share * model.energy(overlap, g.radius[i], g.radius[j], shear);
          }
      },
      model_);
  return parallel::sum(domain_.comm(), e);
}

Vec3 Engine::linear_momentum() const {
  Vec3 p;
  for (std::size_t i = 0; i < grains_.n_local(); ++i)
    if (grains_.body[i] == kFreeBody) p += grains_.mass[i] * grains_.velocity[i];
  return sum_over_ranks(domain_.comm(), p);
}

Vec3 Engine::angular_momentum() const {
  Vec3 l;
  const GrainArrays& g = grains_;
  for (std::size_t i = 0; i < g.n_local(); ++i) {
    if (g.body[i] != kFreeBody) continue;
    l += g.mass[i] * cross(g.position[i], g.velocity[i]);
    if (g.rotation()) l += (0.4 * g.mass[i] * g.radius[i] * g.radius[i]) * g.angular_velocity[i];
  }
  return sum_over_ranks(domain_.comm(), l);
}

std::vector<HistoryEntry> Engine::contact_history() const {
  if (!needs_history(model_)) return {};
  return list_valid_ ? extract_history(list_, grains_, history_) : pending_history_;
}

std::size_t Engine::memory_bytes() const {
  const GrainArrays& g = grains_;
  const std::size_t vec3 = sizeof(Vec3);
  return (g.position.capacity() + g.velocity.capacity() + g.angular_velocity.capacity() +
          g.force.capacity() + g.torque.capacity()) * vec3 +
         (g.radius.capacity() + g.mass.capacity() + g.inv_mass.capacity()) * sizeof(double) +
         g.id.capacity() * sizeof(std::int64_t) + (g.group.capacity() + g.body.capacity()) * sizeof(std::int32_t) +
         list_.memory_bytes() + history_.capacity() * vec3 + films_.capacity() * sizeof(FilmPair) + domain_.ghost_sources().capacity() * sizeof(GhostSource) +
         std::visit([](const auto& t) { return t.pairs.capacity() * sizeof(t.pairs[0]); }, pair_table_);
}

// ---- progress ----------------------------------------------------------------------------------

void Engine::report_progress(std::int64_t done, std::int64_t total, bool final) {
  const auto now = Clock::now();
  std::ostream& out = settings_.progress.out ? *settings_.progress.out : std::cout;
  const FormatGuard keep_callers_format(out);
  const double elapsed = std::chrono::duration<double>(now - run_start_).count();
  if (!final) {
    if (domain_.rank() != 0) return;
    if (std::chrono::duration<double>(now - last_report_).count() < settings_.progress.interval_seconds) return;
    last_report_ = now;
    const double rate = static_cast<double>(done) * static_cast<double>(n_global_) / elapsed;
    const double eta = elapsed * static_cast<double>(total - done) / static_cast<double>(done);
    out << "dem: step " << step_ << " (" << done << "/" << total << "), t = " << time_ << ", "
        << std::setprecision(3) << rate << " grains/s, ETA " << format_seconds(eta) << '\n';
    return;
  }
  Timings worst = timings_;
  static_assert(sizeof(Timings) == 5 * sizeof(double), "the timings are reduced as five doubles");
  parallel::max(domain_.comm(), std::span(&worst.force, 5));
  if (domain_.rank() != 0) return;
  const double all = std::max(worst.total(), 1e-300);
  auto row = [&](const char* name, double s) {
    out << "  " << std::left << std::setw(14) << name << std::right << std::fixed << std::setprecision(3)
        << std::setw(10) << s << " s " << std::setw(6) << std::setprecision(1) << 100.0 * s / all << " %\n";
  };
  out << "dem: " << total << " steps of " << n_global_ << " grains on " << domain_.size() << " rank(s) in "
      << format_seconds(elapsed) << ", " << std::setprecision(4)
      << 1e9 * elapsed / (static_cast<double>(total) * static_cast<double>(n_global_)) * domain_.size()
      << " ns per grain-step per rank\n";
  row("force", worst.force);
  row("neighbour", worst.neighbor);
  row("communication", worst.communication);
  row("integration", worst.integrate);
  row("output", worst.output);
}

}  // namespace sedwave::forward::dem
