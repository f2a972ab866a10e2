// Cost of the Bayesian answer on the shipped field data (data/field/zhou2009_regression.csv, 19
// observations): the posterior with its convergence diagnostics and the log evidence (parallel
// tempering, sedwave compare's ladder: 32 temperatures, 16 walkers, at a fixed 500 steps per
// temperature), and the plain posterior (a fixed 2000 steps), for a
// 3-parameter chain model, a 3D table (the long-wavelength table of five N = 10^4 packings, kappa and
// gamma free at d = 0.3 mm), and a Biot-type model, on 1 and 2 threads.
//   evidence/<model>/<threads>   one model_evidence() per iteration;
//   posterior/<model>/<threads>  one sample_posterior() per iteration.
// Counters: evals_per_s = likelihood evaluations per second of wall time; model_share = the time
// the model itself takes for those evaluations (measured separately, model_only/<model>) over the
// wall time, per thread: how much of the cost the sampler adds.
// Run: build/bin/bench_posterior --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/priors.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using namespace sedwave;

struct ModelCase {
  const char* label;
  std::string spec;
  const char* free;
  double diameter = 0.0;  ///< d [m] held fixed when > 0 (as docs/models/README.md fits the table)
};

const std::vector<ModelCase>& cases() {
  static const std::vector<ModelCase> all{
      {"lattice", "lattice", "kappa,d,gamma"},
      {"table", "table:" SEDWAVE_SOURCE_DIR "/data/tables/field_w3_long_wavelength.h5", "kappa,gamma", 3e-4},
      {"biot-stoll", "biot-stoll", "porosity,permeability,delta_b"},
  };
  return all;
}

/// The data, the model, its global fit and default priors: what a posterior starts from.
struct Problem {
  inversion::ObservationSet data;
  std::shared_ptr<const sediment::SedimentModel> model;
  inversion::FitOptions options{.method = inversion::FitMethod::Global, .profile_likelihood = false};
  inversion::FitResult best;
  std::vector<inversion::Prior> priors;
};

const Problem& problem(std::size_t which) {
  static std::vector<std::unique_ptr<Problem>> made(cases().size());
  if (!made[which]) {
    auto p = std::make_unique<Problem>();
    p->data = inversion::read_observation_csv(SEDWAVE_SOURCE_DIR "/data/field/zhou2009_regression.csv", {});
    p->model = sediment::make_sediment_model(cases()[which].spec);
    inversion::FitParameters start(p->model->parameters());
    start.set_free_from_list(cases()[which].free);
    if (cases()[which].diameter > 0.0) start.spec[start.index_of("d")].value = cases()[which].diameter;
    p->best = inversion::fit(p->data, *p->model, start, p->options);
    p->priors = inversion::make_priors(p->best.fitted, {});
    made[which] = std::move(p);
  }
  return *made[which];
}

/// Seconds the model alone takes per likelihood evaluation: every distinct observed frequency once.
double model_seconds_per_evaluation(const Problem& p) {
  std::set<double> distinct;
  for (const inversion::Observation& o : p.data.observations) distinct.insert(o.frequency_hz);
  const std::vector<double> values = p.best.fitted.values();
  const int repeats = 2000;
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) {
    for (double f : distinct) sink += p.model->evaluate(values, f, false).speed;
  }
  benchmark::DoNotOptimize(sink);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / repeats;
}

void model_only(benchmark::State& state) {
  const Problem& p = problem(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(model_seconds_per_evaluation(p));
  state.SetLabel(cases()[static_cast<std::size_t>(state.range(0))].label);
}

/// Runs `run(problem, threads)` once per iteration (a result with evaluations and wall_seconds) and
/// reports the evaluations per second and the model's share of the time.
template <class Run>
void time_sampler(benchmark::State& state, Run run) {
  const Problem& p = problem(static_cast<std::size_t>(state.range(0)));
  const int threads = static_cast<int>(state.range(1));
  long evaluations = 0;
  double wall = 0.0;
  for (auto _ : state) {
    const auto result = run(p, threads);
    evaluations += result.evaluations;
    wall += result.wall_seconds;
  }
  state.counters["evals_per_s"] = static_cast<double>(evaluations) / wall;
  state.counters["model_share"] = model_seconds_per_evaluation(p) * static_cast<double>(evaluations) / (wall * threads);
  state.SetLabel(cases()[static_cast<std::size_t>(state.range(0))].label);
}

void evidence(benchmark::State& state) {
  time_sampler(state, [](const Problem& p, int threads) {
    // A fixed length (compare's adapts to the data): the figures are a cost per evaluation.
    inversion::EvidenceOptions options;
    options.threads = threads;
    options.steps = 500;
    options.check_every = 0;
    return inversion::model_evidence(p.data, *p.model, p.best, p.priors, p.options, options);
  });
}

void posterior(benchmark::State& state) {
  time_sampler(state, [](const Problem& p, int threads) {
    inversion::PosteriorOptions options;
    options.threads = threads;
    options.steps = 2000;
    options.check_every = 0;
    return inversion::sample_posterior(p.data, *p.model, p.best, p.priors, p.options, options);
  });
}

}  // namespace

BENCHMARK(model_only)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond)->Iterations(3);
BENCHMARK(evidence)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(posterior)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
