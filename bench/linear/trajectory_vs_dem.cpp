// The linearised equations integrated in time against the nonlinear DEM on the same packing, drive
// and time step: layer-averaged displacement records compared sample by sample
// (docs/linear.md, "Trajectories"). The difference is the nonlinearity of the contact network
// (geometry and contacts that open), so it should shrink in proportion to the amplitude.
//
//   bench_trajectory_vs_dem [--omega-hat W] [--gamma-hat G] [--periods P] [--kn KN | --hertz E] --amplitude A [...] [--steady-check] PACKING.h5
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/linear/linear_channel.hpp"
#include "bench_contact.hpp"
#include "../one_process_mpi.hpp"

int main(int argc, char** argv) {
  using namespace sedwave::forward;
  const sedwave::bench::OneProcessMpi mpi(argc, argv, "bench_trajectory_vs_dem");
  if (!mpi.alone()) return 2;
  channel::DriveSettings drive;
  drive.omega_hat = 0.6;
  drive.gamma_hat = 0.1;
  drive.far_end = channel::FarEnd::absorbing;
  drive.periods = 20.0;
  double kn = 726.0;
  double youngs_modulus = 0.0;  // > 0: Hertz contacts of this E (Poisson ratio 2/7, as the scenes)
  std::vector<double> amplitudes;
  bool steady_check = false;  // also print late-time layer amplitudes against the steady-state solve
  std::string file;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return std::atof(argv[++i]); };
    if (a == "--omega-hat") drive.omega_hat = next();
    else if (a == "--gamma-hat") drive.gamma_hat = next();
    else if (a == "--periods") drive.periods = next();
    else if (a == "--kn") kn = next();
    else if (a == "--hertz") youngs_modulus = next();
    else if (a == "--amplitude") amplitudes.push_back(next());
    else if (a == "--steady-check") steady_check = true;
    else file = a;
  }
  const dem::ContactSpec contact = sedwave::bench::bench_contact(kn, youngs_modulus);
  const channel::PreparedChannel packing = experiment::read_packing(file);
  const linear::LinearChannel engine(packing, contact);
  std::printf("omega_hat %g, gamma_hat %g, %g periods; layer displacement / A, linear (integrated) vs DEM\n",
              drive.omega_hat, drive.gamma_hat, drive.periods);
  std::printf("%-10s %8s %10s %14s %14s %14s %9s %9s\n", "A [d]", "steps", "opening", "max|dem|/A", "max|diff|/A",
              "rel. (layers 2-9)", "dem_s", "lin_s");
  for (const double a : amplitudes) {
    channel::DriveSettings d = drive;
    d.amplitude = a;
    const channel::AcousticResult dem = channel::run_acoustic(MPI_COMM_WORLD, packing, contact, d);
    const auto per_sample = static_cast<std::int64_t>(std::llround(dem.sample_dt / dem.time_step));
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::vector<double>> lin = engine.integrate(d, dem.time_step, dem.steps, per_sample);
    const double lin_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double peak = 0.0, diff = 0.0, near_peak = 0.0, near_diff = 0.0;
    for (std::size_t k = 0; k < lin.size() && k < dem.displacement.size(); ++k) {
      const std::size_t n = std::min(lin[k].size(), dem.displacement[k].size());
      for (std::size_t s = 0; s < n; ++s) {
        const double e = std::abs(lin[k][s] - dem.displacement[k][s]);
        peak = std::max(peak, std::abs(dem.displacement[k][s]));
        diff = std::max(diff, e);
        if (k >= 2 && k < 10) {
          near_peak = std::max(near_peak, std::abs(dem.displacement[k][s]));
          near_diff = std::max(near_diff, e);
        }
      }
    }
    if (steady_check) {  // late-time amplitude per layer: integrated, solved, DEM
      const linear::LinearResult steady = engine.respond(d);
      const std::size_t per_period = static_cast<std::size_t>(std::llround(2.0 * 3.141592653589793 / d.omega_hat / dem.sample_dt));
      for (std::size_t k = 2; k < 30 && k < lin.size(); k += 3) {
        double lo = 1e300, hi = -1e300, dlo = 1e300, dhi = -1e300;
        for (std::size_t s2 = lin[k].size() - 2 * per_period; s2 < lin[k].size(); ++s2) {
          lo = std::min(lo, lin[k][s2]); hi = std::max(hi, lin[k][s2]);
          dlo = std::min(dlo, dem.displacement[k][s2]); dhi = std::max(dhi, dem.displacement[k][s2]);
        }
        std::printf("#  layer %zu: integrated %.5g  solved %.5g  DEM %.5g\n", k, 0.5 * (hi - lo) / a,
                    std::abs(steady.layer_field[k]), 0.5 * (dhi - dlo) / a);
      }
    }
    const linear::StateChanges changes = engine.state_changes(engine.displacement(d), d, a);
    std::printf("%-10g %8lld %10lld %14.6g %14.6g %14.3g %9.1f %9.1f\n", a, static_cast<long long>(dem.steps),
                static_cast<long long>(changes.opening), peak / a, diff / a, near_diff / near_peak, dem.wall_seconds,
                lin_seconds);
    std::fflush(stdout);
  }
  return 0;
}
