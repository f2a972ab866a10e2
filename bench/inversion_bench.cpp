// Wall time of sedwave::inversion::fit on the shipped field data (data/field/zhou2009_regression.csv,
// 13 attenuation + 6 sound-speed-ratio rows), as `sedwave invert` runs it by default: kappa, d and
// gamma free from the default start values and bounds of FitParameters, default FitOptions except
// for the method and profile_likelihood.
//
// Benchmarks are named fit/<model>/<method>/profile:<0|1>:
//   model     continuum | lattice
//   method    ceres  (Levenberg-Marquardt from the start values)
//             nlopt  (DIRECT-L over the bounds, max_global_evaluations = 20000)
//             global (the NLopt search, a Ceres polish and a Ceres fit from the start values)
//   profile   0: the fit and its covariance/identifiability analysis only
//             1: plus profile-likelihood intervals of each free parameter
// Each run checks the fit: chi2 is reported as a counter and a non-finite chi2 is an error.
// Times are wall-clock (UseRealTime). Repetitions default to 5 (medians are what to quote); a
// --benchmark_repetitions=N on the command line overrides that.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/parameters.hpp"

#ifndef SEDWAVE_SOURCE_DIR
#error "SEDWAVE_SOURCE_DIR must be defined (bench/CMakeLists.txt sets it)"
#endif

namespace {

namespace inv = sedwave::inversion;

const inv::ObservationSet& field_data() {
  static const inv::ObservationSet data = inv::read_observation_csv(
      std::filesystem::path(SEDWAVE_SOURCE_DIR) / "data" / "field" / "zhou2009_regression.csv");
  return data;
}

const char* method_label(inv::FitMethod method) {
  switch (method) {
    case inv::FitMethod::Ceres: return "ceres";
    case inv::FitMethod::NLopt: return "nlopt";
    default: return "global";
  }
}

void bm_fit(benchmark::State& state, const std::string& model_name, inv::FitMethod method, bool profile) {
  const inv::ObservationSet& data = field_data();
  const std::unique_ptr<sedwave::forward::DispersionModel> model = sedwave::forward::make_dispersion_model(model_name);
  const inv::FitParameters parameters;  // kappa, d, gamma free from the default start values
  inv::FitOptions options;
  options.method = method;
  options.profile_likelihood = profile;

  double chi2 = 0.0;
  int evaluations = 0;
  bool converged = false;
  for (auto _ : state) {
    inv::FitResult result = inv::fit(data, *model, parameters, options);
    benchmark::DoNotOptimize(result);
    chi2 = result.chi2;
    converged = result.converged;
    evaluations = result.global ? result.global->evaluations : 0;
  }
  if (!std::isfinite(chi2)) {
    state.SkipWithError("fit returned a non-finite chi2");
    return;
  }
  state.counters["chi2"] = chi2;
  state.counters["converged"] = converged ? 1.0 : 0.0;
  state.counters["nlopt_evals"] = evaluations;
  state.counters["n_obs"] = static_cast<double>(data.observations.size());
}

bool repetitions_on_command_line(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--benchmark_repetitions", 23) == 0) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    (void)field_data();  // fail early, and outside the timings, if the file is missing or bad
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_inversion: cannot read the field data: %s\n", e.what());
    return 1;
  }
  const bool default_repetitions = !repetitions_on_command_line(argc, argv);
  for (const char* model : {"continuum", "lattice"}) {
    for (inv::FitMethod method : {inv::FitMethod::Ceres, inv::FitMethod::NLopt, inv::FitMethod::Global}) {
      for (bool profile : {false, true}) {
        const std::string name = std::string("fit/") + model + "/" + method_label(method) + "/profile:" +
                                 (profile ? "1" : "0");
        auto* b = benchmark::RegisterBenchmark(name.c_str(), bm_fit, std::string(model), method, profile);
        b->Unit(benchmark::kMillisecond)->UseRealTime()->ReportAggregatesOnly(true);
        if (default_repetitions) b->Repetitions(5);
      }
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
