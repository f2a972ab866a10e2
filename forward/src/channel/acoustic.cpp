#include "sedwave/forward/channel/acoustic.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <span>
#include <stdexcept>
#include <unordered_map>

#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/channel/packing_units.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/forward/spacing.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {

LayerRange fitted_layers(const DriveSettings& d, std::span<const double> layer_z) {
  const std::size_t layers = layer_z.size();
  LayerRange range;
  range.first = std::min(layers, static_cast<std::size_t>(std::max(0, d.skip_layers)));
  range.end = d.far_end == FarEnd::absorbing
                  ? static_cast<std::size_t>((1.0 - d.absorbing_fraction) * static_cast<double>(layers))
                  : layers;
  if (d.max_fit_depth > 0.0) {
    while (range.end > range.first && layer_z[range.end - 1] > d.max_fit_depth) --range.end;
  }
  range.end = std::max(range.end, range.first);
  return range;
}

double absorbing_length(const DriveSettings& d, const PackingUnits& u) {
  return d.far_end == FarEnd::absorbing ? d.absorbing_fraction * u.column_length() : 0.0;
}

double absorbing_drag(const DriveSettings& d, const PackingUnits& u, double omega, double z) {
  const double length = u.column_top - u.wall_surface;
  const double start = u.wall_surface + (1.0 - d.absorbing_fraction) * length;
  if (z <= start) return 0.0;
  const double c_max = d.absorbing_strength * u.mass * omega;
  const double s = (z - start) / (d.absorbing_fraction * length);
  return c_max * s * s;
}

double loaded_wall_mass(const DriveSettings& d, const PackingUnits& u, std::span<const dem::Grain> grains) {
  if (d.far_wall_mass > 0.0) return d.far_wall_mass * u.mass;
  double mass = 0.0;
  for (const dem::Grain& g : grains) mass += g.body == kUpperWallBody ? g.mass : 0.0;
  return mass;
}

namespace {

/// The first `count` entries of a per-layer vector, as the collectives take them.
template <typename T>
std::span<T> first(std::vector<T>& values, int count) {
  return std::span(values).first(static_cast<std::size_t>(count));
}

/// Fixed layer membership and reference coordinate of each local flow grain, by id. The drive is
/// far too small to move grains between ranks (load balancing is off), so this stays valid.
struct Layers {
  int count = 0;
  std::vector<double> centres;  // [d from the driven wall's surface]
  std::unordered_map<std::int64_t, std::pair<int, double>> member;  // id -> (layer, reference coordinate)
  std::vector<int> grains_per_layer;
  bool every_flow_grain = true;  // false: single-grain probes, most flow grains belong to no layer
};

Layers assign_layers(const dem::Engine& e, const PackingUnits& u, double thickness, int axis) {
  const LayerGrid grid(u, thickness);
  Layers l;
  l.count = grid.count;
  l.centres = grid.centres();
  l.grains_per_layer.assign(static_cast<std::size_t>(l.count), 0);
  const dem::GrainArrays& g = e.grains();
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    if (g.group[i] != kFlowGroup) continue;
    const int layer = grid.index(g.position[i].z);
    l.member[g.id[i]] = {layer, g.position[i][axis]};
    ++l.grains_per_layer[static_cast<std::size_t>(layer)];
  }
  parallel::sum(e.domain().comm(), first(l.grains_per_layer, l.count));
  return l;
}

/// One grain per layer of `layers`: the flow grain nearest the layer's centre (lowest id on a tie),
/// as "layers" of one grain each whose centres are the grains' heights (collective).
Layers single_grain_layers(const dem::Engine& e, const PackingUnits& u, const Layers& layers, int axis,
                           std::vector<std::int64_t>& ids) {
  const auto count = static_cast<std::size_t>(layers.count);
  const dem::GrainArrays& g = e.grains();
  MPI_Comm comm = e.domain().comm();
  // Visits every local flow grain with its layer and its distance from the layer's centre [d].
  auto each_grain = [&](auto visit) {
    for (std::size_t i = 0; i < e.n_local(); ++i) {
      const auto it = layers.member.find(g.id[i]);
      if (it == layers.member.end()) continue;
      const auto k = static_cast<std::size_t>(it->second.first);
      visit(i, k, std::abs((g.position[i].z - u.wall_surface) / u.diameter - layers.centres[k]));
    }
  };
  std::vector<double> nearest(count, std::numeric_limits<double>::infinity());
  each_grain([&](std::size_t, std::size_t k, double distance) { nearest[k] = std::min(nearest[k], distance); });
  parallel::min(comm, first(nearest, layers.count));
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  ids.assign(count, kNone);
  each_grain([&](std::size_t i, std::size_t k, double distance) {
    if (distance == nearest[k]) ids[k] = std::min(ids[k], g.id[i]);
  });
  parallel::min(comm, first(ids, layers.count));

  Layers probes;
  probes.count = layers.count;
  probes.every_flow_grain = false;
  probes.centres.assign(count, 0.0);
  probes.grains_per_layer.assign(count, 0);
  each_grain([&](std::size_t i, std::size_t k, double) {
    if (g.id[i] != ids[k]) return;
    probes.member[g.id[i]] = {static_cast<int>(k), g.position[i][axis]};
    probes.centres[k] = (g.position[i].z - u.wall_surface) / u.diameter;
    probes.grains_per_layer[k] = 1;
  });
  parallel::sum(comm, first(probes.centres, layers.count));
  parallel::sum(comm, first(probes.grains_per_layer, layers.count));
  for (std::size_t k = 0; k < count; ++k) {
    if (ids[k] != kNone) continue;
    ids[k] = -1;
    probes.centres[k] = layers.centres[k];  // an empty layer: its record stays 0
  }
  return probes;
}

/// Mean displacement of each layer along `axis` (collective).
std::vector<double> layer_displacements(const dem::Engine& e, const Layers& l, int axis) {
  std::vector<double> sum(static_cast<std::size_t>(l.count), 0.0);
  const dem::GrainArrays& g = e.grains();
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    if (g.group[i] != kFlowGroup) continue;
    const auto it = l.member.find(g.id[i]);
    if (it == l.member.end()) {
      if (!l.every_flow_grain) continue;
      throw std::runtime_error("acoustic run: a grain changed rank during the drive");
    }
    sum[static_cast<std::size_t>(it->second.first)] += g.position[i][axis] - it->second.second;
  }
  parallel::sum(e.domain().comm(), first(sum, l.count));
  for (int k = 0; k < l.count; ++k) {
    const int n = l.grains_per_layer[static_cast<std::size_t>(k)];
    sum[static_cast<std::size_t>(k)] = n > 0 ? sum[static_cast<std::size_t>(k)] / n : 0.0;
  }
  return sum;
}

/// Graded drag in the absorbing layer (absorbing_drag), integrated exactly over each step
/// (operator splitting): v <- v exp(-c(z) dt / m).
void apply_sponge(dem::Engine& e, const PackingUnits& u, const DriveSettings& d, double omega) {
  dem::GrainArrays& g = e.grains();
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    if (g.body[i] != dem::kFreeBody) continue;
    const double c = absorbing_drag(d, u, omega, g.position[i].z);
    if (c > 0.0) g.velocity[i] *= std::exp(-c * e.time_step() / g.mass[i]);
  }
}

/// The wall's broadband motion, dimensionless (t in sqrt(m/kappa), u in d), scaled to amplitude A.
///
/// Gaussian pulse:  u(t) = A w(t) sin(omega_c (t - t_c)), a Gaussian window w of standard
/// deviation sigma_t = 1 / sigma_omega centred at t_c = 5 sigma_t, lowered by its end value and
/// rescaled, so the wall starts and ends exactly at rest at 0 (w = 0 outside [0, 2 t_c]).
///
/// Log chirp:  u(t) = A w(t) sin(phi(t)), phi(t) = omega_a T / ln r (r^(t/T) - 1), so the
/// instantaneous frequency omega_a r^(t/T) sweeps from omega_a = omega_min / 1.5 to omega_b =
/// 1.5 omega_max (r = omega_b / omega_a) in T = sweep_periods periods of omega_min, spending equal
/// time on every octave. The window w = Phi((t - 6 s) / s) Phi((T - 6 s - t) / s), Phi the normal
/// distribution function, is smooth (a chirp cut with kinks in its window leaks far above the band)
/// and ramps up and down while the sweep is outside the band (s = T ln 1.5 / (9 ln r)); it is
/// 1e-9 at the ends, where u is 0 (start) or below 1e-9 A (stop).
class BroadbandDrive {
 public:
  BroadbandDrive(const PulseBand& b, double amplitude)
      : band_(b), amplitude_(amplitude), shape_(b.shape),
        omega_c_(0.5 * (b.omega_hat_min + b.omega_hat_max)),
        sigma_omega_((b.omega_hat_max - b.omega_hat_min) / (2.0 * kBandEdges)),
        sigma_t_(1.0 / sigma_omega_),
        t_c_(kHalfWidths * sigma_t_),
        sweep_(b.sweep_periods * 2.0 * std::numbers::pi / b.omega_hat_min),
        sweep_start_(b.omega_hat_min / kOvershoot),
        log_ratio_(std::log(kOvershoot * kOvershoot * b.omega_hat_max / b.omega_hat_min)),
        ramp_(sweep_ * std::log(kOvershoot) / (9.0 * log_ratio_)),
        floor_(std::exp(-0.5 * kHalfWidths * kHalfWidths)) {}

  [[nodiscard]] double duration() const { return shape_ == BroadbandShape::gaussian_pulse ? 2.0 * t_c_ : sweep_; }

  /// The headline frequency: the pulse's centre, the chirp's geometric mean.
  [[nodiscard]] double centre() const {
    return shape_ == BroadbandShape::gaussian_pulse ? omega_c_ : std::sqrt(band_.omega_hat_min * band_.omega_hat_max);
  }

  [[nodiscard]] double displacement(double t) const {
    if (t <= 0.0 || t >= duration()) return 0.0;
    if (shape_ == BroadbandShape::gaussian_pulse) return amplitude_ * gaussian(t, t_c_, sigma_t_) * std::sin(omega_c_ * (t - t_c_));
    const double w = normal_cdf((t - kRampSigmas * ramp_) / ramp_) * normal_cdf((sweep_ - kRampSigmas * ramp_ - t) / ramp_);
    const double phase = sweep_start_ * sweep_ / log_ratio_ * std::expm1(log_ratio_ * t / sweep_);
    return amplitude_ * w * std::sin(phase);
  }

  /// Above this frequency the drive's spectrum is below kQuiet of its peak: what the records hold
  /// there is noise (transient_noise). The pulse's is its Gaussian tail, 9 sigma_omega out; the
  /// chirp's is found from its sampled spectrum.
  [[nodiscard]] double quiet_frequency() const {
    if (shape_ == BroadbandShape::gaussian_pulse) return omega_c_ + 9.0 * sigma_omega_;
    const double top = kOvershoot * band_.omega_hat_max;
    const double dt = std::numbers::pi / (16.0 * top);  // resolves up to 16 omega_2
    const auto samples = static_cast<std::size_t>(duration() / dt) + 1;
    auto spectrum = [&](double omega) {
      double re = 0.0, im = 0.0;
      for (std::size_t k = 0; k < samples; ++k) {
        const double t = static_cast<double>(k) * dt, u = displacement(t);
        re += u * std::cos(omega * t);
        im -= u * std::sin(omega * t);
      }
      return std::hypot(re, im);
    };
    double peak = 0.0;
    for (int i = 0; i <= 32; ++i) peak = std::max(peak, spectrum(sweep_start_ * std::exp(log_ratio_ * i / 32.0)));
    double here = spectrum(top);
    for (double omega = top;; omega += 0.05 * top) {
      const double next = spectrum(omega + 0.05 * top);
      if (here < kQuiet * peak && next < kQuiet * peak) return omega;
      here = next;
      if (omega > 8.0 * top) {
        throw std::invalid_argument("acoustic run: the chirp's spectrum stays above 1e-8 of its peak up to 12 "
                                    "omega_hat_max; raise sweep_periods");
      }
    }
  }

 private:
  static constexpr double kHalfWidths = 5.0;   // pulse: half-window in sigmas (end value exp(-12.5))
  static constexpr double kBandEdges = 2.5;    // pulse: the band's edges in spectral standard deviations
  static constexpr double kOvershoot = 1.5;    // chirp: the sweep runs this factor beyond the band
  static constexpr double kRampSigmas = 6.0;   // chirp: window 1e-9 at the ends
  static constexpr double kQuiet = 1e-8;

  static double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

  /// A Gaussian of standard deviation sigma peaking (at 1) at centre, lowered by its value 5 sigma
  /// out and rescaled so it is 0 there.
  [[nodiscard]] double gaussian(double t, double centre, double sigma) const {
    const double s = (t - centre) / sigma;
    return (std::exp(-0.5 * s * s) - floor_) / (1.0 - floor_);
  }

  PulseBand band_;
  double amplitude_;
  BroadbandShape shape_;
  double omega_c_, sigma_omega_, sigma_t_, t_c_;  // pulse
  double sweep_, sweep_start_, log_ratio_, ramp_;  // chirp
  double floor_;
};

/// The lower wall's motion: the sinusoid (LAMMPS wiggle) or the pulse, in scene units.
dem::BodyMotion wall_motion(const DriveSettings& d, const PackingUnits& u, int axis) {
  const double t0 = u.time();
  if (!d.pulse) return dem::Wiggle{axis, d.amplitude * u.diameter, 2.0 * std::numbers::pi * t0 / d.omega_hat};
  const BroadbandDrive pulse(*d.pulse, d.amplitude * u.diameter);
  auto along = [axis](double x) {
    dem::Vec3 v;
    v[axis] = x;
    return v;
  };
  return dem::PrescribedMotion{[=](double t) { return along(pulse.displacement(t / t0)); }};
}

/// The upper wall's motion: frozen, or free along z under the constant force that balances the
/// grains' static force on it (`statics`, required when loaded), so that the drive starts from
/// rest, with loaded_wall_mass.
dem::BodyMotion far_wall_motion(MPI_Comm comm, const PreparedChannel& packing, const std::optional<StaticContacts>& statics,
                                const DriveSettings& d, const PackingUnits& u) {
  if (d.far_wall == FarWall::frozen) return dem::Frozen{};
  const double force = statics.value().upper_wall_force;
  // A given mass, or the wall grains' masses summed over the ranks.
  const double mass = d.far_wall_mass > 0.0 ? loaded_wall_mass(d, u, {})
                                            : parallel::sum(comm, loaded_wall_mass(d, u, packing.grains));
  return dem::ConstantForce{{0.0, 0.0, -force}, mass, {false, false, true}};
}

/// The ascending indices up to the first gap of more than one missing index. Where layers fall
/// below the noise floor (or the unsettled tail) in runs, what lies beyond is a few layers that
/// passed by chance, across gaps too long to unwrap the phase through.
std::vector<std::size_t> leading_run(const std::vector<std::size_t>& indices) {
  std::vector<std::size_t> run;
  for (const std::size_t i : indices) {
    if (!run.empty() && i > run.back() + 2) break;
    run.push_back(i);
  }
  return run;
}

/// Broadband measurement: at each frequency of the band, the Fourier transform of every layer's
/// record (the transfer function from the wall to the layer, up to the drive's spectrum, which is
/// the same for all layers) and the straight-line fits over layers, as for the lock-ins.
void measure_pulse(AcousticResult& r, const DriveSettings& d, const PackingUnits& u,
                   std::span<const SampledSignal> signals, LayerRange range) {
  const BroadbandDrive pulse(*d.pulse, d.amplitude);
  const double omega_quiet = pulse.quiet_frequency();
  // Per layer: the noise level, and the record's last quarter, whose share of X at each frequency
  // is a response still running when the run ends (slow, weakly damped low frequencies; scattering
  // coda) and makes X uncertain by about as much.
  std::vector<double> noise;
  std::vector<SampledSignal> tails;
  for (std::size_t k = range.first; k < range.end; ++k) {
    const SampledSignal& record = signals[k];
    noise.push_back(transient_noise(record, omega_quiet));
    const std::size_t tail_start = record.values.size() - record.values.size() / 4;
    tails.push_back({record.values.subspan(tail_start), record.t_first + record.dt * static_cast<double>(tail_start),
                     record.dt});
  }
  for (const double omega : d.pulse->omega_hats()) {
    SpectralResult point;
    point.omega_hat = omega;
    std::vector<LockIn> probes;
    for (std::size_t k = range.first; k < range.end; ++k) {
      const std::size_t i = k - range.first;
      const double unsettled = transient_spectrum(tails[i], omega).amplitude;
      probes.push_back(transient_spectrum(signals[k], omega, std::hypot(noise[i], unsettled)));
    }
    std::vector<double> z;
    std::vector<LockIn> carrying;
    for (const std::size_t i : leading_run(probes_above_noise(probes))) {
      z.push_back(r.layer_z[range.first + i]);
      carrying.push_back(probes[i]);
    }
    point.layers_used = static_cast<int>(carrying.size());
    if (carrying.size() < 3) {
      point.problem = "only " + std::to_string(carrying.size()) + " of " + std::to_string(probes.size()) +
                      " layers carry this frequency clear of the noise floor and of the records' unsettled "
                      "tails (amplitude >= " + std::to_string(kMinSignalToNoise) +
                      " times both): lengthen the run (drive.periods), narrow the band or raise the amplitude";
    } else {
      point.fit = fit_attenuation_and_wavenumber(z, carrying, omega, omega / r.wave_speed_estimate, ProbeWeights::uniform);
      point.problem = resolution_problem(point.fit, z.back() - z.front(), absorbing_length(d, u));
    }
    r.spectrum.push_back(std::move(point));
  }
  // The headline numbers: the measured frequency nearest the band's centre.
  const SpectralResult* centre = nullptr;
  for (const SpectralResult& p : r.spectrum) {
    if (p.ok() && (centre == nullptr || std::abs(p.omega_hat - pulse.centre()) < std::abs(centre->omega_hat - pulse.centre()))) {
      centre = &p;
    }
  }
  if (centre == nullptr) {
    r.problem = "no frequency of the band could be measured; at omega_hat " + std::to_string(r.spectrum.front().omega_hat) +
                ": " + r.spectrum.front().problem;
    return;
  }
  r.omega_hat = centre->omega_hat;
  r.fit = centre->fit;
  r.layers_used = centre->layers_used;
}

void check_pulse(const DriveSettings& d) {
  const PulseBand& b = *d.pulse;
  if (!(b.omega_hat_min > 0.0) || !(b.omega_hat_max > b.omega_hat_min) || b.frequencies < 1) {
    throw std::invalid_argument("acoustic run: a pulse needs 0 < omega_hat_min < omega_hat_max and frequencies >= 1");
  }
  for (const double w : b.measured) {
    if (!(w >= b.omega_hat_min && w <= b.omega_hat_max)) {
      throw std::invalid_argument("acoustic run: the pulse's measured frequency " + std::to_string(w) +
                                  " lies outside its band [" + std::to_string(b.omega_hat_min) + ", " +
                                  std::to_string(b.omega_hat_max) + "]");
    }
  }
  if (d.far_end != FarEnd::absorbing) {
    throw std::invalid_argument("acoustic run: a pulse needs far_end = absorbing (a frozen end sends the whole pulse "
                                "back through the layers being measured)");
  }
}

double centre_omega_hat(const DriveSettings& d) { return d.pulse ? BroadbandDrive(*d.pulse, 1.0).centre() : d.omega_hat; }

/// The 1D lattice speed at the drive's (centre) frequency: a guess of the packing's (of the same
/// order) that sets the run length and the first windows.
double speed_guess(const DriveSettings& d) { return LatticeModel().evaluate(centre_omega_hat(d), d.gamma_hat).c_hat; }

/// How long to run and how often to sample (dimensionless).
struct RunLength {
  double run_time = 0.0;
  double sample_dt = 0.0;
};

constexpr double kRingDownPeriods = 3.0;

RunLength run_length(const DriveSettings& d, const PackingUnits& u) {
  const double length = u.column_length();
  if (!d.pulse) {
    // Long enough for an echo from the far end to return to the first layers, estimated with the
    // 1D lattice speed at this frequency (the 3D packing's speed is of the same order).
    const double period = 2.0 * std::numbers::pi / d.omega_hat;
    return {d.periods > 0.0 ? d.periods * period : 2.0 * length / speed_guess(d) + (d.settle_periods + 4.0) * period,
            period / d.samples_per_period};
  }
  // The pulse, then its slowest part across the measured layers (3D packings run at 0.6-0.8 of the
  // lattice speed, which is at least 1 for omega_hat <= 2: half of it is a safe floor), then the
  // pulse's length again and a few periods of the band's lowest frequency for the coda that
  // scattering leaves behind. measure_pulse checks what is still running at the end.
  const BroadbandDrive pulse(*d.pulse, d.amplitude);
  const double measured = (1.0 - d.absorbing_fraction) * length;
  const double run_time = d.periods > 0.0 ? d.periods * 2.0 * std::numbers::pi / pulse.centre()
                                          : 2.0 * pulse.duration() + measured / 0.5 +
                                                kRingDownPeriods * 2.0 * std::numbers::pi / d.pulse->omega_hat_min;
  // Samples fine enough for the band's top and for the noise probe above it (transient_noise).
  const double sample_dt = std::min(2.0 * std::numbers::pi / (d.pulse->omega_hat_max * d.samples_per_period),
                                    0.25 * std::numbers::pi / pulse.quiet_frequency());
  return {run_time, sample_dt};
}

}  // namespace

std::vector<double> PulseBand::omega_hats() const {
  if (!measured.empty()) return measured;
  if (frequencies == 1) return {std::sqrt(omega_hat_min * omega_hat_max)};
  return log_spaced(omega_hat_min, omega_hat_max, static_cast<std::size_t>(frequencies));
}

/// The fit again over the first and over the last half of every window (layers with at least 4
/// periods): in a steady state the two agree, while a transient still decaying in the windows (the
/// slow modes of a weakly damped channel) sets them apart. Returns a warning when they differ by
/// more than kUnsteadyAlpha in alpha or kUnsteadySpeed in c and by more than 3 standard errors,
/// else nothing.
static std::string steadiness_warning(const AcousticResult& r, std::span<const SampledSignal> signals,
                                      std::span<const std::size_t> fitted, const ChannelTiming& timing) {
  constexpr double kUnsteadyAlpha = 0.05, kUnsteadySpeed = 0.01;
  std::vector<double> z;
  std::vector<LockIn> early, late;
  for (const std::size_t k : fitted) {
    const ProbeWindow& w = r.windows[k];
    if (w.periods < 4) continue;
    const double half = (w.periods / 2) * timing.period;
    const LockIn first = lock_in(signals[k], r.omega_hat, {w.window.begin, w.window.begin + half}, Drift::linear);
    const LockIn second = lock_in(signals[k], r.omega_hat, {w.window.end - half, w.window.end}, Drift::linear);
    // A half-window can hold no signal where the whole one barely does (a heavily damped wave): no
    // phase to compare there, so that layer sits out of the comparison.
    if (!(first.amplitude > 0.0) || !(second.amplitude > 0.0)) continue;
    z.push_back(r.layer_z[k]);
    early.push_back(first);
    late.push_back(second);
  }
  if (z.size() < 3) return {};
  const PropagationFit a = fit_attenuation_and_wavenumber(z, early, r.omega_hat, r.fit.k, ProbeWeights::uniform);
  const PropagationFit b = fit_attenuation_and_wavenumber(z, late, r.omega_hat, r.fit.k, ProbeWeights::uniform);
  // Apart by more than the tolerance and by more than 3 standard errors of the difference (the
  // halves' fit errors, which also hold the packing's disorder, common to both: a cautious test).
  auto apart = [](double x, double y, double sx, double sy, double tolerance) {
    return std::abs(x - y) > tolerance && std::abs(x - y) > 3.0 * std::hypot(sx, sy);
  };
  if (!apart(a.alpha, b.alpha, a.sigma_alpha, b.sigma_alpha, kUnsteadyAlpha * std::abs(r.fit.alpha)) &&
      !apart(a.c, b.c, a.sigma_c, b.sigma_c, kUnsteadySpeed * r.fit.c)) {
    return {};
  }
  char text[256];
  std::snprintf(text, sizeof text,
                "not steady: the first and last halves of the lock-in windows give alpha_hat %.4g and %.4g, c_hat "
                "%.4g and %.4g (a transient still decays: raise settle_periods, or use the linear engine)",
                a.alpha, b.alpha, a.c, b.c);
  return text;
}

/// Lock-in windows for `timing`, the lock-ins and the fit over the layers of `range` that carry the
/// wave (r.windows, lock_ins, fit, layers_used, problem). Returns the fitted layers' indices, or
/// nothing when too few layers are left to fit.
static std::optional<std::vector<std::size_t>> lock_in_and_fit(AcousticResult& r, const DriveSettings& d,
                                                               const PackingUnits& u,
                                                               std::span<const SampledSignal> signals,
                                                               const LayerRange& range, const ChannelTiming& timing) {
  const double omega = r.omega_hat;
  r.windows = measurement_windows(r.layer_z, timing);
  r.lock_ins.assign(r.layer_z.size(), LockIn{});
  std::vector<std::size_t> steady;
  std::vector<LockIn> used;
  for (std::size_t k = range.first; k < range.end; ++k) {
    if (!r.windows[k].valid()) continue;
    r.lock_ins[k] = lock_in(signals[k], omega, r.windows[k].window, Drift::linear);
    steady.push_back(k);
    used.push_back(r.lock_ins[k]);
  }
  if (used.size() < 3) {
    r.layers_used = static_cast<int>(used.size());
    r.problem = "fewer than 3 layers have a steady window before any reflection returns (" +
                std::to_string(used.size()) + "): lengthen the channel, raise the frequency or absorb the far end";
    return std::nullopt;
  }
  // A strongly attenuated wave reaches the noise floor inside the channel; the layers beyond would
  // flatten the fitted decay.
  std::vector<std::size_t> fitted;
  std::vector<LockIn> carrying;
  std::vector<double> z;
  for (const std::size_t i : probes_above_noise(used)) {
    fitted.push_back(steady[i]);
    carrying.push_back(used[i]);
    z.push_back(r.layer_z[steady[i]]);
  }
  r.layers_used = static_cast<int>(carrying.size());
  r.layers_below_noise = static_cast<int>(used.size() - carrying.size());
  if (carrying.size() < 3) {
    r.problem = "only " + std::to_string(carrying.size()) + " of " + std::to_string(steady.size()) +
                " layers carry the wave above the noise floor (amplitude >= " + std::to_string(kMinSignalToNoise) +
                " lock-in errors): raise the drive amplitude or lower the frequency";
    return std::nullopt;
  }
  r.fit = fit_attenuation_and_wavenumber(z, carrying, omega, omega / timing.wave_speed, ProbeWeights::uniform);
  r.problem = resolution_problem(r.fit, z.back() - z.front(), absorbing_length(d, u));
  return fitted;
}

/// measure_layer_records, with the first peaks sought in the first `front_samples` samples only:
/// a run continued because it was not steady keeps the front its first run saw (a first peak is
/// one above a fraction of the record's largest value, which a longer record can move).
static void measure_records(AcousticResult& r, const DriveSettings& d, const PackingUnits& u,
                            std::size_t front_samples) {
  if (r.displacement.empty() || r.displacement.size() != r.layer_z.size() || !(r.sample_dt > 0.0)) {
    throw std::invalid_argument("measure_layer_records: need one record per layer and sample_dt > 0");
  }
  // Forget what an earlier measurement of these records concluded (a continued run measures again).
  r.problem.clear();
  r.warning.clear();
  r.layers_below_noise = 0;
  const double run_time = static_cast<double>(r.displacement.front().size() - 1) * r.sample_dt;
  const double c_guess = speed_guess(d);
  const double omega = r.omega_hat;  // dimensionless from here on: z in d, t in sqrt(m/kappa)
  std::vector<SampledSignal> signals, fronts;
  for (const auto& record : r.displacement) {
    signals.push_back({record, 0.0, r.sample_dt});
    fronts.push_back({std::span<const double>(record).first(std::min(front_samples, record.size())), 0.0, r.sample_dt});
  }
  const LayerRange range = fitted_layers(d, r.layer_z);
  const std::size_t first = range.first, last_driven = range.end;
  if (last_driven <= first + 2) {
    r.problem = "channel too short: fewer than 3 layers between the near field and the far end";
    return;
  }
  const std::span<const double> z(r.layer_z.data() + first, last_driven - first);
  const std::span<const SampledSignal> s(signals.data() + first, last_driven - first);
  r.wave_speed_estimate = c_guess;
  try {
    r.first_peak = first_peak_attenuation(z, std::span<const SampledSignal>(fronts.data() + first, last_driven - first));
    if (r.first_peak.speed > 0.0 && std::isfinite(r.first_peak.speed)) r.wave_speed_estimate = r.first_peak.speed;
  } catch (const std::exception&) {
    // No clear first peak (strong damping smears the front): keep the theory's estimate.
  }
  if (d.pulse) {
    measure_pulse(r, d, u, signals, range);
    return;
  }
  ChannelTiming timing;
  timing.wave_speed = r.wave_speed_estimate;
  timing.speed_uncertainty = 0.2;
  timing.channel_length = d.far_end == FarEnd::frozen ? u.column_length() : 1e300;
  timing.period = 2.0 * std::numbers::pi / omega;
  timing.settle_periods = d.settle_periods;
  timing.run_end = run_time;
  // The windows open once the wave, at the estimated speed less 20 %, has passed a layer. A fitted
  // phase speed below that means the deep layers' windows opened before the wave had settled there
  // (at low omega_hat a 3D packing runs at 0.6 of the 1D lattice's speed, the estimate when no first
  // peaks could be fitted): the windows are then set again from the fitted speed, once.
  std::optional<std::vector<std::size_t>> fitted;
  for (int attempt = 0; attempt < 2; ++attempt) {
    fitted = lock_in_and_fit(r, d, u, signals, range, timing);
    if (!fitted) return;
    if (!(r.fit.c < timing.wave_speed * (1.0 - timing.speed_uncertainty))) break;
    timing.wave_speed = r.wave_speed_estimate = r.fit.c;
  }
  r.warning = steadiness_warning(r, signals, *fitted, timing);
}

void measure_layer_records(AcousticResult& r, const DriveSettings& d, const PackingUnits& u) {
  measure_records(r, d, u, std::numeric_limits<std::size_t>::max());
}

/// The same measurement over the single-grain records.
static void measure_single_grains(AcousticResult& r, const DriveSettings& d, const PackingUnits& u,
                                  std::size_t front_samples) {
  SingleGrainProbes& p = *r.single_grains;
  AcousticResult grains;
  grains.omega_hat = r.omega_hat;
  grains.gamma_hat = r.gamma_hat;
  grains.amplitude = r.amplitude;
  grains.layer_z = p.z;
  grains.sample_dt = r.sample_dt;
  grains.displacement = p.displacement;
  measure_records(grains, d, u, front_samples);
  p.fit = grains.fit;
  p.spectrum = std::move(grains.spectrum);
  p.probes_used = grains.layers_used;
  p.problem = grains.problem;
}

/// Runs `steps` steps; when a log is given, times the first ones and, if the whole run will take
/// longer than kAnnouncedRunSeconds, says so with the numbers before the rest: a long run is never
/// silent (a stiff pore fluid or a low frequency can ask for millions of steps).
void run_announced(dem::Engine& engine, std::int64_t steps, const DriveSettings& d, MPI_Comm comm) {
  const std::int64_t probe = std::min<std::int64_t>(steps, std::max<std::int64_t>(200, steps / 200));
  const auto started = std::chrono::steady_clock::now();
  engine.run(probe);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  parallel::max(comm, std::span<double, 1>(&seconds, 1));  // the slowest rank sets the pace
  const double expected = seconds * static_cast<double>(steps) / static_cast<double>(std::max<std::int64_t>(probe, 1));
  if (d.log && parallel::rank(comm) == 0 && expected > kAnnouncedRunSeconds) {
    char took[32];
    std::snprintf(took, sizeof took, "%.3g", seconds);
    *d.log << "drive: " << steps << " steps of " << engine.n_global() << " grains; the first " << probe << " took "
           << took << " s, so about " << static_cast<long long>(std::ceil(expected)) << " s in all"
           << (d.steady_extensions > 0 ? " (up to " + std::to_string(d.steady_extensions + 1) +
                                             " times that if its windows are not steady)"
                                       : std::string())
           << std::endl;
  }
  engine.run(steps - probe);
}

AcousticResult run_acoustic(MPI_Comm comm, const PreparedChannel& packing, dem::ContactSpec contact,
                            const DriveSettings& d) {
  const auto started = std::chrono::steady_clock::now();
  if (!(d.omega_hat > 0.0) || !(d.gamma_hat >= 0.0) || !(d.amplitude > 0.0)) {
    throw std::invalid_argument("acoustic run: omega_hat and amplitude must be positive, gamma_hat non-negative");
  }
  if (d.pulse) check_pulse(d);
  // The static contacts, found once where the units (Hertz) or a loaded far wall need them: spread
  // over ranks, that is a DEM force evaluation. Static, so the dashpot set below does not enter.
  std::optional<StaticContacts> statics;
  if (units_need_static_contacts(contact) || d.far_wall != FarWall::frozen)
    statics = static_contacts(comm, packing, contact);
  const PackingUnits u = packing_units(comm, packing, contact, statics ? &*statics : nullptr);
  const double t0 = u.time();
  const double omega = centre_omega_hat(d) / t0;  // sets the absorbing layer's drag
  contact = dem::without_dashpot(contact);
  contact[std::string(dem::keys::gamma.key)] = d.gamma_hat * u.damping_scale;  // Hooke: gamma; Hertz: the Tsuji alpha

  const int axis = d.axis == DriveAxis::longitudinal ? 2 : 0;
  dem::EngineSettings settings;
  settings.box = broadcast_box(comm, packing.box);
  settings.contact = contact;
  settings.time_step_fraction = d.time_step_fraction;
  settings.balance.every_rebuilds = 0;
  if (d.fluid) settings.fluid = fluid_in_packing_units(*d.fluid, u);
  std::vector<dem::RigidBody> bodies{dem::RigidBody("lower_wall", wall_motion(d, u, axis)),
                                     dem::RigidBody("upper_wall", far_wall_motion(comm, packing, statics, d, u))};
  dem::Engine engine(comm, settings, packing.grains, std::move(bodies));

  AcousticResult r;
  r.omega_hat = centre_omega_hat(d);
  r.gamma_hat = d.gamma_hat;
  r.amplitude = d.amplitude;
  r.kappa = u.kappa;
  r.grain_mass = u.mass;
  r.mean_diameter = u.diameter;
  const Layers layers = assign_layers(engine, u, d.layer_thickness, axis);
  r.layer_z = layers.centres;
  r.layer_grains = layers.grains_per_layer;
  r.displacement.assign(static_cast<std::size_t>(layers.count), {});

  const double dt = engine.time_step() / t0;
  const RunLength length = run_length(d, u);
  const auto steps_per_sample =
      static_cast<std::int64_t>(std::max(1.0, std::floor(length.sample_dt / dt)));
  const double run_time = length.run_time;
  r.sample_dt = static_cast<double>(steps_per_sample) * dt;
  r.time_step = dt;
  const auto total_steps = static_cast<std::int64_t>(std::ceil(run_time / dt));

  std::optional<Layers> probes;
  if (d.grain_probes) {
    r.single_grains.emplace();
    probes = single_grain_layers(engine, u, layers, axis, r.single_grains->id);
    r.single_grains->z = probes->centres;
    r.single_grains->displacement.assign(static_cast<std::size_t>(layers.count), {});
  }
  auto record = [&](const dem::Engine& e) {
    const std::vector<double> u_layer = layer_displacements(e, layers, axis);
    for (std::size_t k = 0; k < u_layer.size(); ++k) r.displacement[k].push_back(u_layer[k] / u.diameter);
    if (!probes) return;
    const std::vector<double> u_grain = layer_displacements(e, *probes, axis);
    for (std::size_t k = 0; k < u_grain.size(); ++k) r.single_grains->displacement[k].push_back(u_grain[k] / u.diameter);
  };
  record(engine);  // sample 0 at t = 0
  engine.add_step_callback(steps_per_sample, record);
  if (d.far_end == FarEnd::absorbing) {
    engine.add_step_callback(1, [&](const dem::Engine&) { apply_sponge(engine, u, d, omega); });
  }
  run_announced(engine, total_steps, d, comm);
  r.steps = total_steps;
  measure_layer_records(r, d, u);
  // A weakly damped channel can ring for longer than the run, and in a strongly damped one the
  // switch-on transient buries the deep layers' small steady signal: continue the run, and wait as
  // much longer before every window opens, so the windows keep their length and see later motion.
  const bool extendable = !d.pulse && d.far_end == FarEnd::absorbing && !(d.periods > 0.0);
  auto unsettled = [&r] { return r.problem.empty() ? !r.warning.empty() : r.layers_below_noise > 0; };
  DriveSettings later = d;
  const std::size_t first_run_samples = r.displacement.front().size();
  while (extendable && unsettled() && r.extensions < d.steady_extensions) {
    engine.run(total_steps);
    r.steps += total_steps;
    ++r.extensions;
    later.settle_periods += static_cast<double>(total_steps) * dt * d.omega_hat / (2.0 * std::numbers::pi);
    measure_records(r, later, u, first_run_samples);
  }
  if (r.single_grains) measure_single_grains(r, later, u, first_run_samples);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace sedwave::forward::channel
