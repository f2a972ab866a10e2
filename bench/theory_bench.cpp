// ns per evaluation of the 1D chain theories (forward/theory/continuum.hpp, lattice.hpp).
//
// Three ways to evaluate each model, in every (omega_hat, gamma_hat) regime:
//   <model>/value_ref   the bare complex formula, written inline here: VALUE-ONLY REFERENCE, not
//                       library code (continuum k = w / sqrt(1 - i w g); lattice k = 2 asin(k_c / 2));
//   <model>/wavenumber  the library's free function (continuum_wavenumber / lattice_wavenumber):
//                       complex k plus its two exact partial derivatives, with input checks;
//   <model>/evaluate    DispersionModel::evaluate through the base class (virtual call, as the
//                       inversion makes it): alpha_hat, c_hat and their exact gradients.
// Regimes are named by x = omega_hat * gamma_hat (the dashpot's importance); for the lattice also
// above the undamped cutoff omega_hat = 2 (evanescent band), damped and undamped.
//
// Each iteration evaluates one point; the points cycle through 64 inputs scattered by up to +/-10 %
// around the regime's centre, so nothing is constant-folded and branch patterns are not trivial.
// Successive iterations are independent, so the times are throughput (ns per evaluation with
// out-of-order overlap), not latency.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace {

using sedwave::forward::DispersionModel;
using cd = std::complex<double>;

struct Regime {
  std::string name;
  double omega_hat;
  double gamma_hat;
};

struct Input {
  double omega_hat;
  double gamma_hat;
};

constexpr std::size_t kInputs = 64;  // power of two: index with & (kInputs - 1)
using Inputs = std::array<Input, kInputs>;

Inputs make_inputs(const Regime& regime) {
  std::mt19937_64 rng(0x5edbe11c);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  Inputs inputs{};
  for (Input& in : inputs) {
    in.omega_hat = regime.omega_hat * (1.0 + jitter(rng));
    in.gamma_hat = regime.gamma_hat * (1.0 + jitter(rng));  // stays 0 for an undamped regime
  }
  return inputs;
}

// Value-only references: the textbook complex formulas, no derivatives, no input checks.
cd continuum_value_ref(double omega_hat, double gamma_hat) {
  return omega_hat / std::sqrt(cd(1.0, -omega_hat * gamma_hat));
}
cd lattice_value_ref(double omega_hat, double gamma_hat) {
  return 2.0 * std::asin(0.5 * continuum_value_ref(omega_hat, gamma_hat));
}

template <typename F>
void run_points(benchmark::State& state, const Regime& regime, F&& f) {
  Inputs inputs = make_inputs(regime);
  benchmark::DoNotOptimize(inputs.data());
  benchmark::ClobberMemory();
  std::size_t i = 0;
  for (auto _ : state) {
    const Input& in = inputs[i++ & (kInputs - 1)];
    auto result = f(in.omega_hat, in.gamma_hat);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void register_model(const std::string& model_name, const std::vector<Regime>& regimes, cd (*value_ref)(double, double),
                    sedwave::forward::ComplexWavenumber (*wavenumber)(double, double)) {
  // One model object shared by all its benchmarks; evaluate() is called through the base class
  // reference, so the call stays virtual as in the inversion.
  std::shared_ptr<const DispersionModel> model = sedwave::forward::make_dispersion_model(model_name);
  for (const Regime& regime : regimes) {
    benchmark::RegisterBenchmark((model_name + "/value_ref/" + regime.name).c_str(),
                                 [regime, value_ref](benchmark::State& state) { run_points(state, regime, value_ref); });
    benchmark::RegisterBenchmark((model_name + "/wavenumber/" + regime.name).c_str(),
                                 [regime, wavenumber](benchmark::State& state) { run_points(state, regime, wavenumber); });
    benchmark::RegisterBenchmark((model_name + "/evaluate/" + regime.name).c_str(),
                                 [regime, model](benchmark::State& state) {
                                   const DispersionModel& m = *model;
                                   run_points(state, regime, [&m](double w, double g) { return m.evaluate(w, g); });
                                 });
  }
}

}  // namespace

int main(int argc, char** argv) {
  // x = omega_hat * gamma_hat: 1e-4 (elastic), ~1 (crossover), 1e4 (dashpot-dominated).
  const std::vector<Regime> common{
      {"x=1e-4", 1.0e-2, 1.0e-2},
      {"x=1", 0.5, 2.0},
      {"x=1e4", 0.5, 2.0e4},
  };
  std::vector<Regime> lattice = common;
  lattice.push_back({"cutoff,w=3,x=3e-3", 3.0, 1.0e-3});  // above omega_hat = 2, damped
  lattice.push_back({"cutoff,w=3,x=0", 3.0, 0.0});        // above omega_hat = 2, undamped
  register_model("continuum", common, continuum_value_ref, sedwave::forward::continuum_wavenumber);
  register_model("lattice", lattice, lattice_value_ref, sedwave::forward::lattice_wavenumber);

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
