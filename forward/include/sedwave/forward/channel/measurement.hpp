#pragma once
// Measuring attenuation and wavenumber from displacement records along a driven granular channel:
// the lower wall oscillates along z and probes (or layers) at positions z record u(z, t). Pure signal
// processing: nothing here knows about the DEM engine.
//
// Units: any consistent set. sedwave passes dimensionless ones (docs/physics.md): positions z in
// grain diameters d and times t in sqrt(m/kappa), so omega is omega_hat, alpha is alpha_hat [Np per
// grain diameter], k is k_hat and c = omega/k is c_hat.
//
// Sign convention. A wave travelling to +z is Re exp(i(k~ z - omega t)) with k~ = k + i alpha, so a
// probe at z sees A0 exp(-alpha z) cos(omega t - k z + phi0). A lock-in reports a record as
// A cos(omega t - phi); its phase phi = k z - phi0 therefore GROWS with z, and
//   alpha = -d ln A / dz,   k = d phi / dz,   c = omega / k.
// Spectra use the same convention, X(omega) = sum_n x(t_n) exp(+i omega t_n), so a layer dz further
// along has X_probe(omega) = X_ref(omega) exp(i k~(omega) dz).
#include <complex>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace sedwave::forward::channel {

/// A uniformly sampled real record: values[n] is the signal at t_first + n dt.
struct SampledSignal {
  std::span<const double> values;
  double t_first = 0.0;
  double dt = 1.0;
};

/// A time interval [begin, end].
struct TimeWindow {
  double begin = 0.0;
  double end = 0.0;
};

// ---- Lock-in: one probe, one frequency -------------------------------------------------------------

/// What the lock-in fits besides the sinusoid: a constant offset always, a linear drift optionally
/// (a channel that slowly compacts or creeps).
enum class Drift { none, linear };

/// A record's amplitude and phase at one frequency: x(t) ~ amplitude cos(omega t - phase) + offset
/// [+ drift (t - t_mid)], with standard errors from the residual scatter (white-noise assumption).
struct LockIn {
  double amplitude = 0.0;
  double phase = 0.0;  ///< radians in (-pi, pi], referred to t = 0 (not to the window)
  double sigma_amplitude = 0.0;
  double sigma_phase = 0.0;
  double offset = 0.0;
  double drift = 0.0;         ///< slope per unit time (0 unless Drift::linear)
  double residual_rms = 0.0;  ///< rms of what the fit leaves over
  int periods = 0;            ///< whole periods actually used
  std::size_t samples = 0;    ///< samples actually used
};

/// Lock-in at angular frequency omega over the window trimmed to a whole number of periods
/// [begin, begin + P 2pi/omega]. The exact discrete least-squares fit of a cos + b sin + offset
/// (+ drift) makes the answer exact for a noise-free sinusoid whatever the samples per period,
/// where a plain DFT sum is only exact for an integer number of samples per period. Throws
/// std::invalid_argument if the window leaves the record or holds less than one period.
[[nodiscard]] LockIn lock_in(const SampledSignal& signal, double omega, TimeWindow window, Drift drift = Drift::none);

// ---- Attenuation and wavenumber from many probes ---------------------------------------------------

/// alpha, k and c = omega/k from a steady-state wave, with standard errors.
struct PropagationFit {
  double alpha = 0.0;
  double sigma_alpha = 0.0;
  double k = 0.0;
  double sigma_k = 0.0;
  double c = 0.0;
  double sigma_c = 0.0;
  /// chi^2 per degree of freedom of each straight-line fit (NaN with two probes). Values well above
  /// 1 mean the probes scatter more than their lock-in errors say: near-field, reflections, noise
  /// that is not white. The sigmas above are then inflated by sqrt(chi^2/dof) (Birge ratio).
  double chi2_per_dof_amplitude = 0.0;
  double chi2_per_dof_phase = 0.0;
  std::vector<double> unwrapped_phase;  ///< phase per probe after unwrapping along z
};

/// How fit_attenuation_and_wavenumber weighs its probes.
enum class ProbeWeights {
  /// 1/sigma^2 from each lock-in: right when the probes differ only by measurement noise.
  lock_in_errors,
  /// All probes alike, errors from the line's own scatter. Right for the layers of a disordered
  /// packing, whose deviations from the line (scattering, structure: ~0.1 in ln A) dwarf their
  /// lock-in errors (~1e-3): lock-in weights would let the two nearest layers, in the near field,
  /// decide the slope.
  uniform,
};

/// Least squares over probes at strictly ascending positions z: ln A = const - alpha z and
/// phi = const + k z. With ProbeWeights::lock_in_errors the weights are 1/sigma^2 from the lock-ins;
/// if any lock-in sigma is zero (a noise-free record), or with ProbeWeights::uniform, all probes
/// weigh the same and the errors come from the line's own scatter.
///
/// Unwrapping assumption: the phase is unwrapped along z by choosing, at each probe, the branch
/// closest to the previous phase plus expected_k (z_i - z_{i-1}). With expected_k = 0 this needs
/// adjacent probes closer than half a wavelength; with a rough estimate of k (within
/// pi / max spacing of the truth) any spacing works.
[[nodiscard]] PropagationFit fit_attenuation_and_wavenumber(std::span<const double> z, std::span<const LockIn> probes,
                                                            double omega, double expected_k = 0.0,
                                                            ProbeWeights weights = ProbeWeights::lock_in_errors);

/// Probes whose lock-in amplitude is at least this many times its standard error carry the wave.
inline constexpr double kMinSignalToNoise = 10.0;

/// Indices of the probes that carry the wave: amplitude above zero and at least min_snr times its
/// lock-in error.
/// Where a strongly attenuated wave has decayed into the noise floor, ln A of the noise would flatten
/// the fitted decay (|noise| does not decay); a layer at a speckle node of a disordered packing is
/// left out alone, the layers behind it stay.
[[nodiscard]] std::vector<std::size_t> probes_above_noise(std::span<const LockIn> probes,
                                                         double min_snr = kMinSignalToNoise);

/// An absorbing layer at least this many wavelengths long reflects less than 1 % of the wave.
inline constexpr double kAbsorbingWavelengths = 2.5;
/// A shorter layer is accepted when the medium itself damps the round trip through it below this.
inline constexpr double kTolerableEcho = 0.01;

/// Why a steady-state fit over probes spanning `span` cannot be trusted, or empty if it can. A fit
/// over less than a wavelength cannot separate the travelling wave from near field and reflections.
/// An absorbing layer (of length `absorbing_length`; 0 for none) shorter than kAbsorbingWavelengths
/// may reflect more than 1 % of what reaches it, unless the fitted attenuation damps the round trip
/// through the layer, exp(-2 alpha L), below kTolerableEcho. What a channel cannot resolve is
/// reported, not filled with numbers.
[[nodiscard]] std::string resolution_problem(const PropagationFit& fit, double span, double absorbing_length);

// ---- A steady complex field: forward and reflected wave ---------------------------------------------

/// A complex steady-state field sampled at equally spaced positions, written as a wave travelling to
/// +z plus a reflected one: u(z) = a exp(-i q (z - z_0)) + b exp(+i q (z - z_end)), q = k - i alpha.
/// (Time dependence exp(+i omega t), so a lock-in phase is -arg u.) Both terms satisfy
/// u(z + h) + u(z - h) = 2 cos(q h) u(z), which gives q by linear least squares over all triples
/// without any guess; a and b follow by linear least squares.
struct TwoWaveFit {
  double alpha = 0.0;                 ///< of the forward wave [1/length]
  double k = 0.0;                     ///< [1/length], 0 < k h < pi
  std::complex<double> forward;       ///< a: forward amplitude at z_0 (the first sample)
  std::complex<double> backward;      ///< b: reflected amplitude at z_end (the last sample)
  /// |b| / |a exp(-i q (z_end - z_0))|: reflection coefficient at the end of the samples.
  double reflection = 0.0;
  double relative_residual = 0.0;     ///< rms misfit / rms field
};

/// Fits the two waves to samples u[n] at z_0 + n h (n = 0..size-1, at least 4). Throws
/// std::invalid_argument for fewer samples or a zero field.
[[nodiscard]] TwoWaveFit fit_two_waves(double h, std::span<const std::complex<double>> u);
/// The same with the wavenumber given (k and alpha, e.g. from fit_attenuation_and_wavenumber): only
/// a and b are fitted. Far more robust for a noisy (disordered) field, where the three-term
/// recurrence amplifies the noise.
[[nodiscard]] TwoWaveFit fit_two_waves(double h, std::span<const std::complex<double>> u, double k, double alpha);

// ---- Which part of each record is a clean steady state --------------------------------------------

/// The channel's timing: the wall starts driving at drive_start; the wave front reaches z at
/// drive_start + z / c; the reflection from the far end z = channel_length returns to z at
/// drive_start + (2 channel_length - z) / c.
struct ChannelTiming {
  double drive_start = 0.0;
  double wave_speed = 1.0;         ///< estimate of the front speed
  double speed_uncertainty = 0.0;  ///< relative: the front may be this much slower, the echo this much faster
  double channel_length = 0.0;     ///< driven wall at z = 0, reflecting end at z = channel_length
  double period = 0.0;             ///< 2 pi / omega
  double settle_periods = 3.0;     ///< wait after the front before the motion counts as steady
  double margin_periods = 1.0;     ///< stop this long before the reflection can arrive
  int min_periods = 2;             ///< fewer whole periods than this is no window
  double run_end = 1e300;          ///< the record ends here
};

/// A probe's measurement window: whole periods between the settled front and the echo.
struct ProbeWindow {
  TimeWindow window;
  int periods = 0;
  std::string problem;  ///< why there is no valid window; empty when there is one
  [[nodiscard]] bool valid() const { return problem.empty(); }
};

/// Per probe: [front passed + settle, echo arrival - margin] (also <= run_end), shortened to whole
/// periods from its start. Probes without min_periods whole periods get valid() == false and a
/// problem naming the times involved.
[[nodiscard]] std::vector<ProbeWindow> measurement_windows(std::span<const double> z, const ChannelTiming& timing);

// ---- The thesis's first-peak method (for comparison) -----------------------------------------------

/// Time and height of a record's first local maximum above the threshold (refined by a parabola
/// through the three samples around it).
struct Peak {
  double time = 0.0;
  double amplitude = 0.0;
};

/// First local maximum exceeding relative_threshold * max|x| (skips pre-arrival noise). Throws
/// std::invalid_argument if there is none.
[[nodiscard]] Peak first_peak(const SampledSignal& signal, double relative_threshold = 0.5);

/// alpha from the log-height slope of each probe's first peak and speed from the peaks' arrival
/// times, both by unweighted least squares over z (errors from the scatter; NaN with two probes).
/// For a dispersive medium the first peak is a transient, so this is biased against the lock-in.
/// Records without a first peak are left out (their peak is NaN); fewer than 2 with one throw
/// std::invalid_argument.
struct FirstPeakFit {
  double alpha = 0.0;
  double sigma_alpha = 0.0;
  double speed = 0.0;
  double sigma_speed = 0.0;
  std::vector<Peak> peaks;  ///< one per record
  int skipped = 0;          ///< records without a first peak
};
[[nodiscard]] FirstPeakFit first_peak_attenuation(std::span<const double> z, std::span<const SampledSignal> signals,
                                                  double relative_threshold = 0.5);

// ---- Broadband: a transient record at any frequency ------------------------------------------------

/// Fourier transform of a transient record at angular frequency omega,
///   X(omega) = dt sum_n x_n exp(i omega t_n),
/// returned as a LockIn with amplitude |X| and phase arg X (the lock-in's convention: a delay tau
/// adds omega tau to the phase). The record must hold the whole transient (quiet at both ends);
/// X is then the continuous transform at any omega, not only at FFT bins, and X_probe / X_ref is
/// the transfer function between two probes. `noise` is |X| of the record's noise at omega (see
/// transient_noise); it becomes sigma_amplitude, and noise / |X| sigma_phase, so probes_above_noise
/// and the fits treat these like lock-ins.
[[nodiscard]] LockIn transient_spectrum(const SampledSignal& signal, double omega, double noise = 0.0);

/// Noise level of |X| for a record whose signal has no content above omega_quiet: the rms of |X| at
/// `count` frequencies spread over [omega_quiet, 2 omega_quiet]. Whatever is there (round-off,
/// residual motion of the packing, harmonics made by contacts that clap) is not the linear response
/// to the drive. omega_quiet must lie below the record's Nyquist frequency pi / dt.
[[nodiscard]] double transient_noise(const SampledSignal& signal, double omega_quiet, int count = 16);

// ---- Broadband: transfer function between two layers -----------------------------------------------

struct TransferOptions {
  /// A bin counts when both spectra exceed this fraction of their maximum magnitude.
  double relative_threshold = 1e-3;
  /// Rough phase speed to choose the branch of arg H at the first bin of each band with signal.
  /// 0: take the principal branch (needs k dz < pi there).
  double speed_guess = 0.0;
};

/// alpha(omega), k(omega) at one frequency bin with signal.
struct SpectralPoint {
  double omega = 0.0;
  double alpha = 0.0;
  double k = 0.0;
  double c = 0.0;                   ///< omega / k
  double relative_magnitude = 0.0;  ///< |X_ref| over its maximum: how much signal the bin has
};

/// From H = X_probe / X_ref = exp(i k~ dz) between records dz apart (same dt, same start):
/// alpha = -ln|H| / dz and k = arg H / dz, with arg H unwrapped along omega. Records are zero-padded
/// to a power of two; each must hold its whole pulse (quiet at both ends), and be longer than twice
/// the travel time so the phase moves less than pi between neighbouring bins.
[[nodiscard]] std::vector<SpectralPoint> transfer_function(std::span<const double> x_ref,
                                                           std::span<const double> x_probe, double dt, double dz,
                                                           const TransferOptions& options = {});

}  // namespace sedwave::forward::channel
