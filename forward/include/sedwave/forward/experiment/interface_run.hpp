#pragma once
// One run of a granular-solid interface scene and its HDF5 file (docs/interface.md, "Outputs").
// SI units (m, kg, s, N, J).
#include <filesystem>
#include <ostream>
#include <vector>

#include "sedwave/forward/experiment/interface_scene.hpp"

namespace sedwave::forward::experiment {

/// Time series sampled every output interval (and at t = 0).
struct InterfaceSeries {
  std::vector<double> time;
  std::vector<interface::Energies> energies;
  std::vector<double> plate_normal_force;      ///< [N] total grain force on the plate, normal to it
  std::vector<double> plate_tangential_force;  ///< [N] along it
  std::vector<double> step;                    ///< [s] the last step before the sample
  std::vector<double> step_min, step_max;      ///< [s] over the interval
  std::vector<long> steps;                     ///< steps taken so far
  std::vector<interface::StepLimits> limits;   ///< the limits of the last step [s]
  /// How many grains share the grains' mechanical energy: the participation ratio (sum e_i)^2 / sum e_i^2
  /// of each grain's energy (interface::GranularPlate::grain_energies); 0 without grains.
  std::vector<double> grain_participation;
};

struct InterfaceRun {
  InterfaceSeries series;
  /// [J] the strike's kinetic energy (velocity drive) or the pulse's work, plus the static load's work
  /// during the run; the precompressed static state's own energy is not counted
  double input_energy = 0.0;
  long relaxation_steps = 0;  ///< steps taken to bring a precompressed packing to rest
  /// [N] at rest under the precompression: the normal force on the plate, on the left and right walls
  double static_plate_force = 0.0, static_left_wall_force = 0.0, static_right_wall_force = 0.0;
  double direct_from = 0.0, direct_to = 0.0;  ///< [m] the edge struck by a direct strike
  std::vector<int> driven;    ///< indices of the driven grains
  std::vector<int> probe_nodes;
  std::vector<std::vector<double>> probe_velocity;  ///< [probe][sample] |v| [m/s]
  std::vector<double> arrival;                      ///< [s] per probe (NaN: never moved)
  std::vector<int> line_nodes;                      ///< the nodes of the recorded line, left to right
  std::vector<std::vector<double>> line_vx, line_vy;  ///< [sample][node] [m/s]
  std::vector<double> snapshot_time;
  std::vector<std::vector<double>> snapshots;  ///< plate displacements [m], 2 per node (x, y)
  std::vector<double> node_x, node_y;          ///< reference node positions [m]
  std::vector<interface::Grain> final_grains;
  double max_contact_radius = 0.0;             ///< [m] largest grain-plate contact radius
  double element_size = 0.0;                   ///< [m] min(a, b)
  double worst_balance = 0.0;                  ///< max |balance - input| / input over the samples
  double seconds = 0.0;                        ///< wall-clock time of the run
  long iterations = 0;       ///< newmark_rk4: fixed-point iterations in all (0: velocity_verlet)
  int most_iterations = 0;   ///< newmark_rk4: the most in one step
  long factorisations = 0;   ///< newmark_rk4: factorisations of M + C dt/2 + K dt^2/4
  long plate_steps = 0;      ///< the plate's steps (multirate: the outer steps; the grains' steps otherwise)
};

/// What a run will cost and how hard it strikes, from closed forms before anything is allocated
/// (docs/interface.md, "Budgets"). Counts are doubles: a nonsensical scene may ask for more than
/// any integer holds, and is refused on that number.
struct InterfaceEstimate {
  double plate_limit = 0.0;       ///< [s] the mesh's stable step 2/omega_max (exact)
  double hertz_limit = 0.0;       ///< [s] a Hertz contact's limit at the strike's or load's peak overlap
  double friction_limit = 0.0;    ///< [s] Coulomb-tanh's limit at that contact force (inf without friction)
  double step = 0.0;              ///< [s] the step at its tightest: theta times the tightest limit, or the fixed step
  double peak_overlap = 0.0;      ///< [m] the grain-plate Hertz overlap at that peak (0: no beads)
  double contact_radius = 0.0;    ///< [m] sqrt(r delta) there
  double steps = 0.0;             ///< duration / step, and at least one per sample
  double samples = 0.0;           ///< output samples
  double nodes = 0.0;             ///< plate nodes
  double grains = 0.0;
  double memory_bytes = 0.0;      ///< the run's arrays and recorded series
};
[[nodiscard]] InterfaceEstimate estimate_interface_run(const InterfaceScene& scene);

/// Refuses (std::invalid_argument naming the cause and the keys or options that set it) a scene the
/// models cannot describe: a Hertz overlap above a tenth of the bead radius (small-strain contact),
/// a contact radius reaching half the plate's thickness (the plane-stress plate), a fixed step above
/// the mesh's stability limit.
void check_interface_physics(const InterfaceScene& scene, const InterfaceEstimate& estimate);

/// The largest overlap, as a fraction of the bead radius, that check_interface_physics accepts.
inline constexpr double kMaxOverlapFraction = 0.1;
/// A run stops once its energy balance is off by more than this times the input: it is unstable.
inline constexpr double kUnstableBalance = 1.0;

/// Builds the scene's plate and packing, drives the free row and records. `progress` (may be null)
/// gets a line per tenth of the run, and one at least every `progress_seconds` of wall time with
/// the time left. Throws std::runtime_error naming the step and its limits when the energy balance
/// drifts by more than kUnstableBalance times the input.
InterfaceRun run_interface(const InterfaceScene& scene, std::ostream* progress, double progress_seconds = 10.0);

/// Writes the run atomically (every dataset states its unit in an attribute).
void write_interface_run_file(const std::filesystem::path& path, const InterfaceScene& scene, const InterfaceRun& run);

/// energies.csv, probes.csv and snapshot_K.csv (K = 1, 2, ...: each snapshot) under `dir`, for plots.
void write_interface_csv(const std::filesystem::path& dir, const InterfaceScene& scene, const InterfaceRun& run);

}  // namespace sedwave::forward::experiment
