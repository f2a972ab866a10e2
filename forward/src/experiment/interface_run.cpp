#include "sedwave/forward/experiment/interface_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "sedwave/io/hdf5.hpp"
#include "sedwave/forward/dem/critical_step.hpp"
#include "sedwave/forward/experiment/interface_spectrum.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::experiment {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// The driven grains: the free row (the highest grains, within half a radius), the `width` nearest
/// the plate's centre (all when width is 0).
std::vector<int> driven_grains(const std::vector<interface::Grain>& grains, int width, double centre) {
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& g : grains) top = std::max(top, g.y);
  std::vector<int> row;
  for (std::size_t i = 0; i < grains.size(); ++i)
    if (grains[i].y > top - 0.5 * grains[i].radius) row.push_back(static_cast<int>(i));
  std::stable_sort(row.begin(), row.end(), [&](int a, int b) {
    return std::abs(grains[static_cast<std::size_t>(a)].x - centre) < std::abs(grains[static_cast<std::size_t>(b)].x - centre);
  });
  if (width > 0 && static_cast<std::size_t>(width) < row.size()) row.resize(static_cast<std::size_t>(width));
  std::sort(row.begin(), row.end());
  return row;
}

int nearest_node(const plate::ElasticPlate& p, double x, double depth) {
  const int i = std::clamp(static_cast<int>(std::lround(x / p.element_width())), 0, p.nodes_x() - 1);
  const int j = std::clamp(static_cast<int>(std::lround((p.mesh().length_y - depth) / p.element_height())), 0, p.nodes_y() - 1);
  return p.node(i, j);
}

/// First time |v| reaches `fraction` of its maximum, interpolated between samples.
double arrival_time(const std::vector<double>& t, const std::vector<double>& v, double fraction) {
  const double peak = *std::max_element(v.begin(), v.end());
  if (!(peak > 0.0)) return nan;
  const double level = fraction * peak;
  for (std::size_t k = 1; k < v.size(); ++k)
    if (v[k] >= level) return t[k - 1] + (t[k] - t[k - 1]) * (level - v[k - 1]) / (v[k] - v[k - 1]);
  return nan;
}

/// The front of a pulse as short as the mesh allows (the direct strike's: one row of nodes set moving).
/// The lattice's dispersion smooths an impulse into an Airy pulse about the continuum's front, whose
/// leading edge reaches Ai(0) / max Ai = 0.66279 of its first maximum there (a fraction of the largest
/// speed sits in the precursor ahead of it, ever earlier as the mesh coarsens); the first maximum is
/// the first local maximum at or above half the largest speed. Interpolated between samples, which
/// must be much closer than the pulse's rise.
double front_time(const std::vector<double>& t, const std::vector<double>& v) {
  constexpr double airy_front = 0.355028053887817 / 0.535656656015700;  // Ai(0) / Ai(-1.01879)
  const double peak = *std::max_element(v.begin(), v.end());
  if (!(peak > 0.0)) return nan;
  std::size_t first = 0;
  while (first + 1 < v.size() && !(v[first] >= 0.5 * peak && v[first] >= v[first + 1])) ++first;
  if (v.front() >= airy_front * v[first]) return t.front();  // a probe on the struck nodes: moving from the start
  return arrival_time(std::vector<double>(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(first) + 1),
                      std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(first) + 1), airy_front);
}

/// The consistent nodal forces of a uniform load `q` per unit length along y on the top edge over
/// [x0, x1]: q times the integral of each node's linear shape function over the loaded part of its
/// segments (an interior node of a fully loaded span gets q a, an end node q a / 2).
std::vector<double> edge_line_load(const plate::ElasticPlate& p, double x0, double x1, double q) {
  std::vector<double> f(static_cast<std::size_t>(p.dof_count()), 0.0);
  const double a = p.element_width();
  const int j = p.nodes_y() - 1;
  for (int i = 0; i + 1 < p.nodes_x(); ++i) {
    // The loaded part of segment i in its coordinate xi = (x - x_i)/a, in [0, 1].
    const double s = std::clamp((x0 - i * a) / a, 0.0, 1.0), e = std::clamp((x1 - i * a) / a, 0.0, 1.0);
    if (!(e > s)) continue;
    const double right = 0.5 * (e * e - s * s);  // integral of xi
    f[static_cast<std::size_t>(2 * p.node(i, j) + 1)] += q * a * ((e - s) - right);
    f[static_cast<std::size_t>(2 * p.node(i + 1, j) + 1)] += q * a * right;
  }
  return f;
}

/// One Hertz contact at the run's peak: the overlap its strike (kinetic energy of approach at
/// `speed`) or a static `force` reaches, whichever is larger, and its limits.
struct PeakContact {
  double overlap = 0.0;
  double hertz_limit = std::numeric_limits<double>::infinity();
  double friction_limit = std::numeric_limits<double>::infinity();
};

/// `modulus` E*, `radius` R*, `inverse_mass` 1/m*, `inverse_tangential_mass` 1/m_t, and the
/// stiffness the contact adds to (the mesh's omega_max^2 for a bead on the plate, else 0). The limits
/// are GranularPlate's: a grain pair's those of the packing's collective modes, a bead on the plate's
/// or a wall's its own (dem/critical_step.hpp).
PeakContact peak_contact(double modulus, double radius, double inverse_mass, double inverse_tangential_mass,
                         double omega_squared, double speed, double force, const interface::InterfaceContacts& c,
                         bool grain_pair) {
  PeakContact p;
  const double k = (4.0 / 3.0) * modulus * std::sqrt(radius);
  // (2/5) k delta^(5/2) = m* v^2 / 2 for a strike; F = k delta^(3/2) for a static force.
  const double struck = std::pow(1.25 * speed * speed / (inverse_mass * k), 0.4);
  const double loaded = std::pow(force / k, 2.0 / 3.0);
  p.overlap = std::max(struck, loaded);
  if (!(p.overlap > 0.0)) return p;
  const double contact_omega2 = 1.5 * k * std::sqrt(p.overlap) * inverse_mass;
  const double normal_force = k * p.overlap * std::sqrt(p.overlap);
  const double beta =
      c.friction > 0.0 ? c.friction * c.tanh_velocity_scale * normal_force * inverse_tangential_mass : 0.0;
  if (grain_pair) {
    p.hertz_limit = dem::hexagonal_packing_critical_step(contact_omega2, 0.0, 0.0, c.rotation);
    if (beta > 0.0) p.friction_limit = dem::hexagonal_packing_critical_step(contact_omega2, 0.0, beta, c.rotation);
    return p;
  }
  p.hertz_limit = dem::predicted_velocity_critical_step(std::sqrt(omega_squared + contact_omega2), 0.0);
  if (beta > 0.0) p.friction_limit = dem::predicted_velocity_critical_step(std::sqrt(omega_squared), beta);
  return p;
}

// Bytes the run holds per plate node (displacement, velocity, two force arrays, mass, damping and the
// velocity the friction sees, 2 doubles each; the constraints; the node positions; a temporary for
// the strain energy), per node and snapshot, per grain (three copies of its state, its forces by
// kind, the neighbour list and cells), and per sample (the series, the probes, the line's two
// velocity components and their flattened copies for the file).
constexpr double kBytesPerNode = 7 * 16 + 2 + 16 + 16;
constexpr double kBytesPerSnapshotNode = 16;
constexpr double kBytesPerGrain = 3 * 64 + 4 * 24 + 24 + 16 + 72;
constexpr double kBytesPerSample = 7 * 8 + 72 + 32 + 48;
constexpr double kBytesPerSampleProbe = 8;
constexpr double kBytesPerSampleLineNode = 32;

}  // namespace

InterfaceEstimate estimate_interface_run(const InterfaceScene& scene) {
  InterfaceEstimate e;
  const auto& mesh = scene.mesh;
  const auto& pm = scene.plate_material;
  const double a = mesh.length_x / mesh.elements_x, b = mesh.length_y / mesh.elements_y;
  // Every element is the same rectangle: one element gives the mesh's bound (elastic_plate.hpp).
  const plate::ElasticPlate cell(pm, {1, 1, a, b}, scene.edges);
  e.plate_limit = cell.stable_time_step();
  const double omega2 = std::pow(cell.max_frequency_bound(), 2);
  e.nodes = (static_cast<double>(mesh.elements_x) + 1.0) * (static_cast<double>(mesh.elements_y) + 1.0);
  e.grains = static_cast<double>(scene.packing.rows) * static_cast<double>(scene.packing.columns);
  e.hertz_limit = e.friction_limit = std::numeric_limits<double>::infinity();
  const double r = scene.packing.radius;
  const double m = (4.0 / 3.0) * std::numbers::pi * r * r * r * scene.packing.density;
  const double rotation = scene.contacts.rotation ? r * r / (0.4 * m * r * r) : 0.0;  // a^2/I with a = r
  double travel = std::numeric_limits<double>::infinity();
  if (!scene.drive.direct && scene.drive.kind != InterfaceDrive::Kind::edge_impulse) {
    const auto& g = scene.grain_material;
    const bool strike = scene.drive.kind == InterfaceDrive::Kind::velocity;
    const double speed = strike ? scene.drive.speed : 0.0;
    const double force = std::max(strike ? 0.0 : scene.drive.peak, scene.packing_load);
    const double edge_mass = 0.5 * pm.density * pm.thickness * a * b;  // a top-edge node's
    const PeakContact plate_contact =
        peak_contact(interface::grain_plate_modulus(g, pm, scene.contacts.plate_contact), r,
                     1.0 / m + 1.0 / edge_mass, 1.0 / m + 1.0 / edge_mass + rotation, omega2, speed, force,
                     scene.contacts, false);
    const PeakContact grain_contact =
        peak_contact(hertz_effective_modulus(g.youngs_modulus, g.poisson_ratio, g.youngs_modulus, g.poisson_ratio),
                     0.5 * r, 2.0 / m, 2.0 / m + 2.0 * rotation, 0.0, speed, force, scene.contacts, true);
    if (scene.walls.left || scene.walls.right) {
      // A bead pressed on a wall by the static load, or struck at it with the strike's speed.
      interface::InterfaceContacts along_walls = scene.contacts;
      along_walls.friction = scene.walls.friction;
      const PeakContact wall_contact = peak_contact(side_walls(scene).modulus, r, 1.0 / m, 1.0 / m + rotation, 0.0,
                                                    speed, force, along_walls, false);
      e.hertz_limit = std::min(e.hertz_limit, wall_contact.hertz_limit);
      e.friction_limit = std::min(e.friction_limit, wall_contact.friction_limit);
    }
    e.peak_overlap = plate_contact.overlap;
    e.contact_radius = std::sqrt(r * plate_contact.overlap);
    e.hertz_limit = std::min({e.hertz_limit, plate_contact.hertz_limit, grain_contact.hertz_limit});
    e.friction_limit = std::min({e.friction_limit, plate_contact.friction_limit, grain_contact.friction_limit});
    if (speed > 0.0) travel = 0.1 * r / speed;  // half the skin of 0.2 r
  }
  const auto& rec = scene.recording;
  e.step = rec.fixed_step > 0.0
               ? rec.fixed_step
               : std::min(rec.tolerance * std::min({e.plate_limit, e.hertz_limit, e.friction_limit}), travel);
  e.samples = rec.duration / rec.output_interval;
  e.steps = std::max(rec.duration / e.step, e.samples);
  const double probes = rec.probe_x.empty() ? 1.0 : static_cast<double>(rec.probe_x.size());
  e.memory_bytes = e.nodes * (kBytesPerNode + kBytesPerSnapshotNode * rec.snapshots) + e.grains * kBytesPerGrain +
                   (e.samples + 1.0) * (kBytesPerSample + kBytesPerSampleProbe * probes +
                                        kBytesPerSampleLineNode * (mesh.elements_x + 1.0));
  return e;
}

void check_interface_physics(const InterfaceScene& scene, const InterfaceEstimate& e) {
  const auto text = [](double x) {
    char s[32];
    std::snprintf(s, sizeof s, "%.3g", x);
    return std::string(s);
  };
  const std::string cause = scene.drive.kind == InterfaceDrive::Kind::velocity
                                ? "the strike at " + text(scene.drive.speed) + " m/s (drive.speed, --speed)"
                                : "the force of " + text(scene.drive.peak) + " N (drive.peak)";  // edge_impulse: no bead
  const std::string load = scene.packing_load > 0.0 ? " and the precompression (packing.precompression)" : "";
  const double r = scene.packing.radius;
  if (e.peak_overlap > kMaxOverlapFraction * r) {
    throw std::invalid_argument("interface: " + cause + load + " would press a bead " + text(e.peak_overlap) +
                                " m into the plate, " + text(e.peak_overlap / r) +
                                " of its radius: Hertz's small-strain contact holds below " +
                                text(kMaxOverlapFraction) + " of it; strike or load it more softly");
  }
  const double t = scene.plate_material.thickness;
  if (e.contact_radius >= 0.5 * t) {
    throw std::invalid_argument("interface: " + cause + load + " gives a grain-plate contact radius of " +
                                text(e.contact_radius) + " m, above half the plate's thickness (plate.thickness / 2 = " +
                                text(0.5 * t) + " m): the plane-stress plate cannot carry such a contact "
                                "(docs/interface.md, \"The coupling\")");
  }
  // Average-acceleration Newmark is unconditionally stable: only the explicit plate has this limit.
  if (scene.recording.scheme == interface::Scheme::velocity_verlet && scene.recording.fixed_step > e.plate_limit) {
    throw std::invalid_argument("interface: the fixed step " + text(scene.recording.fixed_step) +
                                " s (run.fixed_step, --fixed-step) exceeds the plate's stability limit 2/omega_max = " +
                                text(e.plate_limit) + " s: the explicit integration would blow up; use at most that");
  }
}

InterfaceRun run_interface(const InterfaceScene& scene, std::ostream* progress, double progress_seconds) {
  const auto start = std::chrono::steady_clock::now();
  InterfaceRun out;
  plate::ElasticPlate plate(scene.plate_material, scene.mesh, scene.edges);
  auto grains = interface::make_hex_packing(scene.packing);
  out.driven = driven_grains(grains, scene.drive.width, 0.5 * scene.mesh.length_x);
  for (int n = 0; n < plate.node_count(); ++n) {
    out.node_x.push_back(plate.node_x(n));
    out.node_y.push_back(plate.node_y(n));
  }
  out.element_size = std::min(plate.element_width(), plate.element_height());
  for (const double x : scene.recording.probe_x) out.probe_nodes.push_back(nearest_node(plate, x, scene.recording.probe_depth));
  {
    const int row = plate.node(0, nearest_node(plate, 0.0, scene.recording.line_depth) / plate.nodes_x());
    for (int i = 0; i < plate.nodes_x(); ++i) out.line_nodes.push_back(row + i);
  }

  if (scene.drive.direct && scene.drive.kind != InterfaceDrive::Kind::velocity)
    throw std::invalid_argument("interface: a direct strike takes a velocity drive's energy");
  double strike_energy = 0.0;
  const bool beadless = scene.drive.direct || scene.drive.kind == InterfaceDrive::Kind::edge_impulse;
  if (beadless) {
    out.direct_from = std::numeric_limits<double>::infinity();
    out.direct_to = -out.direct_from;
    for (const int g : out.driven) {
      const auto& b = grains[static_cast<std::size_t>(g)];
      if (scene.drive.direct) strike_energy += 0.5 * b.mass * scene.drive.speed * scene.drive.speed;
      out.direct_from = std::min(out.direct_from, b.x - b.radius);
      out.direct_to = std::max(out.direct_to, b.x + b.radius);
    }
    grains.clear();
  }
  interface::StepControl control{scene.recording.tolerance, std::numeric_limits<double>::infinity(),
                                 scene.recording.fixed_step};
  control.scheme = scene.recording.scheme;
  control.plate_tolerance = scene.recording.plate_tolerance;
  control.reltol = scene.recording.iteration_reltol;
  control.abstol = scene.recording.iteration_abstol;
  interface::GranularPlate run(std::move(grains), scene.grain_material, std::move(plate), scene.contacts, control);
  if (!beadless && (scene.walls.left || scene.walls.right)) run.set_side_walls(side_walls(scene));
  double static_energy = 0.0;
  if (scene.packing_load > 0.0) {
    // Static precompression: the whole free row pushed towards the plate, relaxed to rest first.
    run.set_static_load(driven_grains(run.grains(), 0, 0.5 * scene.mesh.length_x), 0.0, -scene.packing_load);
    out.relaxation_steps = run.relax(scene.relaxation_time, 1e-10, 200'000);
    static_energy = run.energies().mechanical();
    out.static_plate_force = run.plate_normal_force();
    out.static_left_wall_force = run.left_wall_force();
    out.static_right_wall_force = run.right_wall_force();
  }
  if (scene.drive.direct) {
    // One speed V on the struck edge's y-components with (1/2) sum M V^2 = the strike's energy.
    const auto& p = *run.plate();
    std::vector<std::size_t> struck;
    double mass = 0.0;
    for (int i = 0; i < p.nodes_x(); ++i) {
      const int n = p.node(i, p.nodes_y() - 1);
      if (p.node_x(n) < out.direct_from || p.node_x(n) > out.direct_to) continue;
      struck.push_back(static_cast<std::size_t>(2 * n + 1));
      mass += p.mass()[struck.back()];
    }
    if (struck.empty()) throw std::invalid_argument("interface: the direct strike's span holds no node");
    const double speed = std::sqrt(2.0 * strike_energy / mass);
    for (const std::size_t d : struck) run.plate_velocity_mutable()[d] = -speed;
    run.refresh_forces();
  } else if (scene.drive.kind == InterfaceDrive::Kind::edge_impulse) {
    run.set_plate_pulse({edge_line_load(*run.plate(), out.direct_from, out.direct_to, -scene.drive.line_load),
                         scene.drive.duration});
  } else if (scene.drive.kind == InterfaceDrive::Kind::velocity) {
    for (const int g : out.driven) run.grains_mutable()[static_cast<std::size_t>(g)].vy = -scene.drive.speed;
    run.refresh_forces();
  } else {
    run.set_drive({out.driven, scene.drive.peak, scene.drive.duration, 0.0, -1.0});
  }
  const double initial = run.energies().mechanical();

  out.probe_velocity.resize(out.probe_nodes.size());
  double interval_min = std::numeric_limits<double>::infinity(), interval_max = 0.0, last_step = 0.0;
  auto sample = [&] {
    auto& s = out.series;
    s.time.push_back(run.time());
    s.energies.push_back(run.energies());
    s.plate_normal_force.push_back(run.plate_normal_force());
    s.plate_tangential_force.push_back(run.plate_tangential_force());
    s.step.push_back(last_step);
    s.step_min.push_back(std::isfinite(interval_min) ? interval_min : 0.0);
    s.step_max.push_back(interval_max);
    s.steps.push_back(run.steps());
    s.limits.push_back(run.last_limits());
    s.grain_participation.push_back(interface::participation_ratio(run.grain_energies()));
    const auto& v = run.plate_velocity();
    for (std::size_t p = 0; p < out.probe_nodes.size(); ++p) {
      const auto n = static_cast<std::size_t>(out.probe_nodes[p]);
      out.probe_velocity[p].push_back(std::hypot(v[2 * n], v[2 * n + 1]));
    }
    std::vector<double> vx, vy;
    for (const int n : out.line_nodes) {
      vx.push_back(v[2 * static_cast<std::size_t>(n)]);
      vy.push_back(v[2 * static_cast<std::size_t>(n) + 1]);
    }
    out.line_vx.push_back(std::move(vx));
    out.line_vy.push_back(std::move(vy));
    interval_min = std::numeric_limits<double>::infinity();
    interval_max = 0.0;
  };
  sample();
  const auto& rec = scene.recording;
  const double wanted_samples = std::round(rec.duration / rec.output_interval);
  if (!(wanted_samples < 1e15))
    throw std::invalid_argument("interface: " + std::to_string(wanted_samples) + " samples: more than a run can record");
  const long samples = std::max(1L, static_cast<long>(wanted_samples));
  // A balance off by as much as the input is no result: the step outran a stability limit.
  const auto stop_if_unstable = [&](const interface::Energies& e) {
    const double input = initial - static_energy + e.drive_work;
    const double drift = std::abs(e.balance() - initial);
    if (std::isfinite(drift) && !(input > 0.0 && drift > kUnstableBalance * input)) return;
    const auto& l = run.last_limits();
    char text[400];
    std::snprintf(text, sizeof text,
                  "interface: the energy balance is off by %.3g times the input energy at t = %.6g s (step %.3g s; "
                  "limits now: plate %.3g s, Hertz %.3g s, Coulomb-tanh %.3g s): the integration is unstable; %s",
                  drift / input, run.time(), last_step, l.plate, l.hertz, l.friction,
                  rec.fixed_step > 0.0 ? "the fixed step (run.fixed_step, --fixed-step) exceeds a contact's limit: "
                                         "shorten it or use the adaptive step"
                                       : "lower the tolerance (run.tolerance, --tolerance)");
    throw std::runtime_error(text);
  };
  const auto started = std::chrono::steady_clock::now();
  auto reported = started;
  // At least every progress_seconds of wall time: a line with the time left at the rate so far.
  const auto report_if_due = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - reported).count() < progress_seconds) return;
    reported = now;
    const interface::Energies e = run.energies();
    stop_if_unstable(e);
    if (!progress) return;
    const double done = run.time() / rec.duration, spent = std::chrono::duration<double>(now - started).count();
    *progress << "t = " << run.time() << " s (" << std::lround(100.0 * done) << " % of the run), " << run.steps()
              << " steps, plate holds " << (e.plate_kinetic + e.plate_strain) << " J; about "
              << std::lround(done > 0.0 ? spent * (1.0 - done) / done : 0.0) << " s left" << std::endl;
  };
  int next_snapshot = 1;
  long calls = 0;
  for (long k = 1; k <= samples; ++k) {
    const double target = rec.duration * static_cast<double>(k) / static_cast<double>(samples);
    while (run.time() < target) {
      last_step = run.step_towards(target);
      interval_min = std::min(interval_min, run.last_substep_min());  // the grains' steps
      interval_max = std::max(interval_max, run.last_substep_max());
      if (++calls % 256 == 0) report_if_due();
    }
    sample();
    stop_if_unstable(out.series.energies.back());
    while (rec.snapshots > 0 && next_snapshot <= rec.snapshots &&
           run.time() >= rec.duration * next_snapshot / rec.snapshots * (1.0 - 1e-12)) {
      out.snapshot_time.push_back(run.time());
      out.snapshots.push_back(run.plate_displacement());
      ++next_snapshot;
    }
    if (progress && (k * 10) / samples != ((k - 1) * 10) / samples) {
      const auto& e = out.series.energies.back();
      *progress << "t = " << run.time() << " s, " << run.steps() << " steps, plate holds "
                << (e.plate_kinetic + e.plate_strain) << " J" << std::endl;  // flushed: a pipe sees it now
    }
  }
  out.input_energy = initial - static_energy + out.series.energies.back().drive_work;
  for (const auto& e : out.series.energies)
    out.worst_balance = std::max(out.worst_balance, std::abs(e.balance() - initial) / std::max(out.input_energy, 1e-300));
  for (std::size_t p = 0; p < out.probe_nodes.size(); ++p)
    out.arrival.push_back(scene.drive.direct ? front_time(out.series.time, out.probe_velocity[p])
                                             : arrival_time(out.series.time, out.probe_velocity[p], rec.arrival_fraction));
  out.final_grains = run.grains();
  out.max_contact_radius = run.max_plate_contact_radius();
  out.iterations = run.iterations();
  out.most_iterations = run.most_iterations();
  out.factorisations = run.factorisations();
  out.plate_steps = run.plate_steps();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

template <typename T>
void write_with_unit(hid_t parent, const std::string& name, const std::vector<T>& data, const std::string& unit,
                     std::size_t columns = 0) {
  io::write(parent, name, data.data(), columns ? data.size() / columns : data.size(), columns);
  io::Handle set = io::open_dataset(parent, name);
  io::write_string_attribute(set, "unit", unit);
}

template <typename F>
std::vector<double> column(const InterfaceRun& r, F&& field) {
  std::vector<double> c;
  for (std::size_t k = 0; k < r.series.time.size(); ++k) c.push_back(field(k));
  return c;
}

std::vector<double> flatten(const std::vector<std::vector<double>>& rows) {
  std::vector<double> flat;
  for (const auto& row : rows) flat.insert(flat.end(), row.begin(), row.end());
  return flat;
}

}  // namespace

void write_interface_run_file(const std::filesystem::path& path, const InterfaceScene& scene, const InterfaceRun& r) {
  io::write_file_atomically(path, [&](hid_t file) {
    io::write_string_attribute(file, "units", "SI: m, kg, s, N, J");
    io::write_string_dataset(file, "scene", scene.text);
    io::write_attribute(file, "input_energy", r.input_energy);
    io::write_attribute(file, "worst_energy_balance", r.worst_balance);
    io::write_attribute(file, "max_plate_contact_radius", r.max_contact_radius);
    io::write_attribute(file, "element_size", r.element_size);
    io::write_attribute(file, "wall_seconds", r.seconds);
    // newmark_rk4: the fixed-point iterations in all and the most in one step, the factorisations.
    io::write_attribute(file, "fixed_point_iterations", static_cast<double>(r.iterations));
    io::write_attribute(file, "most_fixed_point_iterations_in_a_step", static_cast<double>(r.most_iterations));
    io::write_attribute(file, "factorisations", static_cast<double>(r.factorisations));
    io::write_attribute(file, "plate_steps", static_cast<double>(r.plate_steps));  // multirate: the outer steps
    const auto& s = r.series;
    io::Handle ts = io::create_group(file, "time_series");
    write_with_unit(ts, "time", s.time, "s");
    const auto e = [&](auto member) { return column(r, [&](std::size_t k) { return s.energies[k].*member; }); };
    using E = interface::Energies;
    write_with_unit(ts, "grain_translation", e(&E::grain_translation), "J");
    write_with_unit(ts, "grain_rotation", e(&E::grain_rotation), "J");
    write_with_unit(ts, "contact", e(&E::contact), "J");
    write_with_unit(ts, "plate_kinetic", e(&E::plate_kinetic), "J");
    write_with_unit(ts, "plate_strain", e(&E::plate_strain), "J");
    write_with_unit(ts, "friction_work", e(&E::friction_work), "J");
    write_with_unit(ts, "dashpot_work", e(&E::dashpot_work), "J");
    write_with_unit(ts, "boundary_work", e(&E::boundary_work), "J");
    write_with_unit(ts, "drive_work", e(&E::drive_work), "J");
    write_with_unit(ts, "plate_normal_force", s.plate_normal_force, "N");
    write_with_unit(ts, "plate_tangential_force", s.plate_tangential_force, "N");
    write_with_unit(ts, "step", s.step, "s");
    write_with_unit(ts, "step_min", s.step_min, "s");
    write_with_unit(ts, "step_max", s.step_max, "s");
    std::vector<std::int64_t> steps(s.steps.begin(), s.steps.end());
    write_with_unit(ts, "steps", steps, "1");
    write_with_unit(ts, "limit_plate", column(r, [&](std::size_t k) { return s.limits[k].plate; }), "s");
    write_with_unit(ts, "limit_hertz", column(r, [&](std::size_t k) { return s.limits[k].hertz; }), "s");
    write_with_unit(ts, "limit_friction", column(r, [&](std::size_t k) { return s.limits[k].friction; }), "s");
    write_with_unit(ts, "grain_participation", s.grain_participation, "1");

    io::Handle probes = io::create_group(file, "probes");
    std::vector<double> px, py;
    for (const int n : r.probe_nodes) {
      px.push_back(r.node_x[static_cast<std::size_t>(n)]);
      py.push_back(r.node_y[static_cast<std::size_t>(n)]);
    }
    write_with_unit(probes, "x", px, "m");
    write_with_unit(probes, "y", py, "m");
    write_with_unit(probes, "speed", flatten(r.probe_velocity), "m/s", s.time.size());
    write_with_unit(probes, "arrival_time", r.arrival, "s");

    io::Handle line = io::create_group(file, "line");
    std::vector<double> lx;
    for (const int n : r.line_nodes) lx.push_back(r.node_x[static_cast<std::size_t>(n)]);
    write_with_unit(line, "x", lx, "m");
    io::write_attribute(line, "y", r.node_y[static_cast<std::size_t>(r.line_nodes.front())]);
    write_with_unit(line, "velocity_x", flatten(r.line_vx), "m/s", lx.size());
    write_with_unit(line, "velocity_y", flatten(r.line_vy), "m/s", lx.size());
    const WavenumberSpread spread = wavenumber_spread(r, scene.plate_material.density, scene.plate_material.thickness,
                                                      lx.size() > 1 ? lx[1] - lx[0] : 1.0);
    write_with_unit(line, "k", spread.k, "rad/m");
    write_with_unit(line, "energy_spectrum", flatten(spread.energy), "J/m", spread.k.size());
    write_with_unit(line, "line_energy", spread.line_energy, "J/m");
    write_with_unit(line, "k_variance", spread.variance, "rad^2/m^2");
    io::write_attribute(line, "k_variance_rate", spread.growth.slope);
    io::write_attribute(line, "k_variance_intercept", spread.growth.intercept);
    io::write_attribute(line, "k_variance_r_squared", spread.growth.r_squared);
    io::write_attribute(line, "fit_first_time", s.time[std::min(spread.first, s.time.size() - 1)]);
    io::write_attribute(line, "fit_last_time", s.time[std::min(spread.last, s.time.size()) - 1]);

    io::Handle snap = io::create_group(file, "snapshots");
    write_with_unit(snap, "node_x", r.node_x, "m");
    write_with_unit(snap, "node_y", r.node_y, "m");
    write_with_unit(snap, "time", r.snapshot_time, "s");
    if (!r.snapshots.empty()) write_with_unit(snap, "displacement", flatten(r.snapshots), "m", r.snapshots.front().size());

    io::Handle grains = io::create_group(file, "grains");
    std::vector<double> gx, gy, gvx, gvy, spin, driven(r.final_grains.size(), 0.0);
    for (const auto& g : r.final_grains) {
      gx.push_back(g.x), gy.push_back(g.y), gvx.push_back(g.vx), gvy.push_back(g.vy), spin.push_back(g.spin);
    }
    if (!r.final_grains.empty())  // a direct strike runs without beads
      for (const int d : r.driven) driven[static_cast<std::size_t>(d)] = 1.0;
    write_with_unit(grains, "x", gx, "m");
    write_with_unit(grains, "y", gy, "m");
    write_with_unit(grains, "vx", gvx, "m/s");
    write_with_unit(grains, "vy", gvy, "m/s");
    write_with_unit(grains, "spin", spin, "rad/s");
    write_with_unit(grains, "driven", driven, "1");
  });
}

void write_interface_csv(const std::filesystem::path& dir, const InterfaceScene& scene, const InterfaceRun& r) {
  std::filesystem::create_directories(dir);
  const auto& s = r.series;
  io::write_text_atomically(dir / "energies.csv", [&](std::ostream& f) {
    f << "# granular-solid interface run of " << scene.path.string() << "; SI units; input energy " << r.input_energy
      << " J\n# time_s,grain_translation_J,grain_rotation_J,contact_J,plate_kinetic_J,plate_strain_J,friction_J,"
         "dashpot_J,boundary_J,drive_J,plate_normal_force_N,plate_tangential_force_N,step_s,limit_plate_s,"
         "limit_hertz_s,limit_friction_s,grain_participation\n";
    for (std::size_t k = 0; k < s.time.size(); ++k) {
      const auto& e = s.energies[k];
      char line[512];
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                    s.time[k], e.grain_translation, e.grain_rotation, e.contact, e.plate_kinetic, e.plate_strain,
                    e.friction_work, e.dashpot_work, e.boundary_work, e.drive_work, s.plate_normal_force[k],
                    s.plate_tangential_force[k], s.step[k], s.limits[k].plate, s.limits[k].hertz, s.limits[k].friction,
                    s.grain_participation[k]);
      f << line;
    }
  });
  io::write_text_atomically(dir / "probes.csv", [&](std::ostream& f) {
    f << "# |v| [m/s] of the plate at the probes; columns: time_s then one per probe (x [m] in the header)\n# time_s";
    for (const int n : r.probe_nodes) f << ",x=" << r.node_x[static_cast<std::size_t>(n)];
    f << "\n";
    for (std::size_t k = 0; k < s.time.size(); ++k) {
      f << s.time[k];
      for (const auto& p : r.probe_velocity) f << "," << p[k];
      f << "\n";
    }
  });
  for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
    io::write_text_atomically(dir / ("snapshot_" + std::to_string(k + 1) + ".csv"), [&](std::ostream& f) {
      f << "# plate displacement at t = " << r.snapshot_time[k]
        << " s; x_m,y_m,ux_m,uy_m (blank line per row of nodes)\n";
      const auto& u = r.snapshots[k];
      const std::size_t nx = r.line_nodes.size();
      for (std::size_t n = 0; n < r.node_x.size(); ++n) {
        f << r.node_x[n] << "," << r.node_y[n] << "," << u[2 * n] << "," << u[2 * n + 1] << "\n";
        if ((n + 1) % nx == 0) f << "\n";
      }
    });
  }
}

}  // namespace sedwave::forward::experiment
