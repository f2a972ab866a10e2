// Does a dispersion table determine the grain size d? Synthetic lab data are drawn from one table
// (DATA_TABLE) at known kappa, d and gamma, and fitted with another (FIT_TABLE: the same, or one
// made from disjoint packings, so the fit also sees packing-to-packing model error) and with the
// 1D continuum and lattice theories. Prints one row per damping, band and noise seed (docs/inversion.md, "Does a
// 3D table determine d?").
//
//   bench_diameter_identifiability DATA_TABLE.h5 FIT_TABLE.h5 [ALPHA_NOISE SPEED_NOISE]
//
// Truth: kappa = 2.8e6 N/m, d = 0.3 mm, rho_s = 2650 kg/m^3; gamma from gamma_hat. Bands: 12
// log-spaced frequencies over omega_hat = top/6 .. top. Units: SI in the output.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include <glog/logging.h>

#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/table_model.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/synthetic.hpp"

int main(int argc, char** argv) {
  using namespace sedwave;
  using namespace sedwave::inversion;
  FLAGS_minloglevel = google::GLOG_FATAL;  // Ceres logs every step a table refuses; the fits report it
  if (argc != 3 && argc != 5) {
    std::fprintf(stderr, "usage: %s DATA_TABLE.h5 FIT_TABLE.h5 [ALPHA_NOISE SPEED_NOISE]\n", argv[0]);
    return 1;
  }
  const forward::table::TableModel source(forward::table::read_table(argv[1]), "data table");
  const forward::table::TableModel table(forward::table::read_table(argv[2]), "fit table");
  const forward::ContinuumModel continuum;
  const forward::LatticeModel lattice;
  const double alpha_noise = argc == 5 ? std::atof(argv[3]) : 0.1;
  const double speed_noise = argc == 5 ? std::atof(argv[4]) : 0.01;
  const forward::GrainScales<double> scales{2.8e6, 3.0e-4, 2650.0};
  const double to_hz = 1.0 / (2.0 * std::numbers::pi * scales.time_scale());
  std::printf("noise: attenuation %g, sound speed %g (relative); truth d = %g m\n", alpha_noise, speed_noise,
              scales.diameter);
  std::printf("%9s %13s %4s | %-33s | %-20s | %-33s\n", "", "", "", "table", "continuum", "lattice");
  std::printf("%9s %13s %4s | %6s %9s %9s %4s | %6s %9s %4s | %6s %9s %9s %4s\n", "gamma_hat", "band [kHz]", "seed",
              "chi2", "d [m]", "+-", "det", "chi2", "d [m]", "det", "chi2", "d [m]", "+-", "det");
  for (const double gamma_hat : {1.0, 3.0, 10.0, 19.0, 50.0}) {
    for (const double top : {0.6, 0.95}) {
      for (const unsigned seed : {1u, 2u, 3u}) {
        FitParameters truth;
        truth.spec[truth.index_of("kappa")].value = scales.kappa;
        truth.spec[truth.index_of("d")].value = scales.diameter;
        truth.spec[truth.index_of("gamma")].value = scales.gamma(gamma_hat);
        const SyntheticDesign band{top / 6.0 * to_hz, top * to_hz, 12, alpha_noise, speed_noise, seed};
        const ObservationSet data = synthetic_observations(source, truth, band);
        FitParameters start = truth;
        start.spec[start.index_of("kappa")].value *= 0.9;
        start.spec[start.index_of("d")].value *= 0.9;
        start.spec[start.index_of("gamma")].value *= 1.2;
        const FitResult r = fit(data, table, start, FitOptions{.method = FitMethod::Ceres});
        const FitResult c = fit(data, continuum, start, FitOptions{.method = FitMethod::Global});
        const FitResult l = fit(data, lattice, start, FitOptions{.method = FitMethod::Global});
        const ParameterResult& d = inversion::by_name(r.parameters, "d");
        const ParameterResult& dl = inversion::by_name(l.parameters, "d");
        std::printf("%9g %6.0f-%6.0f %4u | %6.1f %9.3g %9.2g %4s | %6.1f %9.3g %4s | %6.1f %9.3g %9.2g %4s\n", gamma_hat,
                    band.lowest_hz / 1e3, band.highest_hz / 1e3, seed, r.chi2, d.value, d.sigma, d.determined ? "yes" : "no",
                    c.chi2, inversion::by_name(c.parameters, "d").value, inversion::by_name(c.parameters, "d").determined ? "yes" : "no", l.chi2,
                    dl.value, dl.sigma, dl.determined ? "yes" : "no");
      }
    }
  }
  return 0;
}
