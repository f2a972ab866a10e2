// Cost of the granular-solid interface's plate against hand-written lumped Q4 updates of the same
// mesh (element by element and by node stencil), and ns per grain-step of whole interface runs
// (docs/performance.md, "The plate's step against a hand-written lumped Q4 update"). Example 11's
// scene is read from the source tree the build was configured from:
//
//   build-dev/bin/bench_interface_plate --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Meshes: example 11's 120 x 40 elements and a 480 x 160 one (16 times the nodes).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "sedwave/forward/experiment/interface_run.hpp"
#include "sedwave/forward/experiment/interface_scene.hpp"
#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/plate/elastic_plate.hpp"

namespace {

namespace plate = sedwave::forward::plate;
namespace interface = sedwave::forward::interface;
namespace experiment = sedwave::forward::experiment;

// Example 11's aluminium plate (0.12 m x 0.04 m, 5 mm thick), free on top, absorbing elsewhere.
plate::ElasticPlate example_plate(int elements_x, int elements_y) {
  const plate::PlateMaterial aluminium{70e9, 0.33, 2700.0, 5e-3};
  const plate::PlateEdges edges{plate::EdgeCondition::free, plate::EdgeCondition::absorbing,
                                plate::EdgeCondition::absorbing, plate::EdgeCondition::absorbing};
  return plate::ElasticPlate(aluminium, {elements_x, elements_y, 0.12, 0.04}, edges);
}

// A smooth displacement and velocity field of 1 um, so that no arithmetic meets zeros or denormals.
void smooth_field(const plate::ElasticPlate& p, std::vector<double>& u, std::vector<double>& v) {
  u.assign(static_cast<std::size_t>(p.dof_count()), 0.0);
  v = u;
  for (int n = 0; n < p.node_count(); ++n) {
    const double x = p.node_x(n) / 0.12, y = p.node_y(n) / 0.04;
    u[static_cast<std::size_t>(2 * n)] = 1e-6 * std::sin(3.0 * x) * std::cos(2.0 * y);
    u[static_cast<std::size_t>(2 * n + 1)] = 1e-6 * std::cos(5.0 * x) * std::sin(1.0 + y);
    v[static_cast<std::size_t>(2 * n + 1)] = 1e-3 * std::sin(7.0 * x + y);
  }
}

// (i) The interface's plate update: one velocity-Verlet step of a GranularPlate without grains
// (half kick, drift, internal forces, half kick with the edge dashpots and the energy books).
void BM_InterfacePlateStep(benchmark::State& state) {
  auto p = example_plate(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const double dt = 0.5 * p.stable_time_step();
  const int dofs = p.dof_count();
  interface::StepControl control;
  control.fixed_step = dt;
  interface::GranularPlate run({}, {200e9, 0.3}, std::move(p), {}, control);
  smooth_field(*run.plate(), run.plate_displacement_mutable(), run.plate_velocity_mutable());
  run.refresh_forces();
  for (auto _ : state) {
    run.step();
    benchmark::DoNotOptimize(run.plate_velocity().data());
  }
  state.counters["per_node"] = benchmark::Counter(static_cast<double>(dofs / 2) * static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// (ii) The reference: a hand-written lumped Q4 leapfrog update of the same mesh, f = -K u element by
// element with the precomputed 8x8 element stiffness, v += dt f / m (inverse masses, zero where a
// degree of freedom is held), u += dt v. No dashpots and no energy books: the least a step can do.
struct HandQ4 {
  int elements_x, elements_y;
  std::array<double, 64> k;  // rows and columns ordered (i,j), (i+1,j), (i,j+1), (i+1,j+1), x then y
  std::vector<double> inverse_mass, u, v, f;

  explicit HandQ4(const plate::ElasticPlate& p)
      : elements_x(p.mesh().elements_x), elements_y(p.mesh().elements_y), k{} {
    // The plate's element order is counter-clockwise (lower left, lower right, upper right, upper
    // left); reorder it so that an element's 8 unknowns are 4 consecutive values in each node row.
    const int order[4] = {0, 1, 3, 2};
    const auto& ke = p.element_stiffness();
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        k[static_cast<std::size_t>(8 * a + b)] = ke(2 * order[a / 2] + a % 2, 2 * order[b / 2] + b % 2);
    inverse_mass.resize(p.mass().size());
    for (std::size_t d = 0; d < inverse_mass.size(); ++d) inverse_mass[d] = p.fixed()[d] ? 0.0 : 1.0 / p.mass()[d];
    smooth_field(p, u, v);
    f.assign(u.size(), 0.0);
  }

  void forces() {
    std::fill(f.begin(), f.end(), 0.0);
    const std::size_t row = 2 * static_cast<std::size_t>(elements_x + 1);
    for (int j = 0; j < elements_y; ++j) {
      const double* lower_u = u.data() + static_cast<std::size_t>(j) * row;
      double* lower_f = f.data() + static_cast<std::size_t>(j) * row;
      for (int i = 0; i < elements_x; ++i) {
        double ue[8];
        for (int c = 0; c < 4; ++c) {
          ue[c] = lower_u[2 * i + c];
          ue[4 + c] = lower_u[row + 2 * static_cast<std::size_t>(i) + c];
        }
        for (int a = 0; a < 8; ++a) {
          double s = 0.0;
          for (int b = 0; b < 8; ++b) s += k[static_cast<std::size_t>(8 * a + b)] * ue[b];
          lower_f[(a < 4 ? 0 : row) + 2 * static_cast<std::size_t>(i) + a % 4] -= s;
        }
      }
    }
  }

};

// The same update by a hand-written node stencil: the 2 x 18 block that an interior node's four
// elements sum to, applied to its 3 x 3 neighbourhood, and the border nodes from their elements'
// rows. Checked against the element-by-element forces before it is timed.
struct HandStencil : HandQ4 {
  std::array<double, 36> stencil{};  // row r (x, y) of the node, column 6 (dy + 1) + 2 (dx + 1) + c

  explicit HandStencil(const plate::ElasticPlate& p) : HandQ4(p) {
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c)
            stencil[static_cast<std::size_t>(18 * r + 6 * (b / 2 - a / 2 + 1) + 2 * (b % 2 - a % 2 + 1) + c)] +=
                k[static_cast<std::size_t>(8 * (2 * a + r) + 2 * b + c)];
  }

  void border_node(int i, int j, std::size_t row) {
    for (int a = 0; a < 4; ++a) {
      const int ei = i - a % 2, ej = j - a / 2;
      if (ei < 0 || ei >= elements_x || ej < 0 || ej >= elements_y) continue;
      const double* lower = u.data() + static_cast<std::size_t>(ej) * row + static_cast<std::size_t>(2 * ei);
      for (int r = 0; r < 2; ++r) {
        double s = 0.0;
        for (int b = 0; b < 8; ++b)
          s += k[static_cast<std::size_t>(8 * (2 * a + r) + b)] * lower[(b < 4 ? 0 : row) + static_cast<std::size_t>(b % 4)];
        f[static_cast<std::size_t>(j) * row + static_cast<std::size_t>(2 * i + r)] -= s;
      }
    }
  }

  /// body(below, out, left) for each interior node: its 3 x 3 neighbourhood starts at below + left
  /// (three rows of six values, row apart), its force at out + left + 2.
  template <class Body>
  void each_interior_node(Body body) {
    const std::size_t row = 2 * static_cast<std::size_t>(elements_x + 1);
    for (int j = 1; j < elements_y; ++j) {
      const double* below = u.data() + static_cast<std::size_t>(j - 1) * row;
      double* out = f.data() + static_cast<std::size_t>(j) * row;
      for (int i = 1; i < elements_x; ++i) body(below, out, static_cast<std::size_t>(2 * (i - 1)));
    }
  }

  void forces() {
    const std::size_t row = 2 * static_cast<std::size_t>(elements_x + 1);
    each_interior_node([&](const double* below, double* out, std::size_t left) {
      double sx = 0.0, sy = 0.0;
      for (std::size_t level = 0; level < 3; ++level)
        for (std::size_t c = 0; c < 6; ++c) {
          const double value = below[level * row + left + c];
          sx += stencil[6 * level + c] * value;
          sy += stencil[18 + 6 * level + c] * value;
        }
      out[left + 2] = -sx;
      out[left + 3] = -sy;
    });
    border();
  }

  void border() {
    const std::size_t row = 2 * static_cast<std::size_t>(elements_x + 1);
    for (int i = 0; i <= elements_x; ++i) {
      for (const int j : {0, elements_y}) {
        f[static_cast<std::size_t>(j) * row + 2 * static_cast<std::size_t>(i)] = 0.0;
        f[static_cast<std::size_t>(j) * row + 2 * static_cast<std::size_t>(i) + 1] = 0.0;
        border_node(i, j, row);
      }
    }
    for (int j = 1; j < elements_y; ++j)
      for (const int i : {0, elements_x}) {
        f[static_cast<std::size_t>(j) * row + 2 * static_cast<std::size_t>(i)] = 0.0;
        f[static_cast<std::size_t>(j) * row + 2 * static_cast<std::size_t>(i) + 1] = 0.0;
        border_node(i, j, row);
      }
  }

};

// The library's previous interior kernel, kept here to be timed beside the present one: the general
// 2 x 18 stencil as an Eigen product per node, its 18 displacements gathered from three node rows.
struct PreviousKernel : HandStencil {
  Eigen::Matrix<double, 2, 18> matrix;

  explicit PreviousKernel(const plate::ElasticPlate& p) : HandStencil(p) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 18; ++c) matrix(r, c) = stencil[static_cast<std::size_t>(18 * r + c)];
  }

  void forces() {
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    const std::size_t row = 2 * static_cast<std::size_t>(elements_x + 1);
    each_interior_node([&](const double* below, double* out, std::size_t left) {
      Eigen::Matrix<double, 18, 1> around;
      around << Eigen::Map<const Vec6>(below + left), Eigen::Map<const Vec6>(below + row + left),
          Eigen::Map<const Vec6>(below + 2 * row + left);
      Eigen::Map<Eigen::Vector2d>(out + left + 2) = -(matrix * around);
    });
    border();
  }

};

/// A hand-written update of the plate; a stencil is checked against the element products first.
template <class Hand>
Hand hand_update(const plate::ElasticPlate& p) {
  Hand hand(p);
  if constexpr (!std::is_same_v<Hand, HandQ4>) {
    HandQ4 elements(p);
    hand.forces();
    elements.forces();
    double largest = 0.0, worst = 0.0;
    for (std::size_t d = 0; d < hand.f.size(); ++d) {
      largest = std::max(largest, std::abs(elements.f[d]));
      worst = std::max(worst, std::abs(hand.f[d] - elements.f[d]));
    }
    if (!(worst <= 1e-12 * largest)) throw std::logic_error("bench: a stencil's forces are not the elements'");
  }
  return hand;
}

/// One lumped leapfrog step of a hand-written update: v += dt f / m, u += dt v.
template <class Hand>
void leapfrog_step(Hand& hand, double dt) {
  hand.forces();
  for (std::size_t d = 0; d < hand.u.size(); ++d) {
    hand.v[d] += dt * hand.f[d] * hand.inverse_mass[d];
    hand.u[d] += dt * hand.v[d];
  }
}

template <class Hand>
void BM_HandStep(benchmark::State& state) {
  const auto p = example_plate(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Hand hand = hand_update<Hand>(p);
  const double dt = 0.5 * p.stable_time_step();
  for (auto _ : state) {
    leapfrog_step(hand, dt);
    benchmark::DoNotOptimize(hand.u.data());
  }
  state.counters["per_node"] = benchmark::Counter(static_cast<double>(p.node_count()) * static_cast<double>(state.iterations()),
                                                  benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

template <class Hand>
void BM_HandForces(benchmark::State& state) {
  const auto p = example_plate(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Hand hand = hand_update<Hand>(p);
  for (auto _ : state) {
    hand.forces();
    benchmark::DoNotOptimize(hand.f.data());
  }
}

// The interface's internal forces alone: f = -K u, checked against the element products first.
void BM_InterfacePlateForces(benchmark::State& state) {
  const auto p = example_plate(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::vector<double> u, v;
  smooth_field(p, u, v);
  std::vector<double> f(u.size());
  HandQ4 elements(p);
  elements.forces();
  p.elastic_forces(u, f);
  double largest = 0.0, worst = 0.0;
  for (std::size_t d = 0; d < f.size(); ++d) {
    largest = std::max(largest, std::abs(elements.f[d]));
    worst = std::max(worst, std::abs(f[d] - elements.f[d]));
  }
  if (!(worst <= 1e-12 * largest)) throw std::logic_error("bench: the plate's forces are not the elements'");
  state.counters["max_diff_rel"] = worst / largest;  // round-off against the element-by-element sum
  for (auto _ : state) {
    p.elastic_forces(u, f);
    benchmark::DoNotOptimize(f.data());
  }
}

// The multirate scheme's fast internal forces, those of the top row of elements alone, added to f
// at every substep (granular_plate.cpp).
void BM_InterfaceTopRowForces(benchmark::State& state) {
  const auto p = example_plate(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  std::vector<double> u, v;
  smooth_field(p, u, v);
  std::vector<double> f(u.size(), 0.0);
  for (auto _ : state) {
    p.add_top_row_forces(u, f);
    benchmark::DoNotOptimize(f.data());
  }
}

#ifndef SEDWAVE_SOURCE_DIR
#define SEDWAVE_SOURCE_DIR "."
#endif

std::string example_11() {
  std::ifstream in(std::string(SEDWAVE_SOURCE_DIR) + "/examples/11-granular-plate/scene.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("bench: '" + from + "' not in example 11's scene");
  return text.replace(at, from.size(), to);
}

// (iii) Whole runs, in ns per grain-step (the run's wall time over steps times grains). Example 11
// as shipped (200 beads, 4800 elements: mostly plate); and the granular medium alone, 1000 beads on
// a 4 x 2-element plate, frictionless (bench/interface/cost.sh's last row).
void run_scene(benchmark::State& state, const std::string& text) {
  const auto scene = experiment::parse_interface_scene(text, "bench");
  double grain_steps = 0.0;
  for (auto _ : state) {
    const auto run = experiment::run_interface(scene, nullptr);
    grain_steps += static_cast<double>(run.series.steps.back()) * static_cast<double>(run.final_grains.size());
    benchmark::DoNotOptimize(run.series.steps.data());
  }
  state.counters["per_grain_step"] =
      benchmark::Counter(grain_steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Example11(benchmark::State& state) { run_scene(state, example_11()); }

void BM_GrainsOnly(benchmark::State& state) {
  std::string s = example_11();
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"length_x = 0.12 ", "length_x = 0.26 "}, {"elements_x = 120 ", "elements_x = 4 "},
        {"elements_y = 40", "elements_y = 2"}, {"rows = 10\n", "rows = 20\n"}, {"columns = 20\n", "columns = 50\n"},
        {"friction = 0.3\n", "friction = 0.0\n"}, {"duration = 3e-4\n", "duration = 4.4e-3\n"},
        {"output_interval = 5e-7", "output_interval = 2.2e-4"}, {"probe_x = [0.03, 0.06, 0.09]", "probe_x = [0.13]"}})
    s = replaced(s, from, to);
  run_scene(state, s);
}

}  // namespace

BENCHMARK(BM_InterfacePlateStep)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandStep, HandQ4)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandStep, HandStencil)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandStep, PreviousKernel)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InterfacePlateForces)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandForces, HandQ4)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandForces, HandStencil)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_HandForces, PreviousKernel)->Args({120, 40})->Args({480, 160})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InterfaceTopRowForces)->Args({120, 40})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Example11)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_GrainsOnly)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
