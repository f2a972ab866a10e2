// Newton relaxation of a prepared packing (linear/static_equilibrium.hpp): how far it gets, in how
// many trial steps and solves, and how long it takes. The frozen walls stay where they are.
//
//   bench_relax SCENE.toml PACKING.h5 [MAX_TRIAL_STEPS]      (default 100)
//
// SCENE gives the contact law; PACKING is any packing file (e.g. written with --packing-out from a
// scene with newton_relaxation = false and a loose residual_force_tolerance, i.e. FIRE's state).
// Prints one line: grains, trial steps (accepted), solves, the final largest residual force over the
// mean contact force, the energy released, and the wall-clock time.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/experiment/scene.hpp"
#include "sedwave/forward/linear/static_equilibrium.hpp"
#include "../one_process_mpi.hpp"

int main(int argc, char** argv) {
  using namespace sedwave::forward;
  const sedwave::bench::OneProcessMpi mpi(argc, argv, "bench_relax");
  if (!mpi.alone()) return 2;
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_relax SCENE.toml PACKING.h5 [MAX_TRIAL_STEPS]\n");
    return 2;
  }
  const experiment::ChannelScene scene = experiment::read_scene(argv[1]);
  channel::PreparedChannel packing = experiment::read_packing(argv[2]);
  linear::StaticEquilibriumSettings settings;
  settings.max_iterations = argc > 3 ? std::stoi(argv[3]) : 100;
  const auto start = std::chrono::steady_clock::now();
  const linear::StaticEquilibriumReport r =
      linear::relax_to_equilibrium(packing.grains, packing.box, scene.contact, 2, nullptr, settings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("grains %zu: %d trial steps (%d accepted), %d solves, residual ratio %.3e, energy released %.3e, %s, %.1f s\n",
              packing.grains.size(), r.iterations, r.accepted, r.directions, r.residual_ratio, r.energy_drop,
              r.converged ? "converged" : "NOT converged", seconds);
  return r.converged ? 0 : 1;
}
