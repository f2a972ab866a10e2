// `sedwave forward`: one acoustic run of a channel scene: generate (or import) the packing,
// compress and relax it, drive it, measure alpha_hat and c_hat, write everything to HDF5.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "sedwave/forward/channel/run_file.hpp"
#include "sedwave/forward/channel/scene.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"

namespace sedwave::app {
namespace {

struct ForwardOptions {
  std::string scene;
  std::string out = "run.h5";
  std::string packing_in;
  std::string packing_out;
  std::optional<double> omega_hat;
  std::optional<double> gamma_hat;
  bool quiet = false;
};

/// The loose column from the scene (generated, or a LAMMPS data file), on rank 0 only.
forward::channel::ChannelConfiguration initial_column(const forward::channel::ChannelScene& scene, int rank) {
  using namespace forward::channel;
  if (rank != 0) return {};
  if (!scene.import_lammps_data) return generate_channel(scene.geometry);
  const forward::dem::LammpsData data = forward::dem::read_lammps_data(scene.import_lammps_data->string());
  ChannelConfiguration c;
  c.box = data.box;
  c.box.periodic = {true, true, false};
  for (forward::dem::Grain g : data.grains) {
    // Thesis convention: type 1 flow grains, 2 lower wall, 3 upper wall.
    g.group -= 1;
    if (g.group < kFlowGroup || g.group > kUpperWallGroup) {
      throw std::runtime_error(scene.import_lammps_data->string() + ": atom " + std::to_string(g.id) +
                               " has a type other than 1 (flow), 2 (lower wall) or 3 (upper wall)");
    }
    g.body = g.group == kLowerWallGroup ? kLowerWallBody : g.group == kUpperWallGroup ? kUpperWallBody : 0;
    c.grains.push_back(g);
  }
  return c;
}

int run_forward(const ForwardOptions& o) {
  using namespace forward::channel;
  const MpiSession mpi;
  ChannelScene scene = read_scene(o.scene);
  if (o.omega_hat) scene.drive.omega_hat = *o.omega_hat;
  if (o.gamma_hat) scene.drive.gamma_hat = *o.gamma_hat;
  const bool talk = mpi.rank() == 0 && !o.quiet;
  scene.preparation.log = talk ? &std::cout : nullptr;

  PreparedChannel packing;
  if (!o.packing_in.empty()) {
    if (mpi.rank() == 0) packing = read_packing(o.packing_in);
  } else {
    packing = prepare_channel(MPI_COMM_WORLD, initial_column(scene, mpi.rank()), scene.contact,
                              scene.geometry.width, scene.preparation);
    if (talk) std::cout << describe(packing.report) << "\n";
    if (mpi.rank() == 0 && !o.packing_out.empty()) {
      write_packing(o.packing_out, packing, scene.text);
      if (talk) std::cout << "packing written to " << o.packing_out << " (and .data for LAMMPS)\n";
    }
  }
  const AcousticResult r = run_acoustic(MPI_COMM_WORLD, packing, scene.contact, scene.drive);
  if (mpi.rank() == 0) {
    write_run_file(o.out, scene, packing.report, r);
    if (talk) {
      std::printf("omega_hat %.6g  gamma_hat %.6g\n", r.omega_hat, r.gamma_hat);
      if (r.ok()) {
        std::printf("alpha_hat %.6g +- %.2g   c_hat %.6g +- %.2g   (%d layers, %lld steps, %.1f s)\n", r.fit.alpha,
                    r.fit.sigma_alpha, r.fit.c, r.fit.sigma_c, r.layers_used, static_cast<long long>(r.steps),
                    r.wall_seconds);
      } else {
        std::printf("not measured: %s\n", r.problem.c_str());
      }
      std::printf("written to %s\n", o.out.c_str());
    }
  }
  return r.ok() ? 0 : 3;
}

}  // namespace

Command add_forward_command(CLI::App& app) {
  auto o = std::make_shared<ForwardOptions>();
  CLI::App* cmd = app.add_subcommand(
      "forward", "Run one acoustic channel simulation from a scene file (docs/scenes.md); MPI-parallel under mpirun");
  cmd->add_option("scene", o->scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "run file to write (HDF5)")->capture_default_str();
  cmd->add_option("--packing-out", o->packing_out, "also write the prepared packing (HDF5 + LAMMPS .data)");
  cmd->add_option("--packing", o->packing_in, "reuse a packing written by --packing-out instead of preparing")
      ->check(CLI::ExistingFile);
  cmd->add_option("--omega-hat", o->omega_hat, "override the scene's drive frequency omega_hat");
  cmd->add_option("--gamma-hat", o->gamma_hat, "override the scene's dashpot gamma_hat");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  return {cmd, [o]() { return run_forward(*o); }};
}

}  // namespace sedwave::app
