#pragma once
// The DEM engine: owns the grains of this rank, the box and slab decomposition, the rigid walls,
// the contact model, the neighbour list and the contact history, and advances them with velocity
// Verlet. Every public member function that is marked collective must be called on all ranks of
// the communicator.
//
// One step (all ranks):
//   1. half kick v += dt/2 F/m (spins likewise), drift x += dt v; walls move along their path
//   2. if any grain moved more than skin/2 (or a rebuild is forced): wrap, rebalance, migrate,
//      spatially sort, rebuild ghosts and the neighbour list (history carried by key);
//      otherwise refresh the ghosts
//   3. contact forces (and lubrication), gravity, global viscous damping, fluid drag and buoyancy;
//      total force on each wall
//   4. half kick with the new forces; force-controlled walls finish their step
//   5. guard (every guard.check_interval steps), callbacks, checkpoint, progress
#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <stdexcept>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/contact_history.hpp"
#include "sedwave/forward/dem/domain.hpp"
#include "sedwave/forward/dem/fluid.hpp"
#include "sedwave/forward/dem/force_loop.hpp"
#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/dem/neighbor_list.hpp"
#include "sedwave/forward/dem/rigid_body.hpp"
#include "sedwave/forward/dem/time_step.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {

/// Thrown on every rank of the engine when the guard stops a run. The message names the step, the
/// grains, the overlap, the time step and the stable time step.
class GuardError : public parallel::AgreedFailure {
 public:
  using parallel::AgreedFailure::AgreedFailure;
};

struct GuardSettings {
  double max_overlap_fraction = 0.25;  ///< overlap / smaller radius that stops the run
  std::int64_t check_interval = 50;    ///< steps between checks (0: never)
  /// Stop when the kinetic energy grows by more than this factor between two checks (and exceeds
  /// the energy of every grain at the maximum overlap, so a system at rest does not trigger it).
  double kinetic_energy_growth = 1e3;
};

struct CheckpointSettings {
  std::string path;         ///< HDF5 file, written atomically (temp file + rename)
  std::int64_t every = 0;   ///< steps between checkpoints (0: none)
  /// What the run depends on, by name (code version, a hash of the data file, every contact and
  /// wall option), stored in each checkpoint. restore_checkpoint refuses a checkpoint whose record
  /// differs from this one, naming every entry that changed, unless allow_changed_inputs.
  std::map<std::string, std::string> inputs{};
  bool allow_changed_inputs = false;
  /// Grains (and history records) per piece file: one piece is what a checkpoint holds in memory
  /// beside the engine (its image and the copy written out, about 2 x 104 B per row: 55 MB at the
  /// default, below the engine's own peak of about 0.9 KiB per grain from a few 10^5 grains per rank
  /// up, so that checkpoints do not raise a large run's peak). Below it on one rank, one file.
  std::size_t piece_rows = std::size_t{1} << 18;
};

struct ProgressSettings {
  bool enabled = false;          ///< print progress lines and the final timing table (rank 0)
  double interval_seconds = 10;  ///< between progress lines
  std::ostream* out = nullptr;   ///< default std::cout
};

struct BalanceSettings {
  std::int64_t every_rebuilds = 10;  ///< 0: fixed slabs
  bool use_measured_time = false;    ///< work = force-loop seconds (else: listed pairs + grains)
};

struct EngineSettings {
  Box box;
  ContactSpec contact;
  double skin = 0.0;                    ///< Verlet skin; <= 0: 0.1 x mean diameter
  std::optional<double> time_step;      ///< refused above the stability limit; default: fraction t_col
  double time_step_fraction = 0.01;     ///< default dt = fraction x binary collision time (thesis)
  double hertz_reference_overlap = 0.02;  ///< Hertz stiffness for dt: at this overlap / radius
  Vec3 gravity;                         ///< uniform acceleration on free grains
  double viscous_damping = 0.0;         ///< global drag F = -c v on free grains (preparation stages)
  /// A still pore fluid (fluid.hpp): lubrication between grains, drag and buoyancy on free grains.
  /// Absent: dry, and none of it is evaluated.
  std::optional<FluidSpec> fluid;
  std::int64_t sort_every_rebuilds = 1; ///< spatial sorting period (0: never)
  /// LAMMPS "newton on": a pair across a periodic face or slab boundary is computed once and its
  /// reaction sent back to the ghost's owner (fewer pair evaluations; one more communication per
  /// step). Neighbour-list readers then see such a pair from one side only (the channel contact
  /// statistics assume both sides, so the default stays off).
  bool newton = false;
  GuardSettings guard;
  CheckpointSettings checkpoint;
  ProgressSettings progress;
  BalanceSettings balance;
};

/// Wall-clock seconds spent per phase (this rank).
struct Timings {
  double force = 0.0;
  double neighbor = 0.0;
  double communication = 0.0;
  double integrate = 0.0;
  double output = 0.0;
  [[nodiscard]] double total() const { return force + neighbor + communication + integrate + output; }
};

class Engine {
 public:
  using StepCallback = std::function<void(const Engine&)>;

  /// Collective. `grains` may be given on any rank (e.g. all on rank 0); they are distributed.
  /// Grain::body refers to `bodies` (1-based; kFreeBody for free grains). Throws
  /// std::invalid_argument for an inconsistent scene or a time step above the stability limit.
  Engine(MPI_Comm comm, EngineSettings settings, std::span<const Grain> grains,
         std::vector<RigidBody> bodies = {});

  /// Advances n steps (collective).
  void run(std::int64_t n);
  /// Evaluates the forces at the current positions and velocities without advancing and without
  /// touching the contact history (collective). Results in grains().force / torque.
  void compute_forces();
  /// Calls f after every `every` steps (probes, dumps).
  void add_step_callback(std::int64_t every, StepCallback f);

  // ---- state -------------------------------------------------------------------------------------
  [[nodiscard]] const GrainArrays& grains() const { return grains_; }
  /// Mutable access for scenes (e.g. to set velocities). Positions changed here take effect at the
  /// next rebuild: call request_rebuild() after moving grains.
  [[nodiscard]] GrainArrays& grains() { return grains_; }
  void request_rebuild() { force_rebuild_ = true; }
  /// Moves the grains named in `positions` (by id; e.g. from read_lammps_dump) and recomputes
  /// ghosts, lists and forces (collective). Grains may land on any rank.
  void set_positions(const std::unordered_map<std::int64_t, Vec3>& positions);
  /// Strains a z-periodic box and everything in it affinely along z by `factor` about box.lo.z
  /// (LAMMPS's fix deform with remap x): heights, the box, the slab boundaries. Velocities are kept.
  /// Collective; the ghosts and lists are rebuilt at the next step or force evaluation. Throws
  /// std::logic_error for a box open along z (there the walls set the length) and
  /// std::invalid_argument for a factor that is not positive.
  void strain_periodic_z(double factor);
  [[nodiscard]] std::size_t n_local() const { return grains_.n_local(); }
  [[nodiscard]] std::int64_t n_global() const { return n_global_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::int64_t step_count() const { return step_; }
  [[nodiscard]] double time_step() const { return dt_; }
  [[nodiscard]] const TimeStepLimits& time_step_limits() const { return limits_; }
  [[nodiscard]] const std::vector<RigidBody>& bodies() const { return bodies_; }
  [[nodiscard]] const Domain& domain() const { return domain_; }
  [[nodiscard]] const EngineSettings& settings() const { return settings_; }
  [[nodiscard]] const AnyContactModel& contact_model() const { return model_; }
  [[nodiscard]] const NeighborList& neighbor_list() const { return list_; }
  [[nodiscard]] const Timings& timings() const { return timings_; }
  /// Keyed contact history of this rank.
  [[nodiscard]] std::vector<HistoryEntry> contact_history() const;
  /// Opaque scene state (e.g. a serialised RNG) stored in checkpoints.
  void set_user_state(std::string s) { user_state_ = std::move(s); }
  [[nodiscard]] const std::string& user_state() const { return user_state_; }

  // ---- observables (collective) -------------------------------------------------------------------
  [[nodiscard]] double kinetic_energy() const;  ///< translational + rotational, free grains
  [[nodiscard]] double elastic_energy() const;  ///< normal (and tangential spring) contact energy
  [[nodiscard]] Vec3 linear_momentum() const;
  [[nodiscard]] Vec3 angular_momentum() const;  ///< about the origin, spins included
  /// Bytes held by this rank's engine data structures.
  [[nodiscard]] std::size_t memory_bytes() const;

  // ---- files (collective) -----------------------------------------------------------------------
  /// Writes the complete state (grains, walls, history, time, step, dt, user state) to an HDF5 file
  /// atomically: a temporary file is written, flushed and renamed over `path`.
  void write_checkpoint(const std::string& path);
  /// Replaces the state by a checkpoint written by an engine built from the same scene. On one rank
  /// a restored run continues bit-identically to one never interrupted.
  void restore_checkpoint(const std::string& path);

 private:
  template <class Model> void advance(const Model& model);
  /// ghosts_in_flight: a ghost update was started (Domain::start_ghost_update) and is finished
  /// here, after the pairs among held grains.
  template <class Model> OverlapWatch evaluate_forces(const Model& model, bool watch, bool ghosts_in_flight);
  /// Returns whether a local grain is now further than skin/2 from where the list was built (true
  /// while no list is valid): the rebuild check, made in the same pass over the positions.
  [[nodiscard]] bool drift_and_half_kick();
  void final_half_kick();
  void half_kick_spins();
  void rebuild();
  /// Whether any rank must rebuild: a forced or invalid list, or a grain that moved too far (here,
  /// or as the drift reported it).
  [[nodiscard]] bool rebuild_needed();
  [[nodiscard]] bool rebuild_needed(bool moved_too_far);
  void apply_body_forces();
  void apply_fluid_drag_and_buoyancy();
  /// Whether a fluid's squeeze film acts between grains (the lubricated force loop and its films_).
  [[nodiscard]] bool lubricated() const { return settings_.fluid && settings_.fluid->lubrication; }
  /// Largest gap across which grains interact (a fluid's lubrication cut-off; 0 dry).
  [[nodiscard]] double interaction_gap() const { return settings_.fluid ? settings_.fluid->interaction_gap() : 0.0; }
  void guard_check(const OverlapWatch& watch);
  void after_step();
  void update_global_grain_stats();
  void report_progress(std::int64_t done, std::int64_t total, bool final);

  EngineSettings settings_;
  AnyContactModel model_;
  Domain domain_;
  GrainArrays grains_;
  std::vector<RigidBody> bodies_;
  NeighborList list_;
  std::vector<Vec3> history_;                    // slots parallel to list_
  AnyPairTable pair_table_;                      // pair constants parallel to list_
  std::vector<FilmPair> films_;                  // a fluid's film constants parallel to list_
  std::vector<HistoryEntry> pending_history_;    // after restore, until the next rebuild
  bool list_valid_ = false;
  bool force_rebuild_ = true;
  std::vector<std::pair<std::int64_t, StepCallback>> callbacks_;

  std::int64_t n_global_ = 0;
  double max_radius_ = 0.0;
  double min_radius_ = 0.0;
  double skin_ = 0.0;
  double ghost_cutoff_ = 0.0;
  double dt_ = 0.0;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  std::int64_t rebuilds_ = 0;
  TimeStepLimits limits_;
  double guard_energy_floor_ = 0.0;
  double last_kinetic_energy_ = -1.0;
  double work_since_balance_ = 0.0;
  std::string user_state_;
  Timings timings_;
  std::chrono::steady_clock::time_point run_start_;
  std::chrono::steady_clock::time_point last_report_;
};

}  // namespace sedwave::forward::dem
