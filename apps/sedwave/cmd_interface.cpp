// `sedwave interface`: one run of a granular-solid interface scene (docs/interface.md): a 2D
// hexagonal packing of spheres on the edge of an elastic plate, driven at its free end; energies,
// forces, arrival times, step sizes and plate snapshots to HDF5 (and CSV for plots).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/forward/experiment/interface_run.hpp"
#include "sedwave/forward/experiment/interface_scene.hpp"
#include "sedwave/forward/experiment/interface_spectrum.hpp"

namespace sedwave::app {
namespace {

namespace experiment = forward::experiment;

struct InterfaceOptions {
  std::string scene;
  std::string out = "interface.h5";
  std::string csv;
  std::optional<double> speed;
  std::optional<double> tolerance;
  bool direct = false;
  std::optional<double> fixed_step;
  double max_steps = 1e7;
  double max_memory_gb = 4.0;
  bool quiet = false;
};

/// Every file the run writes: the run file and, with --csv, the CSV tables (one per snapshot).
std::vector<OutputPath> output_files(const InterfaceOptions& o, const experiment::InterfaceScene& scene) {
  std::vector<OutputPath> outputs{{"--out", o.out, io::OutputFormat::seekable}};
  if (o.csv.empty()) return outputs;
  const std::filesystem::path dir(o.csv);
  outputs.push_back({"--csv", dir / "energies.csv"});
  outputs.push_back({"--csv", dir / "probes.csv"});
  for (int k = 1; k <= scene.recording.snapshots; ++k)
    outputs.push_back({"--csv", dir / ("snapshot_" + std::to_string(k) + ".csv")});
  return outputs;
}

/// The command line's overrides, on the scene's ranges; a value out of them is a usage error.
void apply_overrides(const InterfaceOptions& o, experiment::InterfaceScene& scene) {
  if (o.tolerance && (o.fixed_step || scene.recording.fixed_step > 0.0))
    throw UsageError("--tolerance sets the adaptive step's theta, and this run has a fixed step (" +
                     std::string(o.fixed_step ? "--fixed-step" : "run.fixed_step in " + o.scene) + "): give one of them");
  if (o.speed && scene.drive.kind != experiment::InterfaceDrive::Kind::velocity)
    throw std::invalid_argument(o.scene + ": --speed overrides a velocity drive; this scene's drive.kind is " +
                                (scene.drive.kind == experiment::InterfaceDrive::Kind::force ? "force" : "edge_impulse"));
  try {
    if (o.speed) experiment::override_speed(scene, *o.speed, "--speed");
    if (o.tolerance) experiment::override_tolerance(scene, *o.tolerance, "--tolerance");
    if (o.fixed_step) experiment::override_fixed_step(scene, *o.fixed_step, "--fixed-step");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  scene.drive.direct = o.direct;
}

/// Refuses a run beyond the step or memory budget, naming the estimate, the budget and the option
/// that raises it; otherwise announces the estimate.
void check_budget(const InterfaceOptions& o, const experiment::InterfaceEstimate& e) {
  char text[600];
  const double gb = e.memory_bytes / 1e9;
  if (!(gb <= o.max_memory_gb)) {
    std::snprintf(text, sizeof text,
                  "%s: the run would hold about %.3g GB (%.3g plate nodes, %.3g grains, %.3g samples), above the "
                  "budget of %.3g GB: use fewer elements, grains or samples, or raise the budget with --max-memory",
                  o.scene.c_str(), gb, e.nodes, e.grains, e.samples, o.max_memory_gb);
    throw std::invalid_argument(text);
  }
  if (!(e.steps <= o.max_steps)) {
    std::snprintf(text, sizeof text,
                  "%s: the run would take about %.3g steps (step %.3g s over run.duration; limits: plate %.3g s, "
                  "Hertz %.3g s, Coulomb-tanh %.3g s; %.3g samples), above the budget of %.3g steps: shorten "
                  "run.duration, lengthen the step or run.output_interval, or raise the budget with --max-steps",
                  o.scene.c_str(), e.steps, e.step, e.plate_limit, e.hertz_limit, e.friction_limit, e.samples,
                  o.max_steps);
    throw std::invalid_argument(text);
  }
  if (o.quiet) return;
  std::printf("estimate: about %.3g steps (step down to %.3g s; limits: plate %.3g s, Hertz %.3g s, Coulomb-tanh %.3g s) "
              "of %.3g plate nodes and %.3g grains, %.3g samples, %.3g GB (budgets: --max-steps %.3g, --max-memory "
              "%.3g GB)\n",
              e.steps, e.step, e.plate_limit, e.hertz_limit, e.friction_limit, e.nodes, e.grains, e.samples, gb,
              o.max_steps, o.max_memory_gb);
  if (e.step > std::min(e.hertz_limit, e.friction_limit))
    std::printf("note: the fixed step %.3g s exceeds the estimated contact limit %.3g s; the run stops if its "
                "energy balance blows up\n", e.step, std::min(e.hertz_limit, e.friction_limit));
  std::fflush(stdout);
}

void print_summary(const experiment::InterfaceScene& scene, const experiment::InterfaceRun& r) {
  const auto& e = r.series.energies.back();
  const double in = r.input_energy;
  double plate_peak = 0.0;
  for (const auto& s : r.series.energies) plate_peak = std::max(plate_peak, s.plate_kinetic + s.plate_strain);
  if (scene.drive.direct) {
    std::printf("direct strike on the plate's edge over x = %.4g .. %.4g m with the energy of %zu beads at %g m/s "
                "(no beads), %d x %d plate elements; %ld steps in %.2f s\n",
                r.direct_from, r.direct_to, r.driven.size(), scene.drive.speed, scene.mesh.elements_x,
                scene.mesh.elements_y, r.series.steps.back(), r.seconds);
    // The front is read from the samples of a pulse as short as the mesh allows (docs/interface.md).
    const auto& m = scene.plate_material;
    const double c_l = std::sqrt(m.youngs_modulus / (m.density * (1.0 - m.poisson_ratio * m.poisson_ratio)));
    const double transit = std::min(scene.mesh.length_x / scene.mesh.elements_x,
                                    scene.mesh.length_y / scene.mesh.elements_y) / c_l;
    if (scene.recording.output_interval > 0.1 * transit)
      std::printf("note: the arrival (the direct pulse's front) is read from samples every %.3g s, coarser than a "
                  "tenth of the mesh's transit time h/c_L = %.3g s: set run.output_interval below %.3g s\n",
                  scene.recording.output_interval, transit, 0.1 * transit);
  } else if (scene.drive.kind == experiment::InterfaceDrive::Kind::edge_impulse) {
    std::printf("uniform impulse of %g N/m for %g s on the plate's edge over x = %.4g .. %.4g m (no beads), %d x %d "
                "plate elements; %ld steps in %.2f s\n",
                scene.drive.line_load, scene.drive.duration, r.direct_from, r.direct_to, scene.mesh.elements_x,
                scene.mesh.elements_y, r.series.steps.back(), r.seconds);
  } else {
    std::printf("%zu grains (%zu driven), %d x %d plate elements; %ld steps in %.2f s\n", r.final_grains.size(),
                r.driven.size(), scene.mesh.elements_x, scene.mesh.elements_y, r.series.steps.back(), r.seconds);
  }
  if (scene.packing_load > 0.0) {
    std::printf("precompression %.6g N on each bead of the free row: relaxed in %ld steps; at rest the plate carries "
                "%.6g N", scene.packing_load, r.relaxation_steps, r.static_plate_force);
    if (scene.walls.left || scene.walls.right)
      std::printf(", the side walls %.6g N (left) and %.6g N (right)", r.static_left_wall_force, r.static_right_wall_force);
    std::printf("\n");
  }
  std::printf("input energy %.6g J; at t = %.6g s: grains %.4f (rotation %.4f), contacts %.4f, plate %.4f, "
              "friction %.4f, dashpots %.4f, absorbed by the plate's edges %.4f of it\n",
              in, r.series.time.back(), (e.grain_translation + e.grain_rotation) / in, e.grain_rotation / in,
              e.contact / in, (e.plate_kinetic + e.plate_strain) / in, e.friction_work / in, e.dashpot_work / in,
              e.boundary_work / in);
  std::printf("largest share in the plate %.4f; energy balance within %.3g of the input\n", plate_peak / in,
              r.worst_balance);
  if (!r.final_grains.empty() && !r.series.grain_participation.empty())
    std::printf("the grains' energy is shared by %.4g of %zu grains at the end (participation ratio; %.4g at the start)\n",
                r.series.grain_participation.back(), r.final_grains.size(), r.series.grain_participation.front());
  double min_step = INFINITY, max_step = 0.0;
  for (std::size_t k = 1; k < r.series.time.size(); ++k) {
    min_step = std::min(min_step, r.series.step_min[k]);
    max_step = std::max(max_step, r.series.step_max[k]);
  }
  std::printf("step %.3g .. %.3g s (plate limit %.3g s, tolerance %g)\n", min_step, max_step,
              r.series.limits.back().plate, scene.recording.tolerance);
  for (std::size_t p = 0; p < r.probe_nodes.size(); ++p) {
    const auto n = static_cast<std::size_t>(r.probe_nodes[p]);
    std::printf("probe at x = %.4g m, y = %.4g m: arrival %.6g s\n", r.node_x[n], r.node_y[n], r.arrival[p]);
  }
  const double spacing = r.node_x.size() > 1 ? r.node_x[1] - r.node_x[0] : 1.0;
  const auto spread = experiment::wavenumber_spread(r, scene.plate_material.density, scene.plate_material.thickness,
                                                    spacing);
  if (spread.last > spread.first + 2) {
    std::printf("line at y = %.4g m: wavenumber variance sigma_k^2 from %.4g to %.4g rad^2/m^2 over %.4g .. %.4g s; "
                "linear fit %.4g rad^2/m^2/s (R^2 = %.3f)\n",
                r.node_y[static_cast<std::size_t>(r.line_nodes.front())], spread.variance[spread.first],
                spread.variance[spread.last - 1], r.series.time[spread.first], r.series.time[spread.last - 1],
                spread.growth.slope, spread.growth.r_squared);
  }
  std::printf("largest grain-plate contact radius %.3g m against element size %.3g m\n", r.max_contact_radius,
              r.element_size);
  if (scene.recording.scheme == forward::interface::Scheme::multirate)
    std::printf("multirate: %ld plate steps, %.3g grain steps each\n", r.plate_steps,
                static_cast<double>(r.series.steps.back()) / static_cast<double>(std::max(r.plate_steps, 1L)));
  if (scene.recording.scheme == forward::interface::Scheme::newmark_rk4)
    std::printf("newmark_rk4: %ld fixed-point iterations (%.3g a step, at most %d), %ld factorisations\n",
                r.iterations, static_cast<double>(r.iterations) / static_cast<double>(r.series.steps.back()),
                r.most_iterations, r.factorisations);
}

int run_interface_command(const InterfaceOptions& o) {
  experiment::InterfaceScene scene = experiment::read_interface_scene(o.scene);
  check_outputs(output_files(o, scene), {o.scene}, "interface");
  apply_overrides(o, scene);
  const experiment::InterfaceEstimate estimate = experiment::estimate_interface_run(scene);
  experiment::check_interface_physics(scene, estimate);
  check_budget(o, estimate);
  const experiment::InterfaceRun r = experiment::run_interface(scene, o.quiet ? nullptr : &std::cout);
  {
    io::DeferredCommits outputs;  // the run file and the tables together, or none of them
    experiment::write_interface_run_file(o.out, scene, r);
    if (!o.csv.empty()) experiment::write_interface_csv(o.csv, scene, r);
    outputs.commit_all();
  }
  if (!o.quiet) {
    print_summary(scene, r);
    std::printf("written to %s%s\n", o.out.c_str(), o.csv.empty() ? "" : (" and " + o.csv + "/*.csv").c_str());
  }
  // The element must be much larger than the contact patch: the Hertz modulus already holds the
  // plate's local indentation, or the patch must fit its rigid layer (docs/interface.md, "The coupling").
  if (r.max_contact_radius > 0.5 * r.element_size) {
    std::printf(scene.contacts.plate_contact == forward::interface::PlateContactModel::rigid_layers
                    ? "flagged: the contact radius exceeds half the element size; the contact patch is wider than "
                      "its rigid layer\n"
                    : "flagged: the contact radius exceeds half the element size; the plate's local compliance is "
                      "counted twice\n");
    return kExitIncomplete;
  }
  // The beads' collective push can exceed the single strike the estimate checked before the run.
  if (r.max_contact_radius >= 0.5 * scene.plate_material.thickness) {
    std::printf("flagged: the contact radius reached half the plate's thickness; the plane-stress plate does not "
                "describe such a contact\n");
    return kExitIncomplete;
  }
  return kExitOk;
}

}  // namespace

Command add_interface_command(CLI::App& app) {
  auto o = std::make_shared<InterfaceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "interface", "Run a granular-solid interface scene: 2D grains on an elastic plate (docs/interface.md)");
  cmd->add_option("scene", o->scene, "interface scene file (TOML, SI units)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "run file to write (HDF5)")->capture_default_str()->check(output_path());
  cmd->add_option("--csv", o->csv, "also write energies.csv, probes.csv and snapshot_K.csv (K = 1, 2, ...) into this directory")
      ->check(output_path());
  cmd->add_option("--speed", o->speed, "override the drive's speed [m/s] (velocity drives), in (0, 1e4]")
      ->check(finite_positive());
  cmd->add_option("--tolerance", o->tolerance, "override the adaptive step's tolerance theta, in (0, 0.5]")
      ->check(finite_positive());
  cmd->add_option("--fixed-step", o->fixed_step,
                  "a fixed step [s] instead of the adaptive one (for comparisons; at most the plate's stability limit)")
      ->check(finite_positive());
  cmd->add_option("--max-steps", o->max_steps, "refuse a run estimated to take more steps")
      ->capture_default_str()->check(finite_in(1.0));
  cmd->add_option("--max-memory", o->max_memory_gb, "refuse a run estimated to hold more memory [GB]")
      ->capture_default_str()->check(finite_positive());
  cmd->add_flag("--direct", o->direct,
                "strike the plate's edge directly (no beads) with the driven beads' energy: the delay's reference");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  return {cmd, [o]() { return run_interface_command(*o); }};
}

}  // namespace sedwave::app
