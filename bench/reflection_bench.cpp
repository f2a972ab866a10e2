// Cost of the plane-wave reflection coefficient R(theta, f) (sediment/reflection.hpp): 90 grazing
// angles x 100 frequencies through 10 layers over a half-space, fluid layers and elastic layers,
// one core. The media are fixed numbers (no sediment model is evaluated): the cost is the
// reflectivity recursion's alone. Reported: the time of the whole grid, and (theta, f) points times
// layers per second (1e9 over it: ns per point per layer).
#include <benchmark/benchmark.h>

#include <complex>
#include <numbers>
#include <vector>

#include "sedwave/sediment/reflection.hpp"

namespace {

using sedwave::sediment::AcousticMedium;
using sedwave::sediment::LayeredHalfspace;
using sedwave::sediment::MediumLayer;

constexpr int kAngles = 90;
constexpr int kFrequencies = 100;
constexpr int kLayers = 10;

LayeredHalfspace stack(bool elastic) {
  LayeredHalfspace s;
  s.water = {1500.0, 0.0, 0.0, 0.0, 1025.0};
  for (int i = 0; i < kLayers; ++i) {
    s.layers.push_back({{1550.0 + 25.0 * i, 0.05 + 0.01 * i, elastic ? 100.0 + 20.0 * i : 0.0, elastic ? 1.0 : 0.0,
                         1600.0 + 40.0 * i},
                        0.5 + 0.2 * i});
  }
  s.halfspace = {2200.0, 0.02, elastic ? 900.0 : 0.0, elastic ? 0.1 : 0.0, 2300.0};
  return s;
}

void grid(benchmark::State& state, bool elastic) {
  const LayeredHalfspace seabed = stack(elastic);
  std::vector<double> angles;
  for (int i = 1; i <= kAngles; ++i) angles.push_back(i * std::numbers::pi / 180.0);
  for (auto _ : state) {
    for (int k = 0; k < kFrequencies; ++k) {
      const double f = 100.0 * (1.0 + k);  // 100 Hz - 10 kHz
      const std::vector<std::complex<double>> r = sedwave::sediment::reflection_coefficients(seabed, angles, f);
      benchmark::DoNotOptimize(r.data());
    }
  }
  // (theta, f) points times layers per second; 1e9 / this is the cost in ns per point per layer.
  state.counters["point_layers_per_s"] = benchmark::Counter(static_cast<double>(kAngles) * kFrequencies * kLayers,
                                                            benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ReflectionFluidLayers(benchmark::State& state) { grid(state, false); }
void BM_ReflectionElasticLayers(benchmark::State& state) { grid(state, true); }

BENCHMARK(BM_ReflectionFluidLayers)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReflectionElasticLayers)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
