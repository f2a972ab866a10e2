#pragma once
// The granular-solid interface: spheres confined to the plane z = 0 (out-of-plane translation and the
// in-plane-axis rotations frozen, as LAMMPS's enforce2d) on the top edge of an elastic plate
// (plate/elastic_plate.hpp), with Hertz contacts, rotation, Coulomb-tanh friction and an optional
// Hertz dashpot between grains; one explicit velocity-Verlet step for grains and plate together with
// a self-adaptive step (docs/interface.md).
//
// Contact laws are the DEM engine's parts: grain-grain contacts are a dem::ContactModel (any normal,
// tangential and rolling law of dem/contact/laws.hpp, composed and evaluated by the engine's code,
// in the plane z = 0), grain-plate contacts the Hertz and Coulomb-tanh parts
// (dem/contact/hertz.hpp, dem/contact/coulomb_tanh.hpp); the step limits are
// dem/critical_step.hpp's.
// Grain-plate contact: a sphere on the deforming edge y = u_y(x), u_y interpolated with the edge's
// linear shape functions at the grain's abscissa; the overlap is delta = r - (y_g - u_y(x_g)); the
// force is the gradient of the Hertz energy (2/5) k delta^(5/2), k = (4/3) E*_gp sqrt(r), so it goes
// back to the nodes with the same shape functions, equal and opposite. Friction acts along x with the
// edge's interpolated velocity. Units: any consistent set (SI in scenes).
//
// The other grain-plate contact, PlateContactModel::rigid_layers, is Wang, Zhang & Vakakis's (Granular
// Matter 23, 21 (2021), appendix 1, eqs. 19a,b): a flat, massless rigid layer at each top-edge node
// (as wide as an element), moving with its node; the grain's overlap is r - (y_g - u_y(node)), the
// modulus E_b/(1 - nu_b^2) of the grain alone (the plate's compliance is not in the law), R* = r, and
// the normal force, the friction and their reactions act on that one node.
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/critical_step.hpp"
#include "sedwave/forward/interface/hex_packing.hpp"
#include "sedwave/forward/interface/planar_contacts.hpp"
#include "sedwave/forward/interface/side_walls.hpp"
#include "sedwave/forward/plate/elastic_plate.hpp"

namespace sedwave::forward::interface {

struct GrainMaterial {
  double youngs_modulus;
  double poisson_ratio;
};

/// How a grain presses on the plate (the header's comment): the deforming edge interpolated by its
/// shape functions with the two bodies' Hertz modulus, or the paper's rigid layers at the nodes.
enum class PlateContactModel { interpolated, rigid_layers };

struct InterfaceContacts {
  double friction = 0.0;             ///< mu, grain-grain and grain-plate (0: frictionless)
  double tanh_velocity_scale = 1e3;  ///< k_s [time/length] of Coulomb-tanh
  double restitution = 1.0;          ///< grain-grain Hertz-Tsuji dashpot from e_n (1: none)
  bool rotation = true;              ///< integrate spins (false: spins stay zero)
  PlateContactModel plate_contact = PlateContactModel::interpolated;
  /// The grain-grain contact as a DEM contact (any law of dem/contact/laws.hpp, with its keys); empty:
  /// grain_contact_spec's default from the fields above. The grain-plate contact stays Hertz and
  /// Coulomb-tanh with `friction` and `tanh_velocity_scale`.
  std::optional<dem::ContactSpec> grain_contact{};
};

/// The grain-grain contact `contacts` describes: its grain_contact, or Hertz with the grains'
/// youngs_modulus and poisson_ratio, the Tsuji dashpot of `restitution` (none at 1) and, with
/// friction, Coulomb-tanh (friction, tanh_velocity_scale).
[[nodiscard]] dem::ContactSpec grain_contact_spec(const InterfaceContacts& contacts, const GrainMaterial& grain);

/// The Hertz modulus E* of a grain-plate contact: 1/E* = (1 - nu_g^2)/E_g + (1 - nu_p^2)/E_p
/// (interpolated), or E_g/(1 - nu_g^2) (rigid_layers: the layer is rigid).
[[nodiscard]] double grain_plate_modulus(const GrainMaterial& grain, const plate::PlateMaterial& plate,
                                         PlateContactModel model);

/// rigid_layers only: throws std::invalid_argument naming the first grain within `reach` of the
/// undeformed edge (y - r < reach) and over the plate (0 <= x <= length_x) whose centre is not over a
/// top-edge node (nodes every element_width from x = 0; to 1e-6 of an element).
void check_grains_over_nodes(const std::vector<Grain>& grains, double element_width, double length_x, double reach);

/// How grains and plate advance together. velocity_verlet: one explicit step for both (the default).
/// newmark_rk4: the paper's (appendix 1, eqs. 15-18): the plate by average-acceleration Newmark
/// (M + C dt/2 + K dt^2/4 factorised by a sparse LDL^T), its motion interpolated over the step
/// (eq. 16), the grains by RK4 against that motion, and the forces on the plate iterated to a fixed
/// point within each step; its grain-plate limits are eqs. 29a,b (docs/interface.md, "Two schemes").
/// multirate: velocity Verlet split by impulse (r-RESPA; Tuckerman, Berne & Martyna 1992): an outer
/// step of plate_tolerance * the plate's limit kicks the plate with the internal forces of all its
/// elements but the top row (and its edge dashpots and pulses) at its ends; in between, the grains
/// and the two top rows of nodes take velocity-Verlet substeps (the single-rate scheme's steps) of
/// the contacts and the top row of elements, and the plate's other nodes drift once
/// (docs/interface.md, "Multirate step").
enum class Scheme { velocity_verlet, newmark_rk4, multirate };

/// dt = tolerance * min(the stability limits of the FE mesh, of the Hertz contacts and of the
/// Coulomb-tanh contacts), each evaluated from the state at the start of the step; the grain
/// contacts' limits are those of a hexagonal packing's collective modes (dem/critical_step.hpp).
struct StepControl {
  double tolerance = 0.1;  ///< theta in (0, 0.5]
  double max_step = std::numeric_limits<double>::infinity();
  /// > 0: every step this long (no adaptation; for comparing against the adaptive step).
  double fixed_step = 0.0;
  Scheme scheme = Scheme::velocity_verlet;
  /// multirate: the outer step is plate_tolerance * the plate's limit; 0: `tolerance`.
  double plate_tolerance = 0.0;
  /// newmark_rk4: a force on the plate has converged when its change in one iteration is below
  /// abstol [force] or below reltol times itself (eqs. 18a,b), every one of them; at most
  /// max_iterations, else the step throws std::runtime_error.
  double abstol = 1e-9;
  double reltol = 1e-10;
  int max_iterations = 100;
};

/// Each limit of the last step (infinite where no such contact exists) and the step taken.
struct StepLimits {
  double plate = std::numeric_limits<double>::infinity();
  double hertz = std::numeric_limits<double>::infinity();
  double friction = std::numeric_limits<double>::infinity();
  /// Not a stability limit: no grain moves more than half the neighbour-list skin in one step.
  double travel = std::numeric_limits<double>::infinity();
  /// min(plate, hertz, friction): the step is the tolerance times this, capped by travel.
  [[nodiscard]] double tightest() const;
};

/// A force pulse F(t) = peak sin(pi t / duration) for t < duration, along (direction_x, direction_y),
/// on each driven grain. (A velocity impulse is an initial velocity and needs no drive.)
struct ForcePulse {
  std::vector<int> grains;
  double peak = 0.0;
  double duration = 0.0;
  double direction_x = 0.0;
  double direction_y = -1.0;
};

/// A rectangular pulse of forces on the plate's degrees of freedom (`forces`, one per degree of
/// freedom, zero where none acts), held for 0 <= t < duration. Each half kick receives exactly the
/// impulse that falls inside it, so the pulse delivers forces * duration whatever the steps.
struct PlatePulse {
  std::vector<double> forces;
  double duration = 0.0;
};

/// The participation ratio (sum e)^2 / sum e^2 of non-negative energies: N when N holders share
/// equally, 1 when one holds everything; 0 when none holds any.
[[nodiscard]] double participation_ratio(const std::vector<double>& energies);

/// Energies [force length]. The balance kinetic + potential + dissipated - drive_work is constant.
struct Energies {
  double grain_translation = 0.0;
  double grain_rotation = 0.0;
  double contact = 0.0;  ///< Hertz energy of grain-grain and grain-plate contacts
  double plate_kinetic = 0.0;
  double plate_strain = 0.0;
  double friction_work = 0.0;  ///< dissipated by Coulomb-tanh (>= 0)
  double dashpot_work = 0.0;   ///< dissipated by grain-grain dashpots
  double boundary_work = 0.0;  ///< absorbed by the plate's absorbing edges
  double drive_work = 0.0;     ///< done by the force pulse
  [[nodiscard]] double mechanical() const {
    return grain_translation + grain_rotation + contact + plate_kinetic + plate_strain;
  }
  /// Mechanical energy plus everything dissipated minus the drive's work: constant in exact dynamics.
  [[nodiscard]] double balance() const {
    return mechanical() + friction_work + dashpot_work + boundary_work - drive_work;
  }
};

class GranularPlate {
 public:
  GranularPlate(std::vector<Grain> grains, const GrainMaterial& grain_material,
                std::optional<plate::ElasticPlate> plate, const InterfaceContacts& contacts,
                const StepControl& control);

  /// One step of at most max_dt; returns the step taken.
  double step(double max_dt = std::numeric_limits<double>::infinity());
  /// One step towards t_end, shortened so that the steps land on t_end exactly without a sliver of
  /// a last step (the last two share what is left); returns the step taken.
  double step_towards(double t_end);
  /// Steps until time t_end exactly.
  void advance_to(double t_end);

  void set_drive(ForcePulse pulse);
  void set_plate_pulse(PlatePulse pulse);
  /// A constant force (force_x, force_y) on each of `grains`, held for the whole run: a static
  /// precompression of the packing against the plate. Its work counts as the drive's.
  void set_static_load(std::vector<int> grains, double force_x, double force_y);
  /// Rigid side walls beside the packing (side_walls.hpp); their contacts count in the forces, the
  /// contact energy and the Hertz and Coulomb-tanh step limits.
  void set_side_walls(const SideWalls& walls);
  /// Brings the loaded packing and plate to rest: steps with every velocity scaled by
  /// exp(-dt/damping_time) after each step until the kinetic energy falls below `tolerance` times
  /// its largest value (or max_steps pass), then zeroes the velocities, the clock, the step and
  /// iteration counts and the energy books, so that the run starts from the static state. Friction
  /// is off while relaxing (the grains' normal law alone; no Coulomb-tanh at the plate or the
  /// walls): Coulomb-tanh and a regularised rolling torque carry no force at rest, so the static
  /// state is the same, a tangential history spring starts from it unloaded, and the steps are not
  /// held to friction's limits. Returns the steps taken;
  /// throws std::runtime_error when the packing is not at rest after max_steps.
  long relax(double damping_time, double tolerance, long max_steps);
  /// Recomputes the neighbour list and the forces after initial conditions were set by hand.
  void refresh_forces();
  [[nodiscard]] double time() const { return time_; }
  /// The grains' steps (multirate: the substeps) and the plate's (the outer steps; = steps() otherwise).
  [[nodiscard]] long steps() const { return steps_; }
  [[nodiscard]] long plate_steps() const { return plate_steps_; }
  /// The shortest and the longest step the grains took in the last call to step (multirate: its
  /// substeps; otherwise both are that step).
  [[nodiscard]] double last_substep_min() const { return substep_min_; }
  [[nodiscard]] double last_substep_max() const { return substep_max_; }
  [[nodiscard]] const std::vector<Grain>& grains() const { return grains_; }
  /// Initial velocities and spins, before the first step. Radii, masses and inertias stay as built:
  /// the pair tables hold what they fix.
  std::vector<Grain>& grains_mutable() {
    step_rates_.reset();
    return grains_;
  }
  [[nodiscard]] const std::optional<plate::ElasticPlate>& plate() const { return plate_; }
  [[nodiscard]] const std::vector<double>& plate_displacement() const { return u_; }
  [[nodiscard]] const std::vector<double>& plate_velocity() const { return v_; }
  std::vector<double>& plate_displacement_mutable() {  ///< initial conditions
    step_rates_.reset();
    return u_;
  }
  std::vector<double>& plate_velocity_mutable() {
    step_rates_.reset();
    return v_;
  }

  [[nodiscard]] Energies energies() const;
  [[nodiscard]] const StepLimits& last_limits() const { return limits_; }
  /// The limits of the current state, every pair's rates computed afresh at the grains' velocities
  /// now. A step reads the grain pairs' rates off the force evaluation that ended the step before it
  /// instead (at the velocities the forces saw, compute_forces), so its limits differ from these by
  /// the last half kick in the approach speeds.
  [[nodiscard]] StepLimits current_limits() const;
  /// Total normal force the grains exert on the plate (>= 0) and its tangential part, at the last step.
  [[nodiscard]] double plate_normal_force() const { return plate_normal_force_; }
  [[nodiscard]] double plate_tangential_force() const { return plate_tangential_force_; }
  /// Total normal force the grains exert on the left and on the right side wall (>= 0), at the last step.
  [[nodiscard]] double left_wall_force() const { return wall_force_[0]; }
  [[nodiscard]] double right_wall_force() const { return wall_force_[1]; }
  /// Hertz effective modulus of grain-plate contacts.
  [[nodiscard]] double plate_contact_modulus() const { return plate_modulus_; }
  /// Largest contact radius sqrt(R delta) seen at the plate so far (compare with the element size).
  [[nodiscard]] double max_plate_contact_radius() const { return max_plate_contact_radius_; }
  /// Number of grain-grain pairs in contact now.
  [[nodiscard]] int grain_contacts() const;
  /// The mechanical energy each grain holds [force length]: its kinetic energy (translation, and
  /// rotation when on), half the Hertz energy of each grain-grain contact it is in and the whole of
  /// its contact with the plate. They sum to grains + contacts of energies().
  [[nodiscard]] std::vector<double> grain_energies() const;
  /// newmark_rk4: fixed-point iterations taken in all, the most in one step, and the factorisations
  /// of M + C dt/2 + K dt^2/4 (one per step size met; zeros for velocity_verlet).
  [[nodiscard]] long iterations() const { return iterations_; }
  [[nodiscard]] int most_iterations() const { return most_iterations_; }
  [[nodiscard]] long factorisations() const { return factorisations_; }

 private:
  /// The grain contact whose forces add_planar_pairs evaluates in SIMD lanes.
  using PlanarLaw = dem::ContactModel<dem::HertzNormal, dem::CoulombTanhFriction, dem::NoRolling>;
  struct Pair {
    int i;
    int j;
  };
  struct Parts {  // forces on one grain by kind: conservative, friction, dashpot, drive
    double fx = 0.0, fy = 0.0, torque = 0.0;
  };
  double step_with(const StepLimits& limits, double max_dt);
  /// The step the scheme takes from `limits` when nothing cuts it (multirate: the outer step).
  [[nodiscard]] double free_step(const StepLimits& limits) const;
  /// The grains' step from `limits` (the single-rate step; multirate: the substep).
  [[nodiscard]] double substep_free(const StepLimits& limits) const;
  double step_multirate(const StepLimits& limits, double dt);
  /// multirate: one velocity-Verlet substep of the fast forces on grains and the two top rows of
  /// nodes towards the outer step's `end` (the last one lands on it and takes the outer step's
  /// closing half kick, of `outer` / 2, on those rows; the first, with `opening` = the outer step,
  /// its opening one). Returns its length.
  double substep(const StepLimits& limits, double end, double opening, double outer);
  /// multirate: half a kick of the two top rows of nodes, the fast forces over h and the slow ones
  /// (with the edge dashpots and a pulse) over slow_h, then their drift by `drift`.
  void kick_edge(double h, double drift, double slow_h, bool second_half);
  double step_newmark_rk4(double dt);  // newmark_rk4.cpp
  void make_newmark();                 // K assembled once
  void restart_newmark();              // the state was changed by hand: start_newmark at the next step
  void start_newmark();                // the plate's acceleration and forces from the state
  struct GrainRates;
  /// RK4 of the grains from `start` over dt against the plate path x(t) of eq. 16; the works of the
  /// non-conservative forces over the step go to `works` (friction, dashpot, drive).
  void rk4_grains(const std::vector<Grain>& start, double t0, double dt, const std::vector<double>& x0,
                  const std::vector<double>& v0, const std::vector<double>& x1, double works[3]);
  void evaluate_rates(double t, GrainRates& rates);
  [[nodiscard]] Energies energies_without_strain() const;  ///< kinetic parts only
  void build_pairs();
  bool pairs_stale() const;
  /// with_elastic false: the contact forces on the plate alone in f_conservative_ and f_friction_.
  /// multirate: the slow forces go to f_elastic_ (with_elastic), f_conservative_ holds the fast ones,
  /// and the top edge's predicted velocity adds slow_half_step of the slow forces and the edge
  /// dashpots (the outer half kick that ends the step; 0 within it).
  void compute_forces(double half_step, bool with_elastic = true, double slow_half_step = 0.0);
  /// What a touching pair's force evaluation computed that depends on its distance alone (d2 names
  /// it; -1: none): the step limit reads it back at the same distance instead of computing it again.
  struct PairFacts {
    double d2 = -1.0;
    double d = 0.0;
    double spring = 0.0, dashpot = 0.0;  ///< the normal law's spring force and dashpot coefficient
    double inverse_slip_mass = 0.0;      ///< inverse_slip_mass at that overlap (a tangential law only)
  };
  /// What a listed pair's two grains fix, set when the list is built: r_i + r_j, the effective mass
  /// and radius and 1/m_i + 1/m_j; for a Hertz law's step limit (grain_pair_rates) reach_energy's
  /// closing factor (5/4) m/k and the weight (k/m)^5 that ranks pairs, k = (4/3) E* sqrt(R).
  struct PairConstants {
    double reach = 0.0, mass = 0.0, radius = 0.0, inverse_mass = 0.0;
    double closing_factor = 0.0, rate_weight = 0.0;  ///< Hertz: (5/4) m/k; ((k/m) / rate_scale_)^5
  };
  /// The grain pairs' largest rates, gathered pair by pair (note_pair_rates) and turned into
  /// dem::PairRates at the end (finish_rates). A Hertz law keeps the pair whose collision reaches the
  /// largest omega^2 and evaluates its oscillator once, in finish_rates.
  struct RateSearch {
    dem::PairRates rates;
    double largest = 0.0;                          ///< Hertz: the largest rate_weight times reach_energy
    double mass = 0.0, radius = 0.0, reach = 0.0;  ///< Hertz: that pair's m, R and delta_max^(5/2)
  };
  /// The listed pairs' constants: this class's and the contact model's (dem::PairTable, as the DEM
  /// engine keeps them), so that no step divides by masses or takes their roots.
  void tabulate_pairs();
  /// The grain contact model and its pair table together, so that the table always is the model's.
  void set_grain_model(const dem::AnyContactModel& model);
  /// One touching grain pair's forces, its torques and its elastic energy, at the squared distance d2
  /// compute_forces found; `shear` is its history slot; `damps`: damped(); its rates into `search`
  /// unless null.
  template <class Model>
  void add_grain_pair(const Model& model, const Pair& p, double d2, const PairConstants& constants,
                      const typename Model::Pair& law_pair, double dt, dem::Vec3& shear, PairFacts& facts,
                      bool damps, RateSearch* search);
  /// The default grain contact (Hertz, Coulomb-tanh, no rolling law): add_grain_pair for the first
  /// `touching` of touching_, their contacts evaluated in SIMD lanes (planar_contacts.hpp).
  void add_planar_pairs(const PlanarLaw& model, const std::vector<PlanarLaw::Pair>& table, std::size_t touching,
                        bool damps, RateSearch* search);
  /// 1/m_i + 1/m_j + a_i^2/I_i + a_j^2/I_j (the inertias with rotation), a = r - overlap/2: a pair's
  /// slip's inverse mass.
  [[nodiscard]] double inverse_slip_mass(const PairConstants& constants, const Grain& gi, const Grain& gj,
                                         double overlap) const;
  /// arm^2/I: what turning adds to the inverse mass of a slip at `arm` from g's centre (0 with
  /// rotation off, where grains do not turn).
  [[nodiscard]] double turning_inverse_mass(const Grain& g, double arm) const {
    return contacts_.rotation ? interface::turning_inverse_mass(arm, g.inertia) : 0.0;
  }
  /// One touching or closing pair into `search`: its overlap and normal velocity (< 0: closing) and,
  /// where it touches and the law rotates, its normal force's magnitude and its slip's inverse mass.
  template <class Model>
  void note_pair_rates(const Model& model, const PairConstants& constants, const typename Model::Pair& law_pair,
                       const Grain& gi, const Grain& gj, double overlap, double normal_velocity, double normal_force,
                       double inverse_mt, RateSearch& search) const;
  /// A Hertz pair's reach_energy now into `search` (note_pair_rates' normal part for a Hertz law).
  static void note_reach(const PairConstants& constants, double reach_now, RateSearch& search);
  /// A touching pair's tangential and rolling rates into `search` (note_pair_rates' other part).
  template <class Model>
  void note_slip_rates(const Model& model, const PairConstants& constants, const typename Model::Pair& law_pair,
                       const Grain& gi, const Grain& gj, double overlap, double normal_force, double inverse_mt,
                       RateSearch& search) const;
  template <class Model>
  [[nodiscard]] dem::PairRates finish_rates(const Model& model, const RateSearch& search) const;
  /// Every listed pair's rates at the grains' positions and velocities now.
  template <class Model>
  [[nodiscard]] dem::PairRates grain_pair_rates(const Model& model) const;
  /// The limits from the grain pairs' rates `pair_rates` and the plate's and walls' contacts now.
  [[nodiscard]] StepLimits limits_with(const dem::PairRates& pair_rates) const;
  /// The limits the next step takes: current_limits with the grain pairs' rates of the last force
  /// evaluation (step_rates_) where it has them.
  [[nodiscard]] StepLimits next_limits() const;
  void add_plate_contact(int g);
  /// The grain-plate normal law: the DEM's Hertz part with R* = r (a sphere on a flat) and no dashpot
  /// (the paper's eq. 19a, either plate contact model's modulus).
  [[nodiscard]] dem::HertzNormal plate_law() const { return {plate_modulus_, 0.0}; }
  void add_wall_contacts(int g);                           // side_walls.cpp
  void add_wall_energies(std::vector<double>& held) const;  // side_walls.cpp
  /// How far grain g presses into the wall at x = face whose normal (+1 left, -1 right) points into the
  /// packing [m] (> 0: touching).
  [[nodiscard]] static double wall_overlap(const Grain& g, double face, double normal);  // side_walls.cpp
  /// The walls' Hertz and Coulomb-tanh limits into `limits`; returns the walls' largest friction rate.
  double tighten_with_walls(StepLimits& limits, double collective_friction) const;
  /// The node(s) and weights through which a grain at abscissa x meets the edge (the contact model's).
  [[nodiscard]] plate::ElasticPlate::EdgePoint contact_point(double x) const;
  [[nodiscard]] double plate_overlap(const Grain& g, const plate::ElasticPlate::EdgePoint& e) const;
  [[nodiscard]] double contact_ceiling() const;
  /// Half a kick of grains and plate; plate_drift > 0 then moves the plate by that step (kick_plate).
  void kick(double h, bool second_half, double plate_drift = 0.0);
  void kick_grains(double h);
  /// Whether any force acting now can rub (friction, a tangential or rolling law) or damp (a dashpot in
  /// the grains' normal law): without either no force reads the seen velocities and their works are 0.
  [[nodiscard]] bool rubbing() const;
  [[nodiscard]] bool damped() const;
  /// Half a kick of the plate's degrees of freedom below `end` by `forces` (and `friction` on the
  /// booked ones unless null), then their drift by `drift`.
  void kick_plate(double h, bool second_half, double drift, const std::vector<double>& forces,
                  const double* friction, std::size_t end);
  [[nodiscard]] bool multirate() const { return control_.scheme == Scheme::multirate && plate_.has_value(); }
  /// multirate: the first degree of freedom of the two top rows of nodes, which take the substeps.
  [[nodiscard]] std::size_t subcycled_dof() const;
  /// multirate: f_elastic_ = the internal forces of every element but the top row's.
  void slow_forces();
  void book_plate_dofs();
  void drift_grains(double h);

  std::vector<Grain> grains_;
  std::optional<plate::ElasticPlate> plate_;
  InterfaceContacts contacts_;
  StepControl control_;
  dem::AnyContactModel grain_model_;
  double plate_modulus_ = 0.0;

  std::vector<Pair> pairs_;
  struct Touching {
    std::size_t pair;  ///< its index in pairs_
    double d2;         ///< |x_i - x_j|^2 < (r_i + r_j)^2
  };
  std::vector<Touching> touching_;  ///< compute_forces' scratch: the listed pairs that touch
  struct Closing {
    std::size_t pair;  ///< its index in pairs_
    double d2;         ///< |x_i - x_j|^2 >= (r_i + r_j)^2
    double approach;   ///< (v_i - v_j) . (x_i - x_j) < 0 at the velocities the forces see
  };
  std::vector<Closing> closing_;  ///< compute_forces' scratch: the listed pairs that close without touching
  /// add_planar_pairs' scratch: the touching pairs' inputs and contacts, one array each.
  struct PlanarScratch {
    std::vector<double> d2, dx, dy, dvx, dvy, spin_i, spin_j, radius_i, radius_j, inertia_i, inertia_j;
    std::vector<double> effective_radius, damping, reach, inverse_mass, closing_factor;
    std::vector<double> distance, nx, ny, overlap, normal_velocity, spring, dashpot, tangential, inverse_slip_mass;
    std::vector<double> reach_energy;
    /// Every array at least n long (they only grow).
    void hold(std::size_t n) {
      for (auto* a : {&d2, &dx, &dy, &dvx, &dvy, &spin_i, &spin_j, &radius_i, &radius_j, &inertia_i, &inertia_j,
                      &effective_radius, &damping, &reach, &inverse_mass, &closing_factor, &distance, &nx, &ny,
                      &overlap, &normal_velocity, &spring, &dashpot, &tangential, &inverse_slip_mass, &reach_energy})
        if (a->size() < n) a->resize(n);
    }
  };
  PlanarScratch planar_;
  /// The grain pairs' rates at the last force evaluation of a velocity-Verlet or multirate step (or
  /// of refresh_forces), at its positions and the velocities its forces saw; empty once the state was
  /// changed by hand (the *_mutable accessors, relax) until the next force evaluation.
  std::optional<dem::PairRates> step_rates_;
  std::vector<dem::Vec3> shear_;  ///< each listed pair's tangential history (history laws), kept across rebuilds
  std::vector<PairFacts> pair_facts_;  ///< each listed pair's, from the last force evaluation
  std::vector<PairConstants> pair_constants_;
  dem::AnyPairTable pair_table_;  ///< grain_model_'s constants of each listed pair
  double rate_scale_ = 0.0;       ///< the first listed pair's k/m: rate_weight's scale, against overflow
  /// The tangential springs' energy now, and when the books were last zeroed: the friction's
  /// dissipation is its work less their gain.
  double tangential_energy_ = 0.0, tangential_energy_origin_ = 0.0;
  std::vector<double> x_at_build_;
  std::vector<double> y_at_build_;
  double skin_ = 0.0;

  std::vector<Parts> conservative_, friction_, dashpot_, drive_;
  struct Motion {  // the velocity and spin a velocity-dependent force sees
    double vx, vy, spin;
  };
  std::vector<Motion> seen_;
  std::vector<double> plate_seen_;  ///< only the top edge's x components are kept (friction's slip)
  /// The plate's degrees of freedom whose work is booked in a kick (edge dashpots, the top edge
  /// under friction, a pulse's loads), ascending.
  std::vector<std::size_t> booked_;
  std::vector<double> u_, v_, f_conservative_, f_friction_;
  /// multirate: the slow forces (slow_forces) at the last outer step's end; f_conservative_ then holds
  /// the fast ones on the two top rows of nodes (the top row of elements' and the contacts').
  std::vector<double> f_elastic_;
  std::optional<ForcePulse> pulse_;
  std::optional<PlatePulse> plate_pulse_;
  /// The plate pulse's force times the part of [t0, t1] it is on: its impulse over that interval per unit force.
  [[nodiscard]] double plate_pulse_time(double t0, double t1) const;
  std::vector<int> loaded_;
  double load_x_ = 0.0, load_y_ = 0.0;

  double time_ = 0.0;
  long steps_ = 0, plate_steps_ = 0;
  double substep_min_ = 0.0, substep_max_ = 0.0;
  StepLimits limits_;
  double contact_energy_ = 0.0;
  double friction_work_ = 0.0, dashpot_work_ = 0.0, boundary_work_ = 0.0, drive_work_ = 0.0;
  double plate_normal_force_ = 0.0, plate_tangential_force_ = 0.0;
  double max_plate_contact_radius_ = 0.0;
  SideWalls walls_;
  double wall_force_[2] = {0.0, 0.0};

  std::vector<Motion> stage_velocity_[4];  // newmark_rk4: each RK4 stage's grain velocities
  // newmark_rk4: K and the factorisations, which depend on the plate and the step alone (copies
  // share them), and this run's state: the plate's acceleration and the converged forces on it.
  struct Newmark;
  std::shared_ptr<Newmark> newmark_;
  bool newmark_started_ = false;
  std::vector<double> newmark_acceleration_, contact_conservative_, contact_friction_;
  long iterations_ = 0;
  int most_iterations_ = 0;
  long factorisations_ = 0;
};

}  // namespace sedwave::forward::interface
