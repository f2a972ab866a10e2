#pragma once
// Driving a prepared channel and measuring how the wave attenuates and how fast it travels.
//
// The lower wall oscillates sinusoidally (along z: longitudinal; along x: transverse) with amplitude
// A and angular frequency omega; the far end is either frozen (the thesis) or an absorbing layer of
// graded viscous drag so little reflects. Flow grains are grouped into layers (slabs along z, fixed
// membership from the static packing); each layer's mean displacement is recorded, which is far
// less noisy than any single probe grain. A lock-in at the drive frequency, over whole periods
// between the passage of the front and the return of any reflection, gives each layer's amplitude
// and phase; straight-line fits over layers give alpha and k (measurement.hpp).
//
// Units: dimensionless, as the rest of forward/: lengths in mean diameters d, masses in the mass m
// of a grain of diameter d, stiffness in kappa (the Hooke kn), so times are in sqrt(m/kappa) and the
// results are alpha_hat, k_hat, c_hat directly (docs/physics.md).
#include <mpi.h>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sedwave/forward/channel/measurement.hpp"
#include "sedwave/forward/channel/packing_units.hpp"
#include "sedwave/forward/channel/preparation.hpp"

namespace sedwave::forward::channel {

enum class DriveAxis { longitudinal, transverse };
enum class FarEnd { frozen, absorbing };
/// The far (upper) wall during a drive: held in place (the thesis), or loaded: a rigid body free
/// to move along z under the constant force that holds the packing at its static state (the
/// grains' static force on it), like a sediment under an overburden. `FarEnd` decides separately
/// whether an absorbing layer lies in front of it.
enum class FarWall { frozen, loaded };

/// The shape of a broadband drive.
enum class BroadbandShape {
  /// One Gaussian-windowed tone burst centred on the band's middle; the band's edges lie 2.5
  /// spectral standard deviations out, where the drive spectrum is 4 % of its peak. Short.
  gaussian_pulse,
  /// A logarithmic sweep (equal time per octave) from omega_hat_min / 1.5 to 1.5 omega_hat_max over
  /// sweep_periods periods of omega_hat_min, with smooth ramps outside the band: across the band the
  /// drive's spectrum stays within 0.3-1 of its peak (falling as 1/sqrt(omega)), where a pulse's
  /// edges get 4 %. Longer.
  log_chirp,
};

/// A broadband drive: the wall moves by one pulse or chirp whose spectrum spans [omega_hat_min,
/// omega_hat_max]. alpha_hat and c_hat are measured at `frequencies` log-spaced frequencies over the
/// band, from the Fourier transforms of the layer records (transient_spectrum): one run, many
/// frequencies. Needs an absorbing far end.
struct PulseBand {
  double omega_hat_min = 0.2;
  double omega_hat_max = 1.8;
  int frequencies = 12;
  /// If not empty: the frequencies to measure (inside the band), e.g. a table's grid values,
  /// instead of `frequencies` log-spaced ones.
  std::vector<double> measured;
  BroadbandShape shape = BroadbandShape::gaussian_pulse;
  double sweep_periods = 20.0;  ///< log_chirp: sweep duration in periods of omega_hat_min
  /// The measured frequencies: `measured`, or log-spaced from omega_hat_min to omega_hat_max.
  [[nodiscard]] std::vector<double> omega_hats() const;
};

struct DriveSettings {
  DriveAxis axis = DriveAxis::longitudinal;
  double amplitude = 1e-4;   ///< A [mean diameters] (thesis: 1e-4)
  double omega_hat = 0.5;    ///< drive angular frequency [1/sqrt(m/kappa)] (sinusoidal drive)
  std::optional<PulseBand> pulse;  ///< set: a broadband pulse instead of the sinusoid at omega_hat
  double gamma_hat = 0.05;   ///< contact dashpot gamma / sqrt(kappa m)
  FarEnd far_end = FarEnd::frozen;
  FarWall far_wall = FarWall::frozen;
  double far_wall_mass = 0.0;  ///< of a loaded far wall [mean grain masses]; 0: its grains' total mass
  double absorbing_fraction = 0.3;  ///< of the column, at the far end
  /// Drag at the far end of the absorbing layer, in units of m omega; it grows quadratically from 0.
  double absorbing_strength = 1.0;
  /// Run length in drive periods (pulse: periods of the band's centre); 0: until echoes could
  /// return (pulse: until the pulse has passed the last measured layer).
  double periods = 0.0;
  int samples_per_period = 32;
  double layer_thickness = 1.0;     ///< [mean diameters]
  int skip_layers = 2;              ///< layers next to the driven wall left out of the fit (near field)
  double max_fit_depth = 0.0;       ///< layers centred deeper than this [mean diameters] are not fitted; 0: no limit
  /// Also record one grain per layer (the flow grain nearest the layer's centre) and measure alpha
  /// and c from those single grains alone, as the thesis did, beside the layer averages.
  bool grain_probes = false;
  double settle_periods = 3.0;      ///< after the front passes, before a layer counts as steady
  /// While the lock-in windows are not steady (AcousticResult::warning), or the fit failed with
  /// layers lost below the noise floor (AcousticResult::layers_below_noise), continue the run by its
  /// first length, with every window moved as far later, at most this many times. Only for a
  /// sinusoid with an absorbing far end and no fixed `periods` (else no later window is echo-free
  /// or the user fixed the length); 0: never.
  int steady_extensions = 2;
  double time_step_fraction = 0.01; ///< dt / binary collision time (thesis: 0.01)
  /// A still pore fluid during the drive, in the packing's dimensionless groups
  /// (fluid_in_packing_units); absent: dry. The packing itself is prepared dry: viscous forces
  /// vanish at rest, so the static state is the same.
  std::optional<dem::FluidSpec> fluid;
  /// Where rank 0 says, before a run longer than kAnnouncedRunSeconds, how many steps it takes and
  /// how long they will last at the rate its first steps measured; nullptr: silent.
  std::ostream* log = nullptr;
};

/// Expected wall time [s] above which a drive announces its length (DriveSettings::log).
inline constexpr double kAnnouncedRunSeconds = 10.0;

/// alpha_hat and c_hat at one frequency of a broadband (pulse) run.
struct SpectralResult {
  double omega_hat = 0.0;
  PropagationFit fit;
  int layers_used = 0;
  std::string problem;  ///< empty when alpha and c were measured at this frequency
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

/// Single-grain probes: one flow grain per layer, the one nearest the layer's centre, measured
/// exactly as the layers are (same windows, fits and rules). A single grain also moves with the
/// incoherent, scattered field that a layer average cancels, so these fits scatter more; they are
/// recorded to show by how much, not to replace the layers.
struct SingleGrainProbes {
  std::vector<std::int64_t> id;                   ///< per layer; -1 where a layer holds no flow grain
  std::vector<double> z;                          ///< the grain's height [d from the driven wall's surface]
  std::vector<std::vector<double>> displacement;  ///< [probe][sample] [d], along the drive axis
  PropagationFit fit;
  std::vector<SpectralResult> spectrum;           ///< broadband drives
  int probes_used = 0;
  std::string problem;                            ///< empty when alpha and c were measured
};

/// Everything measured in one driven run (rank 0 holds the records; results are on every rank).
/// For a pulse, fit, layers_used and problem are those of the measured frequency nearest the band's
/// centre (omega_hat says which), and `spectrum` holds every frequency; problem is set only when no
/// frequency could be measured.
struct AcousticResult {
  // Inputs resolved to dimensionless numbers.
  double omega_hat = 0.0, gamma_hat = 0.0, amplitude = 0.0;
  double kappa = 0.0, grain_mass = 0.0, mean_diameter = 1.0;  ///< the units used
  // Records.
  std::vector<double> layer_z;           ///< layer centres, from the driven wall's surface
  std::vector<int> layer_grains;
  double sample_dt = 0.0;
  double time_step = 0.0;                ///< of the integration [sqrt(m/kappa)]; sample_dt is a multiple
  std::vector<std::vector<double>> displacement;  ///< [layer][sample], along the drive axis
  // Measurement.
  double wave_speed_estimate = 0.0;      ///< from first-peak arrival times (sets the windows)
  std::vector<ProbeWindow> windows;
  std::vector<LockIn> lock_ins;          ///< per layer (zero amplitude where no window)
  PropagationFit fit;                    ///< over layers with valid windows beyond skip_layers
  FirstPeakFit first_peak;               ///< the thesis's method, for comparison
  std::vector<SpectralResult> spectrum;  ///< pulse drives: one entry per measured frequency
  std::optional<SingleGrainProbes> single_grains;  ///< with DriveSettings::grain_probes
  int layers_used = 0;
  /// Layers with a steady window whose lock-in lies below the noise floor (kMinSignalToNoise): in a
  /// strongly damped channel the switch-on transient lingers there, and a later window finds them.
  int layers_below_noise = 0;
  std::int64_t steps = 0;
  int extensions = 0;                    ///< times the run was continued (DriveSettings::steady_extensions)
  double wall_seconds = 0.0;
  std::string problem;                   ///< empty when alpha and c were measured
  /// Set when the first and last halves of the lock-in windows disagree (more than 5 % in alpha or
  /// 1 % in c, and more than 3 standard errors) even after DriveSettings::steady_extensions: the
  /// windows hold a transient. The result stands, but a longer run may move it.
  std::string warning;
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

/// The layers the attenuation and wavenumber fits may use, indices [first, end) into the layer
/// centres `layer_z` [d from the driven wall]: past skip_layers, before the absorbing layer, not
/// deeper than max_fit_depth. Both engines use exactly this.
struct LayerRange {
  std::size_t first = 0, end = 0;
};
[[nodiscard]] LayerRange fitted_layers(const DriveSettings& d, std::span<const double> layer_z);

/// Length of the absorbing layer [d]; 0 with a frozen far end.
[[nodiscard]] double absorbing_length(const DriveSettings& d, const PackingUnits& u);
/// The absorbing layer's drag coefficient [force time / length] on a free grain at height z [length]
/// for a drive at omega [1/time]: strength m omega s^2, s rising from 0 to 1 over the last
/// absorbing_fraction of the column, 0 below. Both engines apply exactly this.
[[nodiscard]] double absorbing_drag(const DriveSettings& d, const PackingUnits& u, double omega, double z);
/// The mass of a loaded far wall [mass]: far_wall_mass mean grain masses, or else the total mass of
/// the upper wall's grains. Both engines use exactly this.
[[nodiscard]] double loaded_wall_mass(const DriveSettings& d, const PackingUnits& u, std::span<const dem::Grain> grains);

/// Drives `packing` (its grains spread over the ranks of comm in any way, e.g. all on rank 0; the box
/// as rank 0 holds it) with contact law `contact`
/// (its damping is replaced by gamma_hat) and measures alpha_hat and c_hat. Collective over comm.
[[nodiscard]] AcousticResult run_acoustic(MPI_Comm comm, const PreparedChannel& packing, dem::ContactSpec contact,
                                          const DriveSettings& drive);

/// Measures alpha_hat and c_hat from layer records already in `r` (omega_hat, gamma_hat, layer_z,
/// displacement [layer][sample] from t = 0 in steps of sample_dt): the windows, lock-ins and fit of
/// run_acoustic, for records made elsewhere, e.g. by LAMMPS on the same packing and drive
/// (bench/channel/lammps_acoustic.sh). Sets wave_speed_estimate, windows, lock_ins, fit,
/// first_peak, layers_used and problem.
void measure_layer_records(AcousticResult& r, const DriveSettings& drive, const PackingUnits& units);

}  // namespace sedwave::forward::channel
