// Sampler overhead per log-density evaluation (sampling/ensemble.hpp), on a density so cheap that
// nearly all the time is the sampler's: the isotropic Gaussian -|x|^2 / 2 in 2, 5 and 10 dimensions.
//   sample/<dim>        one sample() run (default walkers, 1000 updates) per iteration;
//                       items = log-density evaluations, so items_per_second is evaluations per second
//                       and 1 / that is the time per evaluation, density included;
//   bare_density/<dim>  the same density called through the same std::function on stored points:
//                       its time per call is the density's share; the difference is the overhead.
//   diagnose/<dim>      diagnose() of a run's chains (R-hat, tau, ESS), per kept draw.
#include <benchmark/benchmark.h>

#include <vector>

#include "sedwave/sampling/diagnostics.hpp"
#include "sedwave/sampling/ensemble.hpp"

namespace {

using sedwave::sampling::EnsembleOptions;
using sedwave::sampling::LogDensity;

const LogDensity kCheapDensity = [](const Eigen::VectorXd& x) { return -0.5 * x.squaredNorm(); };

EnsembleOptions bench_options() {
  EnsembleOptions options;
  options.steps = 1000;
  return options;
}

sedwave::sampling::EnsembleRun run_once(int dim) {
  const EnsembleOptions options = bench_options();
  return sedwave::sampling::sample(
      kCheapDensity,
      sedwave::sampling::start_ball(Eigen::VectorXd::Zero(dim), Eigen::VectorXd::Ones(dim), options), options);
}

void sample(benchmark::State& state) {
  const auto dim = static_cast<int>(state.range(0));
  long evaluations = 0;
  for (auto _ : state) {
    const sedwave::sampling::EnsembleRun run = run_once(dim);
    benchmark::DoNotOptimize(run.chains.data());
    evaluations += run.evaluations;
  }
  state.SetItemsProcessed(evaluations);
}

void bare_density(benchmark::State& state) {
  const auto dim = static_cast<int>(state.range(0));
  std::vector<Eigen::VectorXd> points;
  for (int i = 0; i < 64; ++i) points.push_back(Eigen::VectorXd::Constant(dim, 0.01 * i));
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(kCheapDensity(points[next]));
    next = (next + 1) % points.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void diagnose(benchmark::State& state) {
  const sedwave::sampling::EnsembleRun run = run_once(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sedwave::sampling::diagnose(run).ess.data());
  state.SetItemsProcessed(state.iterations() * static_cast<long>(run.chains.size() * run.chains.front().rows()));
}

}  // namespace

BENCHMARK(sample)->Arg(2)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond);
BENCHMARK(bare_density)->Arg(2)->Arg(5)->Arg(10);
BENCHMARK(diagnose)->Arg(2)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
