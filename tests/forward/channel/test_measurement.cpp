// Channel measurements on synthetic records with known alpha and k: the lock-in (exact for any
// samples per period; errors that match the scatter), the probe fit, the steady-state window that
// keeps the echo out, the thesis's first-peak method, and the broadband transfer function and
// transient spectra against the lattice theory. Dimensionless units throughout (lengths in d, times in sqrt(m/kappa)).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "sedwave/forward/channel/fft.hpp"
#include "sedwave/forward/channel/measurement.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward::channel {
namespace {

constexpr double kPi = std::numbers::pi;

/// f sampled at t_first + n dt, n < count.
std::vector<double> sample(const std::function<double(double)>& f, double t_first, double dt, std::size_t count) {
  std::vector<double> x(count);
  for (std::size_t n = 0; n < count; ++n) x[n] = f(t_first + dt * static_cast<double>(n));
  return x;
}

/// 0 before s = 0, 1 after s = 1, C2 in between: a drive that switches on smoothly.
double smooth_onset(double s) {
  if (s <= 0.0) return 0.0;
  if (s >= 1.0) return 1.0;
  return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
}

/// A probe's steady-state wave A0 exp(-alpha z) cos(omega t - k z + phi0).
struct PlaneWave {
  double alpha, k, omega, phi0 = 0.3;
  [[nodiscard]] double operator()(double z, double t) const {
    return std::exp(-alpha * z) * std::cos(omega * t - k * z + phi0);
  }
};

/// Probes at z = 0, 1, ..., last: 3000 samples of `wave` from t = 0 in steps dt, plus white noise
/// of rms `noise` (seeded).
struct ProbeRecords {
  std::vector<double> z;
  std::vector<std::vector<double>> records;
};
ProbeRecords noisy_probe_records(const PlaneWave& wave, double noise, std::uint64_t seed, int last, double dt) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, noise);
  ProbeRecords p;
  for (int i = 0; i <= last; ++i) {
    p.z.push_back(i);
    p.records.push_back(sample([&](double t) { return wave(p.z.back(), t) + normal(rng); }, 0.0, dt, 3000));
  }
  return p;
}

std::vector<LockIn> lock_in_all(const std::vector<std::vector<double>>& records, double dt, double omega,
                                const std::vector<TimeWindow>& windows) {
  std::vector<LockIn> out;
  for (std::size_t i = 0; i < records.size(); ++i) out.push_back(lock_in({records[i], 0.0, dt}, omega, windows[i]));
  return out;
}

TEST(Fft, MatchesTheDirectSumAndInverts) {
  const std::size_t n = 64;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::vector<std::complex<double>> x(n);
  for (auto& v : x) v = {normal(rng), normal(rng)};
  std::vector<std::complex<double>> y = x;
  fft_in_place(y, FourierSign::positive);
  for (std::size_t m = 0; m < n; ++m) {
    std::complex<double> direct = 0.0;
    for (std::size_t j = 0; j < n; ++j) direct += x[j] * std::polar(1.0, 2.0 * kPi * double(m * j % n) / double(n));
    EXPECT_LT(std::abs(y[m] - direct), 1e-12) << "bin " << m;
  }
  fft_in_place(y, FourierSign::negative);
  for (std::size_t j = 0; j < n; ++j) EXPECT_LT(std::abs(y[j] / double(n) - x[j]), 1e-14);
  std::vector<std::complex<double>> odd(12);
  EXPECT_THROW(fft_in_place(odd, FourierSign::negative), std::invalid_argument);
  EXPECT_EQ(next_power_of_two(1000), 1024u);
}

TEST(LockIn, ExactForNonIntegerSamplesPerPeriod) {
  // 37.312 samples per period: no whole number of samples spans whole periods.
  const double dt = 0.1, period = 3.7312;
  const double omega = 2.0 * kPi / period;
  const auto x = sample([&](double t) { return 0.7 * std::cos(omega * t - 1.234) + 0.3; }, 0.05, dt, 500);
  const LockIn li = lock_in({x, 0.05, dt}, omega, {2.0, 40.0});
  EXPECT_EQ(li.periods, 10);  // floor(38 / 3.7312)
  EXPECT_NEAR(li.amplitude, 0.7, 1e-13);
  EXPECT_NEAR(li.phase, 1.234, 1e-13);
  EXPECT_NEAR(li.offset, 0.3, 1e-13);
  EXPECT_LT(li.residual_rms, 1e-14);

  // A plain DFT sum over the same samples is what the least-squares fit avoids: off by ~1/N.
  double in_phase = 0.0, quadrature = 0.0;
  const std::size_t first = 20, count = li.samples;
  for (std::size_t n = first; n < first + count; ++n) {
    const double t = 0.05 + dt * double(n);
    in_phase += x[n] * std::cos(omega * t);
    quadrature += x[n] * std::sin(omega * t);
  }
  EXPECT_GT(std::abs(2.0 * std::hypot(in_phase, quadrature) / double(count) - 0.7), 1e-4);
}

TEST(LockIn, RemovesALinearDrift) {
  const double dt = 0.07, omega = 1.3;
  const auto x = sample([&](double t) { return 0.5 * std::cos(omega * t + 2.5) - 0.02 * t + 1.0; }, 0.0, dt, 2000);
  const LockIn li = lock_in({x, 0.0, dt}, omega, {10.0, 130.0}, Drift::linear);
  EXPECT_NEAR(li.amplitude, 0.5, 1e-12);
  EXPECT_NEAR(li.phase, -2.5, 1e-12);
  EXPECT_NEAR(li.drift, -0.02, 1e-13);
  const LockIn without = lock_in({x, 0.0, dt}, omega, {10.0, 130.0});
  EXPECT_GT(std::abs(without.amplitude - 0.5), 1e-4);  // the drift leaks into the sinusoid
}

TEST(LockIn, ReportedErrorsMatchTheScatter) {
  const double dt = 0.1, omega = 2.0 * kPi / 3.73, noise = 0.05;
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> normal(0.0, noise);
  std::vector<double> amplitude, phase;
  double reported_amplitude = 0.0, reported_phase = 0.0;
  const int trials = 400;
  for (int trial = 0; trial < trials; ++trial) {
    auto x = sample([&](double t) { return std::cos(omega * t - 0.4); }, 0.0, dt, 400);
    for (double& v : x) v += normal(rng);
    const LockIn li = lock_in({x, 0.0, dt}, omega, {0.0, 39.0});
    amplitude.push_back(li.amplitude);
    phase.push_back(li.phase);
    reported_amplitude += li.sigma_amplitude / trials;
    reported_phase += li.sigma_phase / trials;
  }
  auto spread = [](const std::vector<double>& v, double truth) {
    double s = 0.0;
    for (const double x : v) s += (x - truth) * (x - truth);
    return std::sqrt(s / double(v.size()));
  };
  // ~390 samples: sigma_A ~ noise sqrt(2/N) = 3.6e-3. 400 trials pin the spread to ~4%.
  EXPECT_NEAR(spread(amplitude, 1.0) / reported_amplitude, 1.0, 0.12);
  EXPECT_NEAR(spread(phase, 0.4) / reported_phase, 1.0, 0.12);
}

TEST(Propagation, RecoversAlphaAndKExactlyWithoutNoise) {
  const PlaneWave wave{0.05, 0.7, 0.6};  // wavelength 9 d, probes 1 d apart
  const double dt = 0.07;
  std::vector<double> z;
  std::vector<std::vector<double>> records;
  for (int i = 0; i <= 20; ++i) {
    z.push_back(i);
    records.push_back(sample([&](double t) { return wave(z.back(), t); }, 0.0, dt, 3000));
  }
  const auto probes = lock_in_all(records, dt, wave.omega, std::vector<TimeWindow>(z.size(), {20.0, 180.0}));
  const PropagationFit fit = fit_attenuation_and_wavenumber(z, probes, wave.omega);
  EXPECT_NEAR(fit.alpha / wave.alpha, 1.0, 1e-10);
  EXPECT_NEAR(fit.k / wave.k, 1.0, 1e-10);
  EXPECT_NEAR(fit.c / (wave.omega / wave.k), 1.0, 1e-10);
  EXPECT_NEAR(fit.unwrapped_phase.back() - fit.unwrapped_phase.front(), 20.0 * wave.k, 1e-9);  // > 2 pi: unwrapped
}

TEST(Propagation, NoisyRecordsWithinReportedErrors) {
  const PlaneWave wave{0.05, 0.7, 0.6};
  const double dt = 0.07, noise = 1e-3;  // absolute, against A0 = 1 (far probe: 0.37)
  const auto [z, records] = noisy_probe_records(wave, noise, 12345, 20, dt);
  const auto probes = lock_in_all(records, dt, wave.omega, std::vector<TimeWindow>(z.size(), {20.0, 180.0}));
  const PropagationFit fit = fit_attenuation_and_wavenumber(z, probes, wave.omega);
  EXPECT_LT(std::abs(fit.alpha - wave.alpha), 3.0 * fit.sigma_alpha);
  EXPECT_LT(std::abs(fit.k - wave.k), 3.0 * fit.sigma_k);
  EXPECT_LT(std::abs(fit.c - wave.omega / wave.k), 3.0 * fit.sigma_c);
  EXPECT_LT(fit.sigma_alpha, 1e-4);  // errors are informative, not just large
  EXPECT_LT(fit.sigma_k, 1e-4);
  EXPECT_GT(fit.chi2_per_dof_amplitude, 0.3);
  EXPECT_LT(fit.chi2_per_dof_amplitude, 3.0);
}

// A layer the wave never reached records exact zeros: amplitude 0 with lock-in error 0 is not a
// probe above the noise (0 >= 10 x 0), and fitting ln 0 would fail.
TEST(Propagation, ALayerWithoutSignalDoesNotCarryTheWave) {
  std::vector<LockIn> probes(4);
  probes[0].amplitude = 1.0;
  probes[0].sigma_amplitude = 1e-3;
  probes[1].amplitude = 0.5;
  probes[1].sigma_amplitude = 1e-3;
  // probes[2], probes[3]: all zero
  const std::vector<std::size_t> carrying = probes_above_noise(probes);
  EXPECT_EQ(carrying, (std::vector<std::size_t>{0, 1}));
}

TEST(Propagation, ProbesBeyondTheNoiseFloorAreLeftOut) {
  // A strongly attenuated wave (amplitude e^-0.9 per probe) under noise 1e-6. The lock-in error is
  // noise sqrt(2 / samples) = 3e-8 (2286 samples), so the wave falls below 10 errors at
  // z = ln(1 / 3e-7) / 0.9 = 16.7. The amplitude of noise does not decay, so fitting every probe
  // flattens the decay; the probes above the noise give alpha within their errors.
  const PlaneWave wave{0.9, 0.7, 0.6};
  const double dt = 0.07, noise = 1e-6;
  const auto [z, records] = noisy_probe_records(wave, noise, 2026, 30, dt);
  const auto probes = lock_in_all(records, dt, wave.omega, std::vector<TimeWindow>(z.size(), {20.0, 180.0}));
  const std::vector<std::size_t> carrying = probes_above_noise(probes);
  EXPECT_GE(carrying.size(), 15u);
  EXPECT_LE(carrying.size(), 19u);
  for (std::size_t i = 0; i < carrying.size(); ++i) EXPECT_EQ(carrying[i], i);  // the decayed tail goes
  for (const ProbeWeights weights : {ProbeWeights::lock_in_errors, ProbeWeights::uniform}) {
    const PropagationFit fit = fit_attenuation_and_wavenumber(std::span(z).first(carrying.size()),
                                                              std::span(probes).first(carrying.size()), wave.omega,
                                                              0.0, weights);
    EXPECT_LT(std::abs(fit.alpha - wave.alpha), 3.0 * fit.sigma_alpha + 1e-3);
    EXPECT_LT(std::abs(fit.k - wave.k), 3.0 * fit.sigma_k + 1e-3);
  }
  const PropagationFit all = fit_attenuation_and_wavenumber(z, probes, wave.omega, 0.0, ProbeWeights::uniform);
  EXPECT_LT(all.alpha, 0.7 * wave.alpha);
}

TEST(Propagation, WidelySpacedProbesNeedAnExpectedK) {
  const PlaneWave wave{0.02, 0.7, 0.6};
  const double dt = 0.07;
  std::vector<double> z;
  std::vector<std::vector<double>> records;
  for (int i = 0; i <= 6; ++i) {
    z.push_back(5.0 * i);  // k dz = 3.5 > pi: adjacent probes more than half a wavelength apart
    records.push_back(sample([&](double t) { return wave(z.back(), t); }, 0.0, dt, 3000));
  }
  const auto probes = lock_in_all(records, dt, wave.omega, std::vector<TimeWindow>(z.size(), {20.0, 180.0}));
  EXPECT_NEAR(fit_attenuation_and_wavenumber(z, probes, wave.omega).k, wave.k - 2.0 * kPi / 5.0, 1e-9);  // aliased
  EXPECT_NEAR(fit_attenuation_and_wavenumber(z, probes, wave.omega, 0.6).k, wave.k, 1e-9);
}

TEST(Windows, FromFrontEchoAndRunEnd) {
  ChannelTiming timing;
  timing.drive_start = 1.0;
  timing.wave_speed = 2.0;
  timing.channel_length = 50.0;
  timing.period = 1.0;
  const std::vector<double> z{10.0, 49.0};
  const auto windows = measurement_windows(z, timing);
  // Front at 1 + 10/2 = 6, settled at 9; echo at 1 + 90/2 = 46, minus one period: 36 periods.
  ASSERT_TRUE(windows[0].valid()) << windows[0].problem;
  EXPECT_DOUBLE_EQ(windows[0].window.begin, 9.0);
  EXPECT_EQ(windows[0].periods, 36);
  EXPECT_DOUBLE_EQ(windows[0].window.end, 45.0);
  // Near the far end the echo arrives (t = 26.5) before the motion settles (t = 28.5).
  EXPECT_FALSE(windows[1].valid());
  EXPECT_NE(windows[1].problem.find("echo"), std::string::npos) << windows[1].problem;

  timing.speed_uncertainty = 0.1;  // front at 1 + 10/1.8, echo at 1 + 90/2.2
  const auto cautious = measurement_windows(z, timing);
  EXPECT_NEAR(cautious[0].window.begin, 1.0 + 10.0 / 1.8 + 3.0, 1e-12);
  EXPECT_EQ(cautious[0].periods, 31);

  timing.run_end = 20.0;
  const auto short_run = measurement_windows(z, timing);
  EXPECT_EQ(short_run[0].periods, 10);
  timing.run_end = 10.0;
  const auto too_short = measurement_windows(z, timing);
  EXPECT_FALSE(too_short[0].valid());
  EXPECT_NE(too_short[0].problem.find("run ends"), std::string::npos) << too_short[0].problem;
}

TEST(Propagation, WindowKeepsTheEchoOut) {
  // A wave switched on smoothly at the wall plus its reflection (coefficient 0.5) from z = L,
  // both travelling at c = omega / k. The echo is 10% of the incident wave at the far probe.
  const PlaneWave wave{0.01, 0.7, 0.6};
  const double c = wave.omega / wave.k, period = 2.0 * kPi / wave.omega, length = 100.0, dt = 0.07;
  auto u = [&](double z, double t) {
    const double incident = smooth_onset((t - z / c) / (2.0 * period)) * wave(z, t);
    const double echo = 0.5 * smooth_onset((t - (2.0 * length - z) / c) / (2.0 * period)) * wave(2.0 * length - z, t);
    return incident + echo;
  };
  std::vector<double> z;
  std::vector<std::vector<double>> records;
  for (int i = 0; i <= 10; ++i) {
    z.push_back(2.0 * i);
    records.push_back(sample([&](double t) { return u(z.back(), t); }, 0.0, dt, 6000));  // to t = 420
  }
  ChannelTiming timing;
  timing.wave_speed = c;
  timing.channel_length = length;
  timing.period = period;
  std::vector<TimeWindow> windows;
  for (const ProbeWindow& w : measurement_windows(z, timing)) {
    ASSERT_TRUE(w.valid()) << w.problem;
    windows.push_back(w.window);
  }
  const PropagationFit clean = fit_attenuation_and_wavenumber(z, lock_in_all(records, dt, wave.omega, windows), wave.omega);
  EXPECT_NEAR(clean.alpha / wave.alpha, 1.0, 1e-10);
  EXPECT_NEAR(clean.k / wave.k, 1.0, 1e-10);

  // The same fit over windows that run on into the echo is visibly wrong.
  for (TimeWindow& w : windows) w.end = 410.0;
  const PropagationFit polluted =
      fit_attenuation_and_wavenumber(z, lock_in_all(records, dt, wave.omega, windows), wave.omega);
  EXPECT_GT(std::abs(polluted.alpha / wave.alpha - 1.0), 1e-2);
}

/// A Gaussian pulse (peak at t = 5, standard deviation 0.5) reaching probes at z = 0, 1, ..., 10 at
/// `speed`, attenuated as e^{-alpha z}, sampled every dt from t = 0; probe i's record also falls by
/// fall(i) per unit time.
struct PulseRecords {
  std::vector<double> z;
  std::vector<std::vector<double>> records;
  std::vector<SampledSignal> signals;  // views of records
};
PulseRecords pulse_records(double alpha, double speed, double dt, const std::function<double(int)>& fall) {
  auto pulse = [](double s) { return std::exp(-0.5 * (s - 5.0) * (s - 5.0) / 0.25); };
  PulseRecords p;
  for (int i = 0; i <= 10; ++i) {
    const double z = i;
    p.z.push_back(z);
    p.records.push_back(
        sample([&](double t) { return std::exp(-alpha * z) * pulse(t - z / speed) - fall(i) * t; }, 0.0, dt, 2000));
  }
  for (const auto& r : p.records) p.signals.push_back({r, 0.0, dt});
  return p;
}

TEST(FirstPeak, RecoversAlphaAndSpeedOfANonDispersivePulse) {
  const double alpha = 0.03, speed = 1.3;
  const PulseRecords p = pulse_records(alpha, speed, 0.01, [](int) { return 0.0; });
  const FirstPeakFit fit = first_peak_attenuation(p.z, p.signals);
  EXPECT_NEAR(fit.alpha, alpha, 1e-6);
  EXPECT_NEAR(fit.speed / speed, 1.0, 1e-6);
  EXPECT_NEAR(fit.peaks[3].time, 5.0 + 3.0 / speed, 1e-6);
}

TEST(FirstPeak, ARecordWithoutAPeakIsLeftOutNotFatal) {
  // As in a layer holding a rattler, which the wave knocks away by more than its own amplitude: the
  // record falls steadily and never has a maximum above half its largest excursion.
  const double alpha = 0.03, speed = 1.3;
  const PulseRecords p = pulse_records(alpha, speed, 0.01, [](int i) { return i == 4 ? 0.2 : 0.0; });
  const FirstPeakFit fit = first_peak_attenuation(p.z, p.signals);
  EXPECT_EQ(fit.skipped, 1);
  EXPECT_TRUE(std::isnan(fit.peaks[4].time));
  EXPECT_NEAR(fit.alpha, alpha, 1e-6);
  EXPECT_NEAR(fit.speed / speed, 1.0, 1e-6);
  // With fewer than two usable records there is no fit.
  EXPECT_THROW((void)first_peak_attenuation(std::span(p.z).subspan(3, 2), std::span(p.signals).subspan(3, 2)),
               std::invalid_argument);
}

/// A Gaussian-windowed tone (centre `centre`, spectral width 1/width) sent dz through the lattice
/// chain with dashpot gamma_hat, exactly in the frequency domain; the record starts and ends quiet.
std::vector<double> lattice_pulse(double dz, double gamma_hat, double dt, std::size_t n) {
  const double centre = 0.8, width = 1.0 / 0.15, t_centre = 100.0;
  const auto source = sample(
      [&](double t) {
        const double s = (t - t_centre) / width;
        return std::exp(-0.5 * s * s) * std::cos(centre * (t - t_centre));
      },
      0.0, dt, n);
  auto spectrum = real_spectrum(source, n, FourierSign::positive);
  for (std::size_t m = 1; m < n / 2; ++m) {
    const double omega = 2.0 * kPi * double(m) / (double(n) * dt);
    spectrum[m] *= std::exp(std::complex<double>(0.0, 1.0) * lattice_wavenumber(omega, gamma_hat).k * dz);
    spectrum[n - m] = std::conj(spectrum[m]);
  }
  spectrum[n / 2] = 0.0;
  fft_in_place(spectrum, FourierSign::negative);
  std::vector<double> out(n);
  for (std::size_t j = 0; j < n; ++j) out[j] = spectrum[j].real() / double(n);
  return out;
}

TEST(TransferFunction, RecoversTheLatticeDispersionOfAPulse) {
  // A Gaussian-windowed tone (centre 0.8, spectral width 0.15) propagated dz = 20 d through the
  // lattice chain in the frequency domain; the measured alpha_hat and c_hat must be the theory's.
  const double gamma_hat = 0.3, dz = 20.0, dt = 0.25;
  const std::size_t n = 4096;
  const auto ref = lattice_pulse(0.0, gamma_hat, dt, n);
  const auto probe = lattice_pulse(dz, gamma_hat, dt, n);

  TransferOptions options;
  options.speed_guess = 1.0;  // k dz ~ 8 rad at the band's low edge: the branch needs a guess
  const auto points = transfer_function(ref, probe, dt, dz, options);
  ASSERT_GT(points.size(), 50u);
  double low = 1e300, high = 0.0, worst = 0.0;
  const LatticeModel lattice;
  for (const SpectralPoint& p : points) {
    const DispersionPoint theory = lattice.evaluate(p.omega, gamma_hat);
    worst = std::max({worst, std::abs(p.alpha / theory.alpha_hat - 1.0), std::abs(p.c / theory.c_hat - 1.0)});
    low = std::min(low, p.omega);
    high = std::max(high, p.omega);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(low, 0.4);  // the band with signal spans the pulse's spectrum
  EXPECT_GT(high, 1.2);
}

TEST(TransientSpectrum, FitOverProbesRecoversTheLatticeDispersionOffTheFftBins) {
  // Probes every d along the lattice chain; at frequencies that are no FFT bin of the record, the
  // transforms' amplitudes and phases fitted over z give the theory's alpha_hat and c_hat.
  const double gamma_hat = 0.3, dt = 0.25;
  const std::size_t n = 4096;
  std::vector<std::vector<double>> records;
  std::vector<double> z;
  for (int i = 0; i <= 12; ++i) {
    z.push_back(i);
    records.push_back(lattice_pulse(i, gamma_hat, dt, n));
  }
  const LatticeModel lattice;
  for (const double omega : {0.45, 0.6137, 0.8, 1.1}) {
    std::vector<LockIn> probes;
    for (const auto& r : records) probes.push_back(transient_spectrum({r, 0.0, dt}, omega));
    const PropagationFit fit = fit_attenuation_and_wavenumber(z, probes, omega, 0.0, ProbeWeights::uniform);
    const DispersionPoint theory = lattice.evaluate(omega, gamma_hat);
    EXPECT_NEAR(fit.alpha / theory.alpha_hat, 1.0, 1e-6) << "omega " << omega;
    EXPECT_NEAR(fit.c / theory.c_hat, 1.0, 1e-6) << "omega " << omega;
  }
}

TEST(TransientSpectrum, ADelayAddsOmegaTauToThePhase) {
  const double dt = 0.01, omega = 2.3, tau = 1.7;
  auto bump = [](double t) { return std::exp(-0.5 * (t - 8.0) * (t - 8.0)); };  // quiet at both ends
  const auto x = sample(bump, 0.0, dt, 2000);
  const auto late = sample([&](double t) { return 0.5 * bump(t - tau); }, 0.0, dt, 2000);
  const LockIn a = transient_spectrum({x, 0.0, dt}, omega), b = transient_spectrum({late, 0.0, dt}, omega);
  // Continuous transform of the Gaussian bump: sqrt(2 pi) exp(-omega^2 / 2).
  EXPECT_NEAR(a.amplitude, std::sqrt(2.0 * kPi) * std::exp(-0.5 * omega * omega), 1e-10);
  EXPECT_NEAR(b.amplitude / a.amplitude, 0.5, 1e-10);
  EXPECT_NEAR(std::remainder(b.phase - a.phase - omega * tau, 2.0 * kPi), 0.0, 1e-9);
}

TEST(TransientSpectrum, NoiseLevelMatchesWhiteNoise) {
  // |X| of white noise of rms sigma over N samples has rms dt sigma sqrt(N).
  const double dt = 0.1, sigma = 1e-3;
  const std::size_t n = 20000;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  const double level = transient_noise({x, 0.0, dt}, 3.0, 64);
  EXPECT_NEAR(level / (dt * sigma * std::sqrt(double(n))), 1.0, 0.2);
  EXPECT_THROW(static_cast<void>(transient_noise({x, 0.0, dt}, 20.0)), std::invalid_argument);  // above Nyquist/2
}

}  // namespace
}  // namespace sedwave::forward::channel
