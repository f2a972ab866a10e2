#include "sedwave/forward/channel/acoustic.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "sedwave/forward/channel/packing_units.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {
namespace {

/// Fixed layer membership and reference coordinate of each local flow grain, by id. The drive is
/// far too small to move grains between ranks (load balancing is off), so this stays valid.
struct Layers {
  int count = 0;
  std::vector<double> centres;  // [d from the driven wall's surface]
  std::unordered_map<std::int64_t, std::pair<int, double>> member;  // id -> (layer, reference coordinate)
  std::vector<int> grains_per_layer;
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
  MPI_Allreduce(MPI_IN_PLACE, l.grains_per_layer.data(), l.count, MPI_INT, MPI_SUM, e.domain().comm());
  return l;
}

/// Mean displacement of each layer along `axis` (collective).
std::vector<double> layer_displacements(const dem::Engine& e, const Layers& l, int axis) {
  std::vector<double> sum(static_cast<std::size_t>(l.count), 0.0);
  const dem::GrainArrays& g = e.grains();
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    if (g.group[i] != kFlowGroup) continue;
    const auto it = l.member.find(g.id[i]);
    if (it == l.member.end()) throw std::runtime_error("acoustic run: a grain changed rank during the drive");
    sum[static_cast<std::size_t>(it->second.first)] += g.position[i][axis] - it->second.second;
  }
  MPI_Allreduce(MPI_IN_PLACE, sum.data(), l.count, MPI_DOUBLE, MPI_SUM, e.domain().comm());
  for (int k = 0; k < l.count; ++k) {
    const int n = l.grains_per_layer[static_cast<std::size_t>(k)];
    sum[static_cast<std::size_t>(k)] = n > 0 ? sum[static_cast<std::size_t>(k)] / n : 0.0;
  }
  return sum;
}

/// Graded drag in the absorbing layer, integrated exactly over each step (operator splitting):
/// v <- v exp(-c(z) dt / m), with c growing quadratically from 0 at the layer's start.
void apply_sponge(dem::Engine& e, const PackingUnits& u, const DriveSettings& d, double omega) {
  const double length = u.column_top - u.wall_surface;
  const double start = u.wall_surface + (1.0 - d.absorbing_fraction) * length;
  const double c_max = d.absorbing_strength * u.mass * omega;
  dem::GrainArrays& g = e.grains();
  for (std::size_t i = 0; i < e.n_local(); ++i) {
    if (g.body[i] != dem::kFreeBody || g.position[i].z <= start) continue;
    const double s = (g.position[i].z - start) / (d.absorbing_fraction * length);
    g.velocity[i] *= std::exp(-c_max * s * s * e.time_step() / g.mass[i]);
  }
}

/// The 1D lattice speed at the drive frequency: a guess of the packing's (of the same order) that
/// sets the run length and the first windows.
double speed_guess(const DriveSettings& d) { return LatticeModel().evaluate(d.omega_hat, d.gamma_hat).c_hat; }

}  // namespace

void measure_layer_records(AcousticResult& r, const DriveSettings& d, const PackingUnits& u) {
  if (r.displacement.empty() || r.displacement.size() != r.layer_z.size() || !(r.sample_dt > 0.0)) {
    throw std::invalid_argument("measure_layer_records: need one record per layer and sample_dt > 0");
  }
  const double run_time = static_cast<double>(r.displacement.front().size() - 1) * r.sample_dt;
  const double c_guess = speed_guess(d);
  const double omega = r.omega_hat;  // dimensionless from here on: z in d, t in sqrt(m/kappa)
  std::vector<SampledSignal> signals;
  for (const auto& record : r.displacement) signals.push_back({record, 0.0, r.sample_dt});
  const std::size_t first = static_cast<std::size_t>(std::max(0, d.skip_layers));
  const std::size_t last_driven = d.far_end == FarEnd::absorbing
                                      ? static_cast<std::size_t>((1.0 - d.absorbing_fraction) * static_cast<double>(r.layer_z.size()))
                                      : r.layer_z.size();
  if (last_driven <= first + 2) {
    r.problem = "channel too short: fewer than 3 layers between the near field and the far end";
    return;
  }
  const std::span<const double> z(r.layer_z.data() + first, last_driven - first);
  const std::span<const SampledSignal> s(signals.data() + first, last_driven - first);
  r.wave_speed_estimate = c_guess;
  try {
    r.first_peak = first_peak_attenuation(z, s);
    if (r.first_peak.speed > 0.0 && std::isfinite(r.first_peak.speed)) r.wave_speed_estimate = r.first_peak.speed;
  } catch (const std::exception&) {
    // No clear first peak (strong damping smears the front): keep the theory's estimate.
  }
  ChannelTiming timing;
  timing.wave_speed = r.wave_speed_estimate;
  timing.speed_uncertainty = 0.2;
  timing.channel_length = d.far_end == FarEnd::frozen ? (u.column_top - u.wall_surface) / u.diameter : 1e300;
  timing.period = 2.0 * std::numbers::pi / omega;
  timing.settle_periods = d.settle_periods;
  timing.run_end = run_time;
  r.windows = measurement_windows(r.layer_z, timing);
  r.lock_ins.assign(r.layer_z.size(), LockIn{});
  std::vector<double> z_used;
  std::vector<LockIn> used;
  for (std::size_t k = first; k < last_driven; ++k) {
    if (!r.windows[k].valid()) continue;
    r.lock_ins[k] = lock_in(signals[k], omega, r.windows[k].window, Drift::linear);
    z_used.push_back(r.layer_z[k]);
    used.push_back(r.lock_ins[k]);
  }
  if (used.size() < 3) {
    r.layers_used = static_cast<int>(used.size());
    r.problem = "fewer than 3 layers have a steady window before any reflection returns (" +
                std::to_string(used.size()) + "): lengthen the channel, raise the frequency or absorb the far end";
    return;
  }
  // A strongly attenuated wave reaches the noise floor inside the channel; the layers beyond would
  // flatten the fitted decay.
  const std::size_t steady = used.size();
  std::vector<LockIn> carrying;
  std::vector<double> z_carrying;
  for (const std::size_t i : probes_above_noise(used)) {
    carrying.push_back(used[i]);
    z_carrying.push_back(z_used[i]);
  }
  used = std::move(carrying);
  z_used = std::move(z_carrying);
  r.layers_used = static_cast<int>(used.size());
  if (used.size() < 3) {
    r.problem = "only " + std::to_string(used.size()) + " of " + std::to_string(steady) +
                " layers carry the wave above the noise floor (amplitude >= " + std::to_string(kMinSignalToNoise) +
                " lock-in errors): raise the drive amplitude or lower the frequency";
    return;
  }
  r.fit = fit_attenuation_and_wavenumber(z_used, used, omega, omega / r.wave_speed_estimate, ProbeWeights::uniform);
  r.problem = resolution_problem(r.fit, z_used.back() - z_used.front(),
                                 d.far_end == FarEnd::absorbing ? d.absorbing_fraction * u.column_length() : 0.0);
}

AcousticResult run_acoustic(MPI_Comm comm, const PreparedChannel& packing, dem::ContactSpec contact,
                            const DriveSettings& d) {
  const auto started = std::chrono::steady_clock::now();
  if (!(d.omega_hat > 0.0) || !(d.gamma_hat >= 0.0) || !(d.amplitude > 0.0)) {
    throw std::invalid_argument("acoustic run: omega_hat and amplitude must be positive, gamma_hat non-negative");
  }
  const PackingUnits u = packing_units(comm, packing, contact);
  const double t0 = u.time();
  const double omega = d.omega_hat / t0;
  contact.restitution.reset();
  contact.lammps_gamma_n.reset();
  contact.gamma = d.gamma_hat * u.damping_scale;  // Hooke: gamma; Hertz: the Tsuji alpha

  const int axis = d.axis == DriveAxis::longitudinal ? 2 : 0;
  dem::EngineSettings settings;
  settings.box = broadcast_box(comm, packing.box);
  settings.contact = contact;
  settings.time_step_fraction = d.time_step_fraction;
  settings.balance.every_rebuilds = 0;
  std::vector<dem::RigidBody> bodies{
      dem::RigidBody("lower_wall", dem::Wiggle{axis, d.amplitude * u.diameter, 2.0 * std::numbers::pi / omega}),
      dem::RigidBody("upper_wall", dem::Frozen{})};
  dem::Engine engine(comm, settings, packing.grains, std::move(bodies));

  AcousticResult r;
  r.omega_hat = d.omega_hat;
  r.gamma_hat = d.gamma_hat;
  r.amplitude = d.amplitude;
  r.kappa = u.kappa;
  r.grain_mass = u.mass;
  r.mean_diameter = u.diameter;
  const Layers layers = assign_layers(engine, u, d.layer_thickness, axis);
  r.layer_z = layers.centres;
  r.layer_grains = layers.grains_per_layer;
  r.displacement.assign(static_cast<std::size_t>(layers.count), {});

  // Run length: long enough for an echo from the far end to return to the first layers, estimated
  // with the 1D lattice speed at this frequency (the 3D packing's speed is of the same order).
  const double c_guess = speed_guess(d);
  const double length = (u.column_top - u.wall_surface) / u.diameter;
  const double period = 2.0 * std::numbers::pi / d.omega_hat;
  const double run_time = d.periods > 0.0 ? d.periods * period : 2.0 * length / c_guess + (d.settle_periods + 4.0) * period;
  const double dt = engine.time_step() / t0;
  const auto steps_per_sample =
      static_cast<std::int64_t>(std::max(1.0, std::floor(period / (d.samples_per_period * dt))));
  r.sample_dt = static_cast<double>(steps_per_sample) * dt;
  r.time_step = dt;
  const auto total_steps = static_cast<std::int64_t>(std::ceil(run_time / dt));

  auto record = [&](const dem::Engine& e) {
    const std::vector<double> u_layer = layer_displacements(e, layers, axis);
    for (std::size_t k = 0; k < u_layer.size(); ++k) r.displacement[k].push_back(u_layer[k] / u.diameter);
  };
  record(engine);  // sample 0 at t = 0
  engine.add_step_callback(steps_per_sample, record);
  if (d.far_end == FarEnd::absorbing) {
    engine.add_step_callback(1, [&](const dem::Engine&) { apply_sponge(engine, u, d, omega); });
  }
  engine.run(total_steps);
  r.steps = total_steps;
  measure_layer_records(r, d, u);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace sedwave::forward::channel
