#include "sedwave/forward/channel/measurement.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sedwave/forward/channel/fft.hpp"

namespace sedwave::forward::channel {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Window edges computed as whole periods land a few ulps either side of the intended instant;
// this slack (in periods or samples) keeps such edges from losing a whole period or sample.
constexpr double kEdgeSlack = 1e-9;

std::string str(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

/// Phase in (-pi, pi].
double wrap_phase(double phi) {
  const double r = std::remainder(phi, kTwoPi);
  return r <= -std::numbers::pi ? r + kTwoPi : r;
}

/// The branch of `phase` (mod 2 pi) closest to `reference`.
double nearest_branch(double phase, double reference) {
  return phase + kTwoPi * std::round((reference - phase) / kTwoPi);
}

// ---- Straight-line least squares ------------------------------------------------------------------

struct LineFit {
  double intercept = 0.0;
  double slope = 0.0;
  double sigma_slope = 0.0;
  double chi2_per_dof = 0.0;
};

/// y = intercept + slope x. With sigma (all > 0): weighted, formal error inflated by the Birge ratio
/// when the scatter exceeds the sigmas. With empty sigma: unweighted, error from the scatter.
LineFit fit_line(std::span<const double> x, std::span<const double> y, std::span<const double> sigma) {
  const std::size_t n = x.size();
  auto weight = [&](std::size_t i) { return sigma.empty() ? 1.0 : 1.0 / (sigma[i] * sigma[i]); };
  // Centre x first: the slope then needs no difference of large sums.
  double sw = 0.0, swx = 0.0, swy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sw += weight(i);
    swx += weight(i) * x[i];
    swy += weight(i) * y[i];
  }
  const double x_mean = swx / sw, y_mean = swy / sw;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += weight(i) * (x[i] - x_mean) * (x[i] - x_mean);
    sxy += weight(i) * (x[i] - x_mean) * (y[i] - y_mean);
  }
  LineFit fit;
  fit.slope = sxy / sxx;
  fit.intercept = y_mean - fit.slope * x_mean;
  double chi2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - fit.intercept - fit.slope * x[i];
    chi2 += weight(i) * r * r;
  }
  const double dof = static_cast<double>(n) - 2.0;
  fit.chi2_per_dof = dof > 0.0 ? chi2 / dof : kNaN;
  if (sigma.empty()) {
    fit.sigma_slope = std::sqrt(fit.chi2_per_dof / sxx);
  } else {
    const double birge = dof > 0.0 ? std::max(1.0, fit.chi2_per_dof) : 1.0;
    fit.sigma_slope = std::sqrt(birge / sxx);
  }
  return fit;
}

void require_ascending(std::span<const double> z, std::size_t count, const char* who) {
  if (z.size() != count) throw std::invalid_argument(std::string(who) + ": one position per probe needed");
  if (z.size() < 2) throw std::invalid_argument(std::string(who) + ": at least two probes needed");
  for (std::size_t i = 1; i < z.size(); ++i) {
    if (!(z[i] > z[i - 1])) throw std::invalid_argument(std::string(who) + ": probe positions must be strictly ascending");
  }
}

// ---- Lock-in ---------------------------------------------------------------------------------------

/// Index range [first, last] of the samples in [begin, stop].
struct SampleRange {
  std::size_t first;
  std::size_t last;
};

SampleRange samples_in(const SampledSignal& signal, double begin, double stop) {
  const double first = std::ceil((begin - signal.t_first) / signal.dt - kEdgeSlack);
  const double last = std::floor((stop - signal.t_first) / signal.dt + kEdgeSlack);
  const double record_end = signal.t_first + signal.dt * static_cast<double>(signal.values.size() - 1);
  if (first < 0.0 || last > static_cast<double>(signal.values.size() - 1)) {
    throw std::invalid_argument("lock_in: window [" + str(begin) + ", " + str(stop) + "] leaves the record [" +
                                str(signal.t_first) + ", " + str(record_end) + "]");
  }
  return {static_cast<std::size_t>(first), static_cast<std::size_t>(last)};
}

}  // namespace

LockIn lock_in(const SampledSignal& signal, double omega, TimeWindow window, Drift drift) {
  if (!(omega > 0.0) || !(signal.dt > 0.0) || signal.values.empty()) {
    throw std::invalid_argument("lock_in: need omega > 0, dt > 0 and a non-empty record");
  }
  const double period = kTwoPi / omega;
  const int periods = static_cast<int>(std::floor((window.end - window.begin) / period + kEdgeSlack));
  if (periods < 1) throw std::invalid_argument("lock_in: window shorter than one period " + str(period));
  const double span = periods * period;
  const SampleRange range = samples_in(signal, window.begin, window.begin + span);

  // Columns cos, sin of omega (t - t_mid), 1 [, (t - t_mid) / span]: centred and scaled so the normal
  // matrix is close to diagonal over whole periods and its solution loses nothing.
  const double t_mid = window.begin + 0.5 * span;
  const Eigen::Index p = drift == Drift::linear ? 4 : 3;
  auto row = [&](std::size_t n) {
    const double tau = signal.t_first + signal.dt * static_cast<double>(n) - t_mid;
    Eigen::Vector4d r(std::cos(omega * tau), std::sin(omega * tau), 1.0, tau / span);
    return r;
  };
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(p);
  for (std::size_t n = range.first; n <= range.last; ++n) {
    const Eigen::VectorXd r = row(n).head(p);
    normal.noalias() += r * r.transpose();
    rhs += r * signal.values[n];
  }
  const Eigen::LDLT<Eigen::MatrixXd> solver(normal);
  const Eigen::VectorXd beta = solver.solve(rhs);
  const std::size_t count = range.last - range.first + 1;
  if (count <= static_cast<std::size_t>(p)) throw std::invalid_argument("lock_in: too few samples in the window");

  double rss = 0.0;
  for (std::size_t n = range.first; n <= range.last; ++n) {
    const double r = signal.values[n] - row(n).head(p).dot(beta);
    rss += r * r;
  }
  const double variance = rss / static_cast<double>(count - static_cast<std::size_t>(p));
  const Eigen::MatrixXd covariance = variance * solver.solve(Eigen::MatrixXd::Identity(p, p));

  // a cos(w tau) + b sin(w tau) = A cos(w tau - psi), psi = atan2(b, a); tau = t - t_mid, so the
  // phase referred to t = 0 is psi + w t_mid.
  const double a = beta(0), b = beta(1);
  const double amplitude = std::hypot(a, b);
  const double var_amplitude =
      (a * a * covariance(0, 0) + 2.0 * a * b * covariance(0, 1) + b * b * covariance(1, 1)) / (amplitude * amplitude);
  const double var_phase = (b * b * covariance(0, 0) - 2.0 * a * b * covariance(0, 1) + a * a * covariance(1, 1)) /
                           (amplitude * amplitude * amplitude * amplitude);
  LockIn result;
  result.amplitude = amplitude;
  result.phase = wrap_phase(std::atan2(b, a) + omega * t_mid);
  result.sigma_amplitude = std::sqrt(std::max(0.0, var_amplitude));
  result.sigma_phase = std::sqrt(std::max(0.0, var_phase));
  result.offset = beta(2);
  result.drift = drift == Drift::linear ? beta(3) / span : 0.0;
  result.residual_rms = std::sqrt(rss / static_cast<double>(count));
  result.periods = periods;
  result.samples = count;
  return result;
}

PropagationFit fit_attenuation_and_wavenumber(std::span<const double> z, std::span<const LockIn> probes, double omega,
                                              double expected_k, ProbeWeights weights) {
  require_ascending(z, probes.size(), "fit_attenuation_and_wavenumber");
  const std::size_t n = z.size();
  std::vector<double> log_amplitude(n), sigma_log_amplitude(n), phase(n), sigma_phase(n);
  bool weighted = weights == ProbeWeights::lock_in_errors;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(probes[i].amplitude > 0.0)) throw std::invalid_argument("fit_attenuation_and_wavenumber: zero amplitude");
    log_amplitude[i] = std::log(probes[i].amplitude);
    sigma_log_amplitude[i] = probes[i].sigma_amplitude / probes[i].amplitude;
    sigma_phase[i] = probes[i].sigma_phase;
    weighted = weighted && sigma_log_amplitude[i] > 0.0 && sigma_phase[i] > 0.0;
    phase[i] = i == 0 ? probes[i].phase
                      : nearest_branch(probes[i].phase, phase[i - 1] + expected_k * (z[i] - z[i - 1]));
  }
  const LineFit amplitude_line = fit_line(z, log_amplitude, weighted ? sigma_log_amplitude : std::vector<double>{});
  const LineFit phase_line = fit_line(z, phase, weighted ? sigma_phase : std::vector<double>{});

  PropagationFit fit;
  fit.alpha = -amplitude_line.slope;
  fit.sigma_alpha = amplitude_line.sigma_slope;
  fit.k = phase_line.slope;
  fit.sigma_k = phase_line.sigma_slope;
  fit.c = omega / fit.k;
  fit.sigma_c = omega * fit.sigma_k / (fit.k * fit.k);
  fit.chi2_per_dof_amplitude = amplitude_line.chi2_per_dof;
  fit.chi2_per_dof_phase = phase_line.chi2_per_dof;
  fit.unwrapped_phase = std::move(phase);
  return fit;
}

std::vector<std::size_t> probes_above_noise(std::span<const LockIn> probes, double min_snr) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < probes.size(); ++i) {
    // > 0 too: a layer the wave never reached has amplitude 0 and (no noise either) error 0.
    if (probes[i].amplitude > 0.0 && probes[i].amplitude >= min_snr * probes[i].sigma_amplitude) kept.push_back(i);
  }
  return kept;
}

std::vector<ProbeWindow> measurement_windows(std::span<const double> z, const ChannelTiming& timing) {
  if (!(timing.wave_speed > 0.0) || !(timing.period > 0.0) || !(timing.channel_length > 0.0) ||
      !(timing.speed_uncertainty >= 0.0 && timing.speed_uncertainty < 1.0)) {
    throw std::invalid_argument("measurement_windows: need wave_speed, period, channel_length > 0 and "
                                "0 <= speed_uncertainty < 1");
  }
  const double slowest = timing.wave_speed * (1.0 - timing.speed_uncertainty);
  const double fastest = timing.wave_speed * (1.0 + timing.speed_uncertainty);
  std::vector<ProbeWindow> windows;
  windows.reserve(z.size());
  for (const double zi : z) {
    const double settled = timing.drive_start + zi / slowest + timing.settle_periods * timing.period;
    const double echo = timing.drive_start + (2.0 * timing.channel_length - zi) / fastest;
    const double stop = std::min(echo - timing.margin_periods * timing.period, timing.run_end);
    ProbeWindow w;
    w.periods = std::max(0, static_cast<int>(std::floor((stop - settled) / timing.period + kEdgeSlack)));
    w.window = {settled, settled + w.periods * timing.period};
    if (zi < 0.0 || zi > timing.channel_length) {
      w.problem = "probe at z=" + str(zi) + " lies outside the channel [0, " + str(timing.channel_length) + "]";
    } else if (w.periods < timing.min_periods) {
      const bool run_too_short = timing.run_end < echo - timing.margin_periods * timing.period;
      w.problem = "probe at z=" + str(zi) + ": motion settles at t=" + str(settled) + " but " +
                  (run_too_short ? "the run ends at t=" + str(timing.run_end)
                                 : "the echo from z=" + str(timing.channel_length) + " arrives at t=" + str(echo)) +
                  ": " + std::to_string(w.periods) + " whole periods, fewer than " +
                  std::to_string(timing.min_periods);
    }
    windows.push_back(w);
  }
  return windows;
}

Peak first_peak(const SampledSignal& signal, double relative_threshold) {
  const std::span<const double> x = signal.values;
  double largest = 0.0;
  for (const double v : x) largest = std::max(largest, std::abs(v));
  const double threshold = relative_threshold * largest;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    if (x[i] > threshold && x[i] > x[i - 1] && x[i] >= x[i + 1]) {
      // Parabola through the three samples: vertex offset delta in samples and its height.
      const double curvature = x[i - 1] - 2.0 * x[i] + x[i + 1];
      const double delta = curvature < 0.0 ? 0.5 * (x[i - 1] - x[i + 1]) / curvature : 0.0;
      return {signal.t_first + (static_cast<double>(i) + delta) * signal.dt,
              x[i] - 0.25 * (x[i - 1] - x[i + 1]) * delta};
    }
  }
  throw std::invalid_argument("first_peak: no local maximum above " + str(relative_threshold) + " of the largest value");
}

FirstPeakFit first_peak_attenuation(std::span<const double> z, std::span<const SampledSignal> signals,
                                    double relative_threshold) {
  require_ascending(z, signals.size(), "first_peak_attenuation");
  FirstPeakFit fit;
  std::vector<double> z_found, log_height, time;
  for (std::size_t k = 0; k < signals.size(); ++k) {
    try {
      fit.peaks.push_back(first_peak(signals[k], relative_threshold));
    } catch (const std::invalid_argument&) {
      // E.g. a layer holding a rattler, which the wave knocks about by more than the wave's own
      // amplitude: one such layer must not cost the whole fit.
      fit.peaks.push_back({std::nan(""), std::nan("")});
      ++fit.skipped;
      continue;
    }
    z_found.push_back(z[k]);
    log_height.push_back(std::log(fit.peaks.back().amplitude));
    time.push_back(fit.peaks.back().time);
  }
  if (z_found.size() < 2) {
    throw std::invalid_argument("first_peak_attenuation: fewer than 2 of " + std::to_string(signals.size()) +
                                " records have a first peak");
  }
  const LineFit height_line = fit_line(z_found, log_height, {});
  const LineFit arrival_line = fit_line(z_found, time, {});  // slope = 1 / speed
  fit.alpha = -height_line.slope;
  fit.sigma_alpha = height_line.sigma_slope;
  fit.speed = 1.0 / arrival_line.slope;
  fit.sigma_speed = arrival_line.sigma_slope / (arrival_line.slope * arrival_line.slope);
  return fit;
}

LockIn transient_spectrum(const SampledSignal& signal, double omega, double noise) {
  if (!(omega > 0.0) || !(signal.dt > 0.0) || signal.values.empty()) {
    throw std::invalid_argument("transient_spectrum: need omega > 0, dt > 0 and a non-empty record");
  }
  // exp(i omega t_n) by a rotating phasor, renormalised now and then so round-off cannot build up.
  const std::complex<double> step = std::polar(1.0, omega * signal.dt);
  std::complex<double> phasor = std::polar(1.0, omega * signal.t_first);
  std::complex<double> sum = 0.0;
  for (std::size_t n = 0; n < signal.values.size(); ++n) {
    sum += signal.values[n] * phasor;
    phasor *= step;
    if (n % 1024 == 1023) phasor = std::polar(1.0, omega * (signal.t_first + signal.dt * static_cast<double>(n + 1)));
  }
  const std::complex<double> x = signal.dt * sum;
  LockIn result;
  result.amplitude = std::abs(x);
  result.phase = std::arg(x);
  result.sigma_amplitude = noise;
  result.sigma_phase = result.amplitude > 0.0 ? noise / result.amplitude : std::numbers::pi;
  result.samples = signal.values.size();
  return result;
}

double transient_noise(const SampledSignal& signal, double omega_quiet, int count) {
  if (!(omega_quiet > 0.0) || count < 1 || 2.0 * omega_quiet >= std::numbers::pi / signal.dt) {
    throw std::invalid_argument("transient_noise: need 0 < omega_quiet < pi / (2 dt) and count >= 1, got omega_quiet " +
                                str(omega_quiet) + ", dt " + str(signal.dt));
  }
  double sum2 = 0.0;
  for (int m = 0; m < count; ++m) {
    const double omega = omega_quiet * (1.0 + (m + 0.5) / count);
    const double a = transient_spectrum(signal, omega).amplitude;
    sum2 += a * a;
  }
  return std::sqrt(sum2 / count);
}

std::vector<SpectralPoint> transfer_function(std::span<const double> x_ref, std::span<const double> x_probe, double dt,
                                             double dz, const TransferOptions& options) {
  if (x_ref.size() != x_probe.size() || x_ref.size() < 4) {
    throw std::invalid_argument("transfer_function: records must have the same length (at least 4)");
  }
  if (!(dt > 0.0) || dz == 0.0) throw std::invalid_argument("transfer_function: need dt > 0 and dz != 0");
  const std::size_t n_fft = next_power_of_two(x_ref.size());
  const auto ref = real_spectrum(x_ref, n_fft, FourierSign::positive);
  const auto probe = real_spectrum(x_probe, n_fft, FourierSign::positive);
  const std::size_t half = n_fft / 2;  // bins 1 .. half-1: no DC, no Nyquist
  double ref_max = 0.0, probe_max = 0.0;
  for (std::size_t m = 1; m < half; ++m) {
    ref_max = std::max(ref_max, std::abs(ref[m]));
    probe_max = std::max(probe_max, std::abs(probe[m]));
  }
  const double bin_width = kTwoPi / (static_cast<double>(n_fft) * dt);
  std::vector<SpectralPoint> points;
  bool previous_bin_used = false;
  double previous_phase = 0.0;
  for (std::size_t m = 1; m < half; ++m) {
    const bool has_signal = std::abs(ref[m]) >= options.relative_threshold * ref_max &&
                            std::abs(probe[m]) >= options.relative_threshold * probe_max;
    if (!has_signal) {
      previous_bin_used = false;
      continue;
    }
    const double omega = bin_width * static_cast<double>(m);
    const std::complex<double> h = probe[m] / ref[m];
    // Within a band, arg H moves by less than pi per bin; at a band's first bin the branch comes
    // from the speed guess, else from the last band's phase speed, else the principal value.
    double reference = std::arg(h);
    if (previous_bin_used) {
      reference = previous_phase;
    } else if (options.speed_guess > 0.0) {
      reference = omega * dz / options.speed_guess;
    } else if (!points.empty()) {
      reference = points.back().k * dz * omega / points.back().omega;
    }
    const double phase = nearest_branch(std::arg(h), reference);
    SpectralPoint p;
    p.omega = omega;
    p.alpha = -std::log(std::abs(h)) / dz;
    p.k = phase / dz;
    p.c = omega / p.k;
    p.relative_magnitude = std::abs(ref[m]) / ref_max;
    points.push_back(p);
    previous_bin_used = true;
    previous_phase = phase;
  }
  return points;
}

std::string resolution_problem(const PropagationFit& fit, double span, double absorbing_length) {
  const double wavelength = 2.0 * std::numbers::pi / fit.k;
  if (!(fit.k > 0.0) || span < wavelength) {
    return "the probes span " + std::to_string(span) + " d, less than one wavelength (" + std::to_string(wavelength) +
           " d); lengthen the channel";
  }
  if (absorbing_length > 0.0 && absorbing_length < kAbsorbingWavelengths * wavelength) {
    // Measured on the exact ordered chain (docs/linear.md, "The absorbing layer"): the layer's
    // reflection stays below both the round-trip damping exp(-2 alpha L) of the medium over the
    // layer and 1 % once the layer is 2.5 wavelengths long.
    const double echo = std::exp(-2.0 * std::max(fit.alpha, 0.0) * absorbing_length);
    if (echo > kTolerableEcho) {
      return "the absorbing layer (" + std::to_string(absorbing_length) + " d) is " +
             std::to_string(absorbing_length / wavelength) + " wavelengths long (" + std::to_string(wavelength) +
             " d each) and the medium damps the round trip through it only to " + std::to_string(echo) +
             "; it may reflect more than 1 %: lengthen the channel or raise the absorbing fraction";
    }
  }
  return {};
}

TwoWaveFit fit_two_waves(double h, std::span<const std::complex<double>> u) {
  using C = std::complex<double>;
  const std::size_t n = u.size();
  if (n < 4) throw std::invalid_argument("two-wave fit: needs at least 4 samples");
  // 2 cos(q h) = sum conj(u_i)(u_{i+1} + u_{i-1}) / sum |u_i|^2 over interior samples.
  C numerator = 0.0;
  double denominator = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    numerator += std::conj(u[i]) * (u[i + 1] + u[i - 1]);
    denominator += std::norm(u[i]);
  }
  if (!(denominator > 0.0)) throw std::invalid_argument("two-wave fit: the field is zero");
  C qh = std::acos(numerator / (2.0 * denominator));  // principal branch: 0 <= Re <= pi
  double k = qh.real() / h;
  double alpha = -qh.imag() / h;  // exp(-i q z) with q = k - i alpha decays as exp(-alpha z)
  // cos is even: the branch fixes only Re q > 0; the sign of alpha is the one that makes the forward
  // wave decay.
  return fit_two_waves(h, u, k, std::abs(alpha));
}

TwoWaveFit fit_two_waves(double h, std::span<const std::complex<double>> u, double k, double alpha) {
  using C = std::complex<double>;
  const std::size_t n = u.size();
  if (n < 4) throw std::invalid_argument("two-wave fit: needs at least 4 samples");
  const C qh(k * h, -alpha * h);
  TwoWaveFit fit;
  fit.k = k;
  fit.alpha = alpha;
  const C i_unit(0.0, 1.0);
  const double z_end = static_cast<double>(n - 1) * h;
  Eigen::MatrixX2cd basis(static_cast<Eigen::Index>(n), 2);
  Eigen::VectorXcd values(static_cast<Eigen::Index>(n));
  for (std::size_t j = 0; j < n; ++j) {
    const double z = static_cast<double>(j) * h;
    const auto row = static_cast<Eigen::Index>(j);
    basis(row, 0) = std::exp(-i_unit * qh * (z / h));
    basis(row, 1) = std::exp(i_unit * qh * ((z - z_end) / h));
    values(row) = u[j];
  }
  const Eigen::Vector2cd ab = basis.colPivHouseholderQr().solve(values);
  fit.forward = ab(0);
  fit.backward = ab(1);
  fit.reflection = std::abs(fit.backward) / std::abs(fit.forward * std::exp(-i_unit * qh * (z_end / h)));
  fit.relative_residual = (basis * ab - values).norm() / values.norm();
  return fit;
}

}  // namespace sedwave::forward::channel
