// Interpolation error and speed of the table model's two schemes (docs/tables.md, "Direct or
// correction interpolation"):
//   direct      the Hermite surface of ln alpha_hat, ln c_hat;
//   correction  the same surface of ln(table / lattice theory), the theory's exact values added back.
//
// Error: leave one grid line out. For every interior omega_hat column (and then every interior
// gamma_hat row) the model is built from the table without that line and compared with the table at
// the line's ok points: |model - table| in units of the point's own sigma (z) and as a relative error.
// The held-back point is interpolated over twice the local spacing, so these errors bound the
// table's own interpolation error from above (third order: about 8x smaller at the table's spacing).
// Points whose widened cell has a non-ok corner are not answered by either scheme and are counted.
// Tables: the shipped 3D tables and two made from the 1D theories (their values are exact, so the
// error is the true one): the lattice theory (correction identically 0) and the continuum theory.
//
// Speed (Google Benchmark, after the error tables): ns per TableModel::evaluate (values, exact
// derivatives, sigmas) cycling through 64 points inside ok cells, and the lattice theory alone.
// `--no-speed` prints the error tables only. Benchmark flags (--benchmark_repetitions=...) pass on.
//
//   build/bin/bench_table_interpolation [--no-speed]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/table_model.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace {

using sedwave::forward::ContinuumModel;
using sedwave::forward::DispersionModel;
using sedwave::forward::DispersionPoint;
using sedwave::forward::LatticeModel;
using namespace sedwave::forward::table;

std::string source(const std::string& relative) { return std::string(SEDWAVE_SOURCE_DIR) + "/" + relative; }

DispersionTable theory_table(const DispersionModel& theory, const TableGrid& grid) {
  DispersionTable table(grid, {"", "theory:" + theory.name(), "", "", ""});
  for (std::size_t g = 0; g < table.n_gamma(); ++g) {
    for (std::size_t w = 0; w < table.n_omega(); ++w) {
      const DispersionPoint p = theory.evaluate(grid.omega_hat[w], grid.gamma_hat[g]);
      table.set(g, w, {PointStatus::ok, p.alpha_hat, p.c_hat, 0.0, 0.0, 0.0, ""});
    }
  }
  return table;
}

/// The table without omega_hat column `skip_w` (or gamma_hat row `skip_g`); npos keeps all.
DispersionTable without_line(const DispersionTable& table, std::size_t skip_w, std::size_t skip_g) {
  TableGrid grid;
  for (std::size_t w = 0; w < table.n_omega(); ++w) {
    if (w != skip_w) grid.omega_hat.push_back(table.grid().omega_hat[w]);
  }
  for (std::size_t g = 0; g < table.n_gamma(); ++g) {
    if (g != skip_g) grid.gamma_hat.push_back(table.grid().gamma_hat[g]);
  }
  DispersionTable out(grid, table.metadata());
  std::size_t gi = 0;
  for (std::size_t g = 0; g < table.n_gamma(); ++g) {
    if (g == skip_g) continue;
    std::size_t wi = 0;
    for (std::size_t w = 0; w < table.n_omega(); ++w) {
      if (w == skip_w) continue;
      out.set(gi, wi++, table.at(g, w));
    }
    ++gi;
  }
  return out;
}

struct Errors {
  std::vector<double> z_alpha, z_c, rel_alpha, rel_c;
  std::size_t not_answered = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double maximum(const std::vector<double>& v) { return v.empty() ? NAN : *std::max_element(v.begin(), v.end()); }
/// The 90th percentile (nearest rank).
double p90(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(v.size()))) - 1];
}

Errors leave_one_line_out(const DispersionTable& table, Interpolation scheme) {
  Errors e;
  auto compare = [&](const TableModel& model, std::size_t g, std::size_t w) {
    const PointResult& truth = table.at(g, w);
    if (truth.status != PointStatus::ok) return;
    DispersionPoint p;
    try {
      p = model.evaluate(table.grid().omega_hat[w], table.grid().gamma_hat[g]);
    } catch (const std::domain_error&) {
      ++e.not_answered;
      return;
    }
    e.rel_alpha.push_back(std::abs(p.alpha_hat / truth.alpha_hat - 1.0));
    e.rel_c.push_back(std::abs(p.c_hat / truth.c_hat - 1.0));
    if (truth.sigma_alpha_hat > 0.0) e.z_alpha.push_back(std::abs(p.alpha_hat - truth.alpha_hat) / truth.sigma_alpha_hat);
    if (truth.sigma_c_hat > 0.0) e.z_c.push_back(std::abs(p.c_hat - truth.c_hat) / truth.sigma_c_hat);
  };
  constexpr std::size_t all = static_cast<std::size_t>(-1);
  for (std::size_t w = 1; w + 1 < table.n_omega(); ++w) {
    const TableModel model(without_line(table, w, all), "held", OutsideTable::error, scheme);
    for (std::size_t g = 0; g < table.n_gamma(); ++g) compare(model, g, w);
  }
  for (std::size_t g = 1; g + 1 < table.n_gamma(); ++g) {
    const TableModel model(without_line(table, all, g), "held", OutsideTable::error, scheme);
    for (std::size_t w = 0; w < table.n_omega(); ++w) compare(model, g, w);
  }
  return e;
}

struct Case {
  std::string name;
  DispersionTable table;
};

std::vector<Case> cases() {
  const TableGrid theory_grid{log_spaced(1e-3, 1.0, 41), log_spaced(1e-2, 1e2, 21)};
  std::vector<Case> out;
  for (const char* file : {"field_w3_driven.h5", "linear_w3.h5", "field_w3_long_wavelength.h5"}) {
    out.push_back({file, read_table(source(std::string("data/tables/") + file))});
  }
  out.push_back({"lattice theory 41 x 21", theory_table(LatticeModel(), theory_grid)});
  out.push_back({"continuum theory 41 x 21", theory_table(ContinuumModel(), theory_grid)});
  return out;
}

std::string cell(double v, const char* format) {
  if (std::isnan(v)) return "–";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

void print_errors() {
  std::printf("Leave one grid line out: the model without each interior omega_hat column, then each interior\n"
              "gamma_hat row, at that line's ok points (an interior point is held back twice). z = |model - table| /\n"
              "sigma of the point; rel = |model / table - 1|; median / 90th percentile / maximum.\n\n");
  std::printf("| table | scheme | held back | not answered | α̂ z | ĉ z | α̂ rel | ĉ rel |\n");
  std::printf("|---|---|---:|---:|---|---|---|---|\n");
  for (const Case& c : cases()) {
    for (const Interpolation scheme : {Interpolation::direct, Interpolation::correction}) {
      const Errors e = leave_one_line_out(c.table, scheme);
      auto stats = [](const std::vector<double>& v, const char* format) {
        if (v.empty()) return std::string("–");
        return cell(median(v), format) + " / " + cell(p90(v), format) + " / " + cell(maximum(v), format);
      };
      std::printf("| %s | %s | %zu | %zu | %s | %s | %s | %s |\n", c.name.c_str(),
                  scheme == Interpolation::direct ? "direct" : "correction", e.rel_alpha.size(), e.not_answered,
                  stats(e.z_alpha, "%.2g").c_str(), stats(e.z_c, "%.2g").c_str(), stats(e.rel_alpha, "%.1e").c_str(),
                  stats(e.rel_c, "%.1e").c_str());
    }
  }
  std::printf("\n");
  std::fflush(stdout);
}

// ---- Speed -------------------------------------------------------------------------------------------

struct Input {
  double omega_hat;
  double gamma_hat;
};
constexpr std::size_t kInputs = 64;

/// 64 points the direct model answers (inside ok cells), log-uniform over the table's range.
std::array<Input, kInputs> inside_points(const TableModel& model) {
  const TableGrid& grid = model.table().grid();
  std::mt19937_64 rng(0x7ab1e);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto between = [&](const std::vector<double>& axis) { return axis.front() * std::pow(axis.back() / axis.front(), u(rng)); };
  std::array<Input, kInputs> inputs{};
  for (std::size_t i = 0; i < kInputs;) {
    const Input in{between(grid.omega_hat), between(grid.gamma_hat)};
    try {
      (void)model.evaluate(in.omega_hat, in.gamma_hat);
      inputs[i++] = in;
    } catch (const std::domain_error&) {
    }
  }
  return inputs;
}

void run(benchmark::State& state, const DispersionModel& model, const std::array<Input, kInputs>& inputs) {
  std::size_t i = 0;
  for (auto _ : state) {
    const Input& in = inputs[i++ & (kInputs - 1)];
    DispersionPoint p = model.evaluate(in.omega_hat, in.gamma_hat);
    benchmark::DoNotOptimize(p);
  }
}

void register_speed() {
  struct Speed {
    std::string name;
    std::shared_ptr<DispersionTable> table;
  };
  const std::vector<Speed> tables{
      {"field_w3_driven", std::make_shared<DispersionTable>(read_table(source("data/tables/field_w3_driven.h5")))},
      {"lattice_41x21", std::make_shared<DispersionTable>(
                            theory_table(LatticeModel(), {log_spaced(1e-3, 1.0, 41), log_spaced(1e-2, 1e2, 21)}))}};
  for (const Speed& s : tables) {
    auto direct = std::make_shared<TableModel>(*s.table, s.name, OutsideTable::error, Interpolation::direct);
    auto correction = std::make_shared<TableModel>(*s.table, s.name, OutsideTable::error, Interpolation::correction);
    auto inputs = std::make_shared<std::array<Input, kInputs>>(inside_points(*direct));
    auto lattice = std::make_shared<LatticeModel>();
    benchmark::RegisterBenchmark((s.name + "/direct").c_str(), [direct, inputs](benchmark::State& st) { run(st, *direct, *inputs); });
    benchmark::RegisterBenchmark((s.name + "/correction").c_str(),
                                 [correction, inputs](benchmark::State& st) { run(st, *correction, *inputs); });
    benchmark::RegisterBenchmark((s.name + "/lattice_theory_alone").c_str(),
                                 [lattice, inputs](benchmark::State& st) { run(st, *lattice, *inputs); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool speed = true;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--no-speed") == 0) {
      speed = false;
    } else {
      args.push_back(argv[i]);
    }
  }
  print_errors();
  if (!speed) return 0;
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
  register_speed();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
