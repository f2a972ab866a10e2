// The linear engine against the time-domain DEM on the same packings and drive: per packing and
// frequency, alpha_hat and c_hat from the steady-state solve and from a lock-in of a driven DEM run;
// then the ensemble means with their standard errors and the difference in units of the combined
// uncertainty (docs/linear.md, "Against the time-domain engine").
//
//   bench_linear_vs_dem [--gamma-hat G] [--amplitude A] [--absorbing-fraction F] [--periods P] [--kn KN | --hertz E] --omega-hat W [--omega-hat W...] PACKING.h5 ...
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/linear/ensemble.hpp"
#include "sedwave/forward/linear/linear_channel.hpp"
#include "bench_contact.hpp"
#include "../one_process_mpi.hpp"

int main(int argc, char** argv) {
  using namespace sedwave::forward;
  const sedwave::bench::OneProcessMpi mpi(argc, argv, "bench_linear_vs_dem");
  if (!mpi.alone()) return 2;
  channel::DriveSettings drive;
  drive.gamma_hat = 0.1;
  drive.far_end = channel::FarEnd::absorbing;
  double kn = 726.0;
  double youngs_modulus = 0.0;  // > 0: Hertz contacts of this E (Poisson ratio 2/7, as the scenes)
  std::vector<double> omegas;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return std::atof(argv[++i]); };
    if (a == "--omega-hat") omegas.push_back(next());
    else if (a == "--gamma-hat") drive.gamma_hat = next();
    else if (a == "--amplitude") drive.amplitude = next();
    else if (a == "--absorbing-fraction") drive.absorbing_fraction = next();
    else if (a == "--periods") drive.periods = next();  // DEM run length; default: until echoes could return
    else if (a == "--kn") kn = next();
    else if (a == "--hertz") youngs_modulus = next();
    else files.push_back(a);
  }
  const dem::ContactSpec contact = sedwave::bench::bench_contact(kn, youngs_modulus);
  std::vector<channel::PreparedChannel> packings;
  for (const std::string& f : files) packings.push_back(experiment::read_packing(f));

  std::printf("gamma_hat %g, amplitude %g d, %zu packings\n", drive.gamma_hat, drive.amplitude, packings.size());
  std::printf("%-9s %-7s %10s %9s %10s %9s %10s %9s %10s %9s %8s %8s   %s\n", "omega_hat", "packing", "lin_alpha", "+-",
              "dem_alpha", "+-", "lin_c", "+-", "dem_c", "+-", "lin_s", "dem_s",
              "[equivalent linearisation: alpha, c, iterations; contacts opening / gaps closing]");
  for (const double w : omegas) {
    channel::DriveSettings d = drive;
    d.omega_hat = w;
    std::vector<double> la, lc, da, dc, ea, ec;
    for (std::size_t k = 0; k < packings.size(); ++k) {
      const linear::LinearResult lin = linear::LinearChannel(packings[k], contact).respond(d);
      const linear::LinearResult eq = linear::LinearChannel(packings[k], contact).respond_equivalent(d);
      const channel::AcousticResult dem = channel::run_acoustic(MPI_COMM_WORLD, packings[k], contact, d);
      std::printf("%-9g %-7zu %10.5f %9.5f %10.5f %9.5f %10.5f %9.5f %10.5f %9.5f %8.3f %8.1f   [%.5f %.5f %d; %lld/%lld %lld/%lld] %s%s\n",
                  w, k, lin.fit.alpha, lin.fit.sigma_alpha, dem.fit.alpha, dem.fit.sigma_alpha, lin.fit.c, lin.fit.sigma_c,
                  dem.fit.c, dem.fit.sigma_c, lin.solve_seconds, dem.wall_seconds, eq.fit.alpha, eq.fit.c, eq.iterations,
                  static_cast<long long>(lin.state_changes.opening), static_cast<long long>(lin.state_changes.contacts),
                  static_cast<long long>(lin.state_changes.closing), static_cast<long long>(lin.state_changes.gaps),
                  lin.problem.c_str(), dem.problem.c_str());
      std::fflush(stdout);
      if (!lin.ok() || !dem.ok()) continue;
      la.push_back(lin.fit.alpha);
      lc.push_back(lin.fit.c);
      ea.push_back(eq.fit.alpha);
      ec.push_back(eq.fit.c);
      da.push_back(dem.fit.alpha);
      dc.push_back(dem.fit.c);
    }
    const auto stats = [](const std::vector<double>& v) { return linear::mean_and_standard_error(v); };
    const auto apart = [](const linear::MeanAndError& a, const linear::MeanAndError& b) {
      return std::abs(a.mean - b.mean) / std::hypot(a.standard_error, b.standard_error);
    };
    const linear::MeanAndError a1 = stats(la), a2 = stats(da), c1 = stats(lc), c2 = stats(dc);
    std::printf("%-9g mean    %10.5f %9.5f %10.5f %9.5f %10.5f %9.5f %10.5f %9.5f   alpha: %.2f sigma apart, c: %.2f "
                "sigma apart (%zu packings)\n",
                w, a1.mean, a1.standard_error, a2.mean, a2.standard_error, c1.mean, c1.standard_error, c2.mean,
                c2.standard_error, apart(a1, a2), apart(c1, c2), la.size());
    const linear::MeanAndError e1 = stats(ea), e2 = stats(ec);
    std::printf("%-9g equivalent linearisation: alpha %.5f +- %.5f (%.2f sigma from DEM), c %.5f +- %.5f (%.2f sigma "
                "from DEM)\n",
                w, e1.mean, e1.standard_error, apart(e1, a2), e2.mean, e2.standard_error, apart(e2, c2));
    std::fflush(stdout);
  }
  return 0;
}
