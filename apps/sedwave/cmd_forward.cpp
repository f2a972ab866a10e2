// `sedwave forward`: one acoustic run of a channel scene: generate (or import) the packing,
// compress and relax it, drive it, measure alpha_hat and c_hat, write everything to HDF5. The
// scene's `engine` picks the time-domain DEM or the linear-response engine (over an ensemble of
// packings).
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/experiment/linear_run_file.hpp"
#include "sedwave/forward/experiment/packings.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/experiment/scene.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::app {
namespace {

namespace experiment = forward::experiment;

struct ForwardOptions {
  std::string scene;
  std::string out = "run.h5";
  std::string packing_in;
  std::string packing_out;
  std::optional<double> omega_hat;
  std::optional<double> gamma_hat;
  bool quiet = false;
};

/// The scene's pore fluid and the dashpots it puts beside the contacts' gamma_hat (collective over
/// `comm`, over whose ranks the packing's grains are spread; printed on its rank 0): docs/fluid.md.
void print_fluid(MPI_Comm comm, const experiment::ChannelScene& scene, const forward::channel::PreparedChannel& packing) {
  if (!scene.drive.fluid) return;
  namespace channel = forward::channel;
  const channel::PackingUnits u = channel::packing_units(comm, packing, scene.contact);
  if (forward::parallel::rank(comm) != 0) return;
  const forward::dem::FluidSpec f = channel::fluid_in_packing_units(*scene.drive.fluid, u);
  const double unit = std::sqrt(u.kappa * u.mass), r = 0.5 * u.diameter;
  std::printf("pore fluid: %s; in sqrt(kappa m): film at the roughness %.3g (two grains of diameter d), drag %.3g "
              "per grain (porosity %.3g)\n",
              channel::describe_fluid_groups(*scene.drive.fluid).c_str(), f.lubrication_coefficient(0.0, r, r) / unit,
              f.drag_coefficient(r) / unit, f.porosity);
}

/// The linear engine: one packing per ensemble member (prepared, or read with --packing), solved on
/// rank 0 (the solve is serial and takes seconds; preparation uses every rank).
int run_linear(const ForwardOptions& o, const experiment::ChannelScene& scene, const MpiSession& mpi, bool talk) {
  std::vector<forward::linear::LinearChannel> members;
  std::vector<forward::channel::PreparationReport> reports;
  for (int k = 0; k < scene.linear.ensemble; ++k) {
    experiment::ScenePacking packing =
        experiment::scene_packing(scene, k, {o.packing_in, o.packing_out}, talk ? &std::cout : nullptr);
    if (talk && packing.prepared) {
      std::cout << "member " << k << ":\n" << forward::channel::describe(packing.channel.report) << "\n";
    }
    packing.channel.grains = forward::parallel::gather_on_root(MPI_COMM_WORLD, packing.channel.grains);
    if (mpi.rank() != 0) continue;
    if (talk && k == 0) print_fluid(MPI_COMM_SELF, scene, packing.channel);
    reports.push_back(packing.channel.report);
    members.emplace_back(packing.channel, scene.contact, scene.linear, scene.drive.fluid);
  }
  if (mpi.rank() != 0) return 0;
  const forward::linear::EnsembleResult e = forward::linear::respond(members, scene.drive);
  experiment::write_linear_run_file(o.out, scene, reports, e);
  if (talk) {
    std::printf("linear engine, %zu packing(s): omega_hat %.6g  gamma_hat %.6g\n", members.size(),
                scene.drive.omega_hat, scene.drive.gamma_hat);
    for (std::size_t k = 0; k < e.members.size(); ++k) {
      const forward::linear::LinearResult& r = e.members[k];
      std::printf("  member %zu: alpha_hat %.6g +- %.2g  c_hat %.6g +- %.2g  (%d layers; of %lld contacts "
                  "%lld open, %lld slide; %.2f s)\n",
                  k, r.fit.alpha, r.fit.sigma_alpha, r.fit.c, r.fit.sigma_c, r.layers_used,
                  static_cast<long long>(r.state_changes.contacts), static_cast<long long>(r.state_changes.opening),
                  static_cast<long long>(r.state_changes.sliding), r.solve_seconds);
    }
    if (!e.members.empty()) {
      std::printf("contacts opening / sliding / gaps closing per cycle (member 0) at A [d] =");
      for (const auto& c : e.members.front().amplitude_ladder) {
        std::printf("  %.0e: %lld/%lld/%lld", c.amplitude, static_cast<long long>(c.opening),
                    static_cast<long long>(c.sliding), static_cast<long long>(c.closing));
      }
      std::printf("  (of %lld contacts, %lld gaps)\n", static_cast<long long>(e.members.front().state_changes.contacts),
                  static_cast<long long>(e.members.front().state_changes.gaps));
    }
    if (e.ok()) {
      std::printf("alpha_hat %.6g +- %.2g   c_hat %.6g +- %.2g   (%.2f s of solving)\n", e.alpha_hat,
                  e.sigma_alpha_hat, e.c_hat, e.sigma_c_hat, e.solve_seconds);
    } else {
      std::printf("not measured: %s\n", e.problem.c_str());
    }
    if (!e.warning.empty()) std::printf("warning: %s\n", e.warning.c_str());
    std::printf("written to %s\n", o.out.c_str());
  }
  return e.ok() ? kExitOk : kExitIncomplete;
}

/// A pulse run: one line per frequency of the band.
void print_spectrum(const forward::channel::AcousticResult& r) {
  std::printf("pulse: %zu frequencies from one run\n", r.spectrum.size());
  for (const forward::channel::SpectralResult& p : r.spectrum) {
    if (p.ok()) {
      std::printf("  omega_hat %-9.4g alpha_hat %.6g +- %.2g   c_hat %.6g +- %.2g   (%d layers)\n", p.omega_hat,
                  p.fit.alpha, p.fit.sigma_alpha, p.fit.c, p.fit.sigma_c, p.layers_used);
    } else {
      std::printf("  omega_hat %-9.4g not measured: %s\n", p.omega_hat, p.problem.c_str());
    }
  }
  std::printf("at the band's centre:\n");
}

/// The front speed the windows come from, and the lock-in windows of the first and last layer that
/// has one (a sinusoid's measurement; every layer's window is in the run file).
void print_windows(const forward::channel::AcousticResult& r) {
  std::printf("front speed %.4g (first peaks; sets the windows)", r.wave_speed_estimate);
  std::vector<std::size_t> locked;  // layers with a window and a lock-in
  for (std::size_t k = 0; k < r.windows.size(); ++k) {
    if (r.windows[k].valid() && r.lock_ins[k].amplitude != 0.0) locked.push_back(k);
  }
  if (!locked.empty()) {
    const std::size_t a = locked.front(), b = locked.back();
    const forward::channel::ProbeWindow &first = r.windows[a], &last = r.windows[b];
    std::printf("; lock-in windows [t in sqrt(m/kappa)] from z = %.1f d: %.4g .. %.4g (%d periods) to z = %.1f d: %.4g .. %.4g "
                "(%d periods)",
                r.layer_z[a], first.window.begin, first.window.end, first.periods, r.layer_z[b], last.window.begin,
                last.window.end, last.periods);
  }
  std::printf("\n");
}

/// The single-grain probes' result beside the layers' (the headline frequency; a broadband run's
/// per-frequency values are in the run file).
void print_single_grains(const forward::channel::SingleGrainProbes& p, bool sinusoid) {
  if (!p.problem.empty()) {
    std::printf("single grains: not measured: %s\n", p.problem.c_str());
  } else {
    std::printf("single grains: alpha_hat %.6g +- %.2g   c_hat %.6g +- %.2g   (%d grains%s)\n", p.fit.alpha,
                p.fit.sigma_alpha, p.fit.c, p.fit.sigma_c, p.probes_used,
                sinusoid ? "" : "; every frequency in the run file");
  }
}

/// Every file the run writes and reads (ensembles: one packing per member), checked before any work.
void check_forward_paths(const ForwardOptions& o, const experiment::ChannelScene& scene) {
  const int members = scene.engine == experiment::EngineKind::linear ? scene.linear.ensemble : 1;
  std::vector<OutputPath> outputs{{"--out", o.out, io::OutputFormat::seekable}};
  std::vector<std::filesystem::path> inputs{o.scene};
  if (scene.import_lammps_data) inputs.push_back(*scene.import_lammps_data);
  for (int k = 0; k < members; ++k) {
    if (!o.packing_in.empty()) inputs.emplace_back(experiment::member_path(o.packing_in, k));
    if (o.packing_out.empty()) continue;
    std::filesystem::path packing = experiment::member_path(o.packing_out, k);
    outputs.push_back({"--packing-out", packing, io::OutputFormat::seekable});
    outputs.push_back({"--packing-out", packing.replace_extension(".data")});  // its LAMMPS twin
  }
  check_outputs(outputs, inputs, "forward");
}

int run_forward(const ForwardOptions& o, const MpiSession& mpi) {
  using namespace forward::channel;
  experiment::ChannelScene scene;
  mpi.alike([&] {  // every rank reads the scene: a mistake in it is told once
    scene = experiment::read_scene(o.scene);
    check_forward_paths(o, scene);
    if (o.omega_hat && scene.drive.pulse) {
      throw std::invalid_argument(o.scene + ": --omega-hat sets a sinusoid's frequency; this scene drives a pulse "
                                  "(set [drive] omega_hat_min/omega_hat_max instead)");
    }
  });
  // One run at a time per --out, after every check (a refused run waits for nothing): a second run
  // waits, as invert's and compare's do, instead of both reporting the file written. Rank 0 holds
  // the lock; the other ranks sleep meanwhile rather than spin in a collective.
  std::optional<io::OutputFileLock> lock;
  std::exception_ptr locking;
  if (mpi.rank() == 0) {
    try {
      lock.emplace(o.out, "--out");
    } catch (...) {
      locking = std::current_exception();
    }
  }
  forward::parallel::barrier_sleeping(MPI_COMM_WORLD);
  mpi.alike([&] {
    if (locking) std::rethrow_exception(locking);
  });
  if (o.omega_hat) scene.drive.omega_hat = *o.omega_hat;
  if (o.gamma_hat) scene.drive.gamma_hat = *o.gamma_hat;
  const bool talk = mpi.rank() == 0 && !o.quiet;
  scene.preparation.log = talk ? &std::cout : nullptr;
  scene.drive.log = scene.preparation.log;
  if (scene.engine == experiment::EngineKind::linear) return run_linear(o, scene, mpi, talk);

  const experiment::ScenePacking packing =
      experiment::scene_packing(scene, 0, {o.packing_in, o.packing_out}, scene.preparation.log);
  if (talk && packing.prepared) {
    std::cout << describe(packing.channel.report) << "\n";
    if (!o.packing_out.empty()) std::cout << "packing written to " << o.packing_out << " (and .data for LAMMPS)\n";
  }
  if (!o.quiet) print_fluid(MPI_COMM_WORLD, scene, packing.channel);  // every rank knows o.quiet
  const AcousticResult r = run_acoustic(MPI_COMM_WORLD, packing.channel, scene.contact, scene.drive);
  if (mpi.rank() == 0) {
    experiment::write_run_file(o.out, scene, packing.channel.report, r);
    if (talk) {
      std::printf("omega_hat %.6g  gamma_hat %.6g\n", r.omega_hat, r.gamma_hat);
      if (!r.spectrum.empty()) print_spectrum(r);
      else print_windows(r);
      if (r.ok()) {
        std::printf("alpha_hat %.6g +- %.2g   c_hat %.6g +- %.2g   (%d layers, %lld steps, %.1f s)\n", r.fit.alpha,
                    r.fit.sigma_alpha, r.fit.c, r.fit.sigma_c, r.layers_used, static_cast<long long>(r.steps),
                    r.wall_seconds);
      } else {
        std::printf("not measured: %s\n", r.problem.c_str());
      }
      if (r.extensions > 0) {
        std::printf("the run was continued %d time(s): its windows were not steady or deep layers lay below the "
                    "noise floor%s\n", r.extensions, r.ok() && r.warning.empty() ? "; now measured and steady" : "");
      }
      if (!r.warning.empty()) std::printf("warning: %s\n", r.warning.c_str());
      if (r.single_grains) print_single_grains(*r.single_grains, r.spectrum.empty());
      std::printf("written to %s\n", o.out.c_str());
    }
  }
  return r.ok() ? kExitOk : kExitIncomplete;
}

}  // namespace

Command add_forward_command(CLI::App& app) {
  auto o = std::make_shared<ForwardOptions>();
  CLI::App* cmd = app.add_subcommand(
      "forward", "Run one acoustic channel simulation from a scene file (docs/scenes.md); MPI-parallel under mpirun");
  cmd->add_option("scene", o->scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "run file to write (HDF5)")->capture_default_str();
  cmd->add_option("--packing-out", o->packing_out, "also write the prepared packing (HDF5 + LAMMPS .data)");
  cmd->add_option("--packing", o->packing_in, "reuse a packing written by --packing-out instead of preparing (ensembles: member k reads FILE.member<k>)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--omega-hat", o->omega_hat, "override the scene's drive frequency omega_hat");
  cmd->add_option("--gamma-hat", o->gamma_hat, "override the scene's dashpot gamma_hat");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  return {cmd, [o]() {
    const MpiSession mpi;
    return mpi.run([&] { return run_forward(*o, mpi); });
  }};
}

}  // namespace sedwave::app
