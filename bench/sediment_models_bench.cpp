// Cost of every sediment model (sediment/catalog.hpp): ns per frequency point, values only and with
// the exact gradient (what a Ceres step needs), and the wall time of a local fit of the shipped field
// data (data/field/zhou2009_regression.csv, 19 observations) with each model's usual free parameters.
//
// Points cycle through 64 log-spaced frequencies 50 Hz - 100 kHz, so nothing is constant-folded.
// Run: build/bin/bench_sediment_models (docs/models/README.md quotes the medians of 5 repetitions:
// --benchmark_repetitions=5 --benchmark_report_aggregates_only=true).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using sedwave::sediment::SedimentModel;

struct ModelCase {
  const char* spec;
  const char* free;  ///< parameters fitted to the field data
};

// The free parameters each model's section of docs/models/README.md fits to the field data.
const ModelCase kCases[] = {
    {"lattice", "kappa,d,gamma"},
    {"saturated-lattice", "kappa,gamma,porosity,permeability"},
    {"biot-stoll", "K_b,delta_b,permeability"},
    {"edfm", "porosity,permeability"},
    {"grain-shearing", "gamma_p,n"},
    {"vgs-lambda", "gamma_p,n,tau_p"},
};

std::vector<double> frequencies() {
  std::vector<double> f;
  for (int i = 0; i < 64; ++i) f.push_back(50.0 * std::pow(2000.0, i / 63.0));
  return f;
}

void evaluate(benchmark::State& state, const char* spec, bool derivatives) {
  const std::shared_ptr<const SedimentModel> model = sedwave::sediment::make_sediment_model(spec);
  std::vector<double> values = model->default_values();
  if (std::string(spec) == "lattice" || std::string(spec) == "saturated-lattice") {
    values[0] = 5.0e5;  // kappa [N/m], d = 0.2 mm: a sand's frame
    values[2] = 10.0;   // gamma [kg/s]
  }
  const std::vector<double> f = frequencies();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model->evaluate(values, f[i++ & 63u], derivatives));
  }
}

void field_fit(benchmark::State& state, const ModelCase& c) {
  const auto data = sedwave::inversion::read_observation_csv(SEDWAVE_SOURCE_DIR "/data/field/zhou2009_regression.csv", {});
  const bool permeability = std::string(c.free).find("permeability") != std::string::npos;
  const auto model = sedwave::sediment::make_sediment_model(c.spec, {sedwave::sediment::DampingForm::Gamma, permeability});
  sedwave::inversion::FitParameters start(model->parameters());
  if (model->dimensionless_engine()) {  // a grain contact: kappa, d, gamma
    start.spec[start.index_of("kappa")].value = 5.0e5;
    start.spec[start.index_of("d")].value = 3.0e-4;
    start.spec[start.index_of("gamma")].value = 10.0;
  }
  start.set_free_from_list(c.free);
  sedwave::inversion::FitOptions options;
  options.method = sedwave::inversion::FitMethod::Ceres;
  options.profile_likelihood = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(sedwave::inversion::fit(data, *model, start, options));
}

}  // namespace

int main(int argc, char** argv) {
  for (const ModelCase& c : kCases) {
    benchmark::RegisterBenchmark((std::string(c.spec) + "/value").c_str(), evaluate, c.spec, false);
    benchmark::RegisterBenchmark((std::string(c.spec) + "/gradient").c_str(), evaluate, c.spec, true);
    benchmark::RegisterBenchmark((std::string(c.spec) + "/field_fit").c_str(), field_fit, c)
        ->Arg(0)->Arg(1)->ArgName("profiles")->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
