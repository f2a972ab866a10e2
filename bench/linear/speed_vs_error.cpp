// Speed versus error of the forward models at one (omega_hat, gamma_hat) point, measured in one run
// (docs/performance.md, "Speed versus error"). Every row: model, size, wall time (median of
// repeats), alpha_hat, c_hat (with standard errors where the model has them) and the relative error
// of each against the reference row (the first linear-engine ensemble given with --reference).
//
//   bench_speed_vs_error [--omega-hat W] [--gamma-hat G] [--dem N_PERIODS...] PACKING.h5 ...
//
// Packings are files written by `sedwave forward --packing-out` (same scene units, Hooke kn given
// by --kn). Each packing is one linear-engine member; packings with the same grain count form an
// ensemble. --tile K also times the solve on channels made of 1, 2, 4, ... and K copies of the first packing stacked
// along z (the contacts across the joins are not in equilibrium: a cost measurement only).
// --dem runs the time-domain engine on the first packing of each size for each run length given
// (in periods; 0: until echoes could return), on sizes up to --dem-max-grains N only (default: all).
// --reference N takes the ensemble of N-grain packings as the reference (default: the largest).
// --rows FILE also writes the rows tab-separated.
// --fit-layers L adds, per linear member, the fit over the layers skip_layers..L-1 only: the
// stretch a short DEM run's lock-in windows reach (its "layers used"), for a like-for-like
// comparison on the same packing.
// --fluid MU_HAT also times the linear engine with a pore fluid of that viscosity (squeeze films
// below --fluid-cutoff, default 0.1 d, regularised at --fluid-roughness, default 0.001 d;
// Richardson-Zaki drag) against the dry engine on the first packing of each size: assembly and
// solve and respond, dry and wet alternating, median of --fluid-repeats (default 5) each.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/experiment/run_file.hpp"
#include "sedwave/forward/linear/ensemble.hpp"
#include "sedwave/forward/linear/ordered_chain.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"
#include "bench_contact.hpp"
#include "../one_process_mpi.hpp"

namespace {

using namespace sedwave::forward;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds_since(start));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// Assembly, solve (displacement) and respond (solve and measurement) of the dry and the wet
/// engine on one packing, alternating, median of `repeats` each: what a fluid costs the linear engine.
void fluid_cost(const channel::PreparedChannel& packing, const dem::ContactSpec& contact,
                const channel::DriveSettings& drive, const dem::FluidSpec& fluid, int repeats) {
  enum { kAssembly, kSolve, kRespond, kStages };
  std::vector<double> seconds[2][kStages];
  std::size_t slabs[2] = {0, 0}, gaps[2] = {0, 0};
  long largest[2] = {0, 0};
  linear::LinearResult result[2];
  for (int r = 0; r < repeats; ++r) {
    for (int wet = 0; wet < 2; ++wet) {
      channel::DriveSettings d = drive;
      if (wet == 1) d.fluid = fluid;
      auto start = std::chrono::steady_clock::now();
      const linear::LinearChannel engine(packing, contact, {}, d.fluid);
      seconds[wet][kAssembly].push_back(seconds_since(start));
      start = std::chrono::steady_clock::now();
      (void)engine.displacement(d);
      seconds[wet][kSolve].push_back(seconds_since(start));
      start = std::chrono::steady_clock::now();
      result[wet] = engine.respond(d);
      seconds[wet][kRespond].push_back(seconds_since(start));
      slabs[wet] = engine.solver().slabs();
      largest[wet] = static_cast<long>(engine.solver().largest_slab());
      gaps[wet] = engine.network().gaps.size();
    }
  }
  double median[2][kStages];
  for (int wet = 0; wet < 2; ++wet) {
    for (int stage = 0; stage < kStages; ++stage) {
      std::vector<double>& t = seconds[wet][stage];
      std::sort(t.begin(), t.end());
      median[wet][stage] = t[t.size() / 2];
    }
  }
  std::printf("# fluid cost, %zu grains (mu_hat %g, h_r %g d, h_c %g d, median of %d alternating runs):\n",
              packing.grains.size(), fluid.viscosity, fluid.roughness, fluid.cutoff, repeats);
  for (int wet = 0; wet < 2; ++wet) {
    std::printf("#   %s: assembly %.4f s, solve %.4f s, respond %.4f s; %zu gaps, %zu slabs of <= %ld unknowns; "
                "alpha_hat %.5g c_hat %.5g %s\n",
                wet ? "fluid" : "dry  ", median[wet][kAssembly], median[wet][kSolve], median[wet][kRespond], gaps[wet],
                slabs[wet], largest[wet], result[wet].fit.alpha, result[wet].fit.c, result[wet].problem.c_str());
  }
  std::printf("#   fluid / dry: assembly %.3f, solve %.3f, respond %.3f, assembly + respond %.3f\n",
              median[1][kAssembly] / median[0][kAssembly], median[1][kSolve] / median[0][kSolve],
              median[1][kRespond] / median[0][kRespond],
              (median[1][kAssembly] + median[1][kRespond]) / (median[0][kAssembly] + median[0][kRespond]));
}

struct Row {
  std::string model;
  std::string size;
  double seconds = 0.0;
  double alpha = 0.0, sigma_alpha = 0.0, c = 0.0, sigma_c = 0.0;
};

channel::PreparedChannel tiled(const channel::PreparedChannel& p, int copies) {
  double lo = 1e300, hi = -1e300;
  for (const dem::Grain& g : p.grains) {
    if (g.group == channel::kFlowGroup) {
      lo = std::min(lo, g.position.z - g.radius);
      hi = std::max(hi, g.position.z + g.radius);
    }
  }
  const double height = hi - lo;
  channel::PreparedChannel t;
  t.box = p.box;
  std::int64_t id = 1;
  for (const dem::Grain& g : p.grains) {
    for (int k = 0; k < copies; ++k) {
      dem::Grain c = g;
      const bool keep = g.group == channel::kFlowGroup || (g.group == channel::kLowerWallGroup && k == 0) ||
                        (g.group == channel::kUpperWallGroup && k == copies - 1);
      if (!keep) continue;
      c.position.z += k * height;
      c.id = id++;
      t.grains.push_back(c);
    }
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const sedwave::bench::OneProcessMpi mpi(argc, argv, "bench_speed_vs_error");
  if (!mpi.alone()) return 2;
  channel::DriveSettings drive;
  drive.omega_hat = 0.5;
  drive.gamma_hat = 0.1;
  drive.far_end = channel::FarEnd::absorbing;
  double kn = 726.0;
  int tile = 0;
  std::vector<double> dem_periods;
  int fit_layers = 0;
  std::optional<dem::FluidSpec> fluid;
  double fluid_cutoff = 0.1, fluid_roughness = 1e-3;
  int fluid_repeats = 5;
  std::size_t dem_max_grains = 0, reference_grains = 0;
  std::string rows_file;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return std::atof(argv[++i]); };
    if (a == "--omega-hat") drive.omega_hat = next();
    else if (a == "--gamma-hat") drive.gamma_hat = next();
    else if (a == "--kn") kn = next();
    else if (a == "--tile") tile = static_cast<int>(next());
    else if (a == "--dem") dem_periods.push_back(next());
    else if (a == "--fit-layers") fit_layers = static_cast<int>(next());
    else if (a == "--dem-max-grains") dem_max_grains = static_cast<std::size_t>(next());
    else if (a == "--reference") reference_grains = static_cast<std::size_t>(next());
    else if (a == "--rows") rows_file = argv[++i];
    else if (a == "--fluid") fluid.emplace().viscosity = next();
    else if (a == "--fluid-cutoff") fluid_cutoff = next();
    else if (a == "--fluid-roughness") fluid_roughness = next();
    else if (a == "--fluid-repeats") fluid_repeats = static_cast<int>(next());
    else files.push_back(a);
  }
  const dem::ContactSpec contact = sedwave::bench::bench_contact(kn, 0.0);
  if (fluid) {
    fluid->cutoff = fluid_cutoff;
    fluid->roughness = fluid_roughness;
  }

  std::vector<Row> rows;
  // 1D theories: closed forms (median of 1e5 evaluations per repeat).
  const ContinuumModel continuum;
  const LatticeModel lattice;
  for (const auto& [name, theory] : std::vector<std::pair<std::string, const DispersionModel*>>{
           {"1D continuum", &continuum}, {"1D lattice", &lattice}}) {
    // A copy: C++20 lets a lambda capture a structured binding, Clang 14 does not yet.
    const DispersionModel* model = theory;
    DispersionPoint p{};
    const double t = median_seconds(5, [&] {
      for (int r = 0; r < 100000; ++r) p = model->evaluate(drive.omega_hat * (1.0 + 1e-12 * r), drive.gamma_hat);
    }) / 100000.0;
    rows.push_back({name, "-", t, p.alpha_hat, 0.0, p.c_hat, 0.0});
  }

  // The linear engine: members grouped by grain count into ensembles.
  // Grouped by their flow-grain count to two significant figures: stacked channels of the same size
  // differ by a few grains (each cell's walls take what lies within their thickness).
  std::map<std::size_t, std::vector<channel::PreparedChannel>> packings;
  for (const std::string& f : files) {
    channel::PreparedChannel p = experiment::read_packing(f);
    std::size_t flow = 0;
    for (const dem::Grain& g : p.grains) flow += g.group == channel::kFlowGroup ? 1 : 0;
    std::size_t unit = 1;
    while (flow / unit >= 100) unit *= 10;
    packings[(flow + unit / 2) / unit * unit].push_back(std::move(p));
  }
  for (const auto& [n, members_packings] : packings) {
    std::vector<linear::LinearChannel> members;
    const auto start = std::chrono::steady_clock::now();
    for (const auto& p : members_packings) members.emplace_back(p, contact);
    const double assembly = seconds_since(start);
    linear::EnsembleResult e;
    const double t = median_seconds(3, [&] { e = linear::respond(members, drive); });
    std::printf("# linear N = %zu x %zu: assembly %.3f s, solve %.3f s per member; slabs %zu of <= %ld unknowns;"
                " %s%s\n",
                n, members.size(), assembly, t / static_cast<double>(members.size()), members[0].solver().slabs(),
                static_cast<long>(members[0].solver().largest_slab()), e.problem.c_str(),
                e.warning.c_str());
    for (std::size_t k = 0; k < e.members.size(); ++k) {
      rows.push_back({"3D linear (one packing)", std::to_string(n) + " #" + std::to_string(k),
                      t / static_cast<double>(members.size()) + assembly / static_cast<double>(members.size()),
                      e.members[k].fit.alpha, e.members[k].fit.sigma_alpha, e.members[k].fit.c, e.members[k].fit.sigma_c});
    }
    for (std::size_t k = 0; fit_layers > drive.skip_layers && k < e.members.size(); ++k) {
      const linear::LinearResult& m = e.members[k];
      std::vector<channel::LockIn> probes;
      const auto first = static_cast<std::size_t>(drive.skip_layers);
      const std::size_t end = std::min(m.layer_field.size(), static_cast<std::size_t>(fit_layers));
      for (std::size_t layer = first; layer < end; ++layer) {
        channel::LockIn l;
        l.amplitude = std::abs(m.layer_field[layer]);
        l.phase = -std::arg(m.layer_field[layer]);
        probes.push_back(l);
      }
      const channel::PropagationFit f = channel::fit_attenuation_and_wavenumber(
          std::span(m.layer_z.data() + first, end - first), probes, drive.omega_hat, m.fit.k, channel::ProbeWeights::uniform);
      rows.push_back({"linear, layers < " + std::to_string(fit_layers), std::to_string(n) + " #" + std::to_string(k),
                      t / static_cast<double>(members.size()), f.alpha, f.sigma_alpha, f.c, f.sigma_c});
    }
    if (members.size() > 1) {
      rows.push_back({"3D linear (ensemble)", std::to_string(n) + " x" + std::to_string(members.size()), t + assembly,
                      e.alpha_hat, e.sigma_alpha_hat, e.c_hat, e.sigma_c_hat});
    }
  }
  for (const auto& [n, members_packings] : packings) {
    if (fluid) fluid_cost(members_packings.front(), contact, drive, *fluid, fluid_repeats);
  }
  if (tile > 1 && !packings.empty()) {
    for (int copies = 1; copies <= tile; copies = copies < tile && 2 * copies > tile ? tile : 2 * copies) {
      const channel::PreparedChannel big = tiled(packings.begin()->second.front(), copies);
      const auto start = std::chrono::steady_clock::now();
      const linear::LinearChannel engine(big, contact);
      const double assembly = seconds_since(start);
      const double t = median_seconds(3, [&] { (void)engine.displacement(drive); });
      std::printf("# cost, tiled x%d: %zu grains, %zu slabs of <= %ld unknowns: assembly %.3f s, solve %.3f s\n", copies,
                  big.grains.size(), engine.solver().slabs(), static_cast<long>(engine.solver().largest_slab()),
                  assembly, t);
    }
  }

  // The absorbing layer: its reflection measured exactly in an undamped ordered chain (the field
  // before the layer is two lattice waves), against the layer's length in wavelengths; then the 3D
  // results' dependence on the layer's settings.
  {
    const int n = 1000;
    const linear::LinearChannel chain(linear::ordered_chain(n, 0.999), contact);
    std::printf("# absorbing layer in an undamped ordered chain (strength 1): reflection vs length / wavelength\n");
    for (const double w : {0.05, 0.2, 0.5, 1.0}) {
      for (const double fraction : {0.02, 0.05, 0.1, 0.3}) {
        channel::DriveSettings d = drive;
        d.omega_hat = w;
        d.gamma_hat = 0.0;
        d.absorbing_fraction = fraction;
        const Eigen::VectorXcd u = chain.displacement(d);
        std::vector<std::complex<double>> field;
        for (int i = 0; i < static_cast<int>((1.0 - fraction) * n) - 2; ++i) field.push_back(u(3 * i + 2));
        const channel::TwoWaveFit waves = channel::fit_two_waves(0.999, field);
        const double wavelength = 2.0 * std::numbers::pi / waves.k;
        std::printf("#   omega_hat %-5g layer %6.1f d = %6.2f wavelengths: reflection %.2e\n", w, fraction * n,
                    fraction * n / wavelength, waves.reflection);
      }
    }
  }
  for (const auto& [n, members_packings] : packings) {
    std::vector<linear::LinearChannel> members;
    for (const auto& p : members_packings) members.emplace_back(p, contact);
    for (const auto& [fraction, strength] : std::vector<std::pair<double, double>>{{0.3, 1.0}, {0.2, 1.0}, {0.4, 1.0}, {0.3, 3.0}, {0.3, 0.3}}) {
      channel::DriveSettings d = drive;
      d.absorbing_fraction = fraction;
      d.absorbing_strength = strength;
      const linear::EnsembleResult e = linear::respond(members, d);
      std::printf("# 3D N = %zu x %zu, absorbing fraction %.1f strength %.1f: alpha_hat %.5f +- %.5f  c_hat %.5f +- %.5f %s\n",
                  n, members.size(), fraction, strength, e.alpha_hat, e.sigma_alpha_hat, e.c_hat, e.sigma_c_hat,
                  e.problem.c_str());
    }
  }

  // The time-domain engine on the first packing of each size, for each run length.
  for (const auto& [n, ps] : packings) {
    if (dem_max_grains > 0 && n > dem_max_grains) continue;
    for (const double periods : dem_periods) {
      channel::DriveSettings d = drive;
      d.periods = periods;
      const auto start = std::chrono::steady_clock::now();
      const channel::AcousticResult r = channel::run_acoustic(MPI_COMM_WORLD, ps.front(), contact, d);
      rows.push_back({"3D time-domain DEM",
                      std::to_string(n) + " #0, " + (periods > 0.0 ? std::to_string(static_cast<int>(periods)) + " periods"
                                                                    : std::string("until echoes")),
                      seconds_since(start), r.fit.alpha, r.fit.sigma_alpha, r.fit.c, r.fit.sigma_c});
      if (!r.ok()) std::printf("# DEM N = %zu, %g periods: %s\n", n, periods, r.problem.c_str());
    }
  }

  // Reference: the ensemble row of --reference grains, else the last ensemble row (largest grain
  // count), else the last linear row.
  const Row* reference = nullptr;
  for (const Row& r : rows) {
    const bool chosen = reference_grains == 0 || r.size.rfind(std::to_string(reference_grains) + " ", 0) == 0;
    if (r.model.rfind("3D linear", 0) == 0 && chosen) reference = &r;
  }
  std::printf("omega_hat %.4g, gamma_hat %.4g; errors relative to: %s %s\n", drive.omega_hat, drive.gamma_hat,
              reference ? reference->model.c_str() : "-", reference ? reference->size.c_str() : "-");
  std::printf("%-26s %-20s %12s %11s %9s %9s %9s %9s %9s\n", "model", "size", "seconds", "alpha_hat", "+-", "c_hat",
              "+-", "err_alpha", "err_c");
  for (const Row& r : rows) {
    const double ea = reference ? std::abs(r.alpha / reference->alpha - 1.0) : 0.0;
    const double ec = reference ? std::abs(r.c / reference->c - 1.0) : 0.0;
    std::printf("%-26s %-20s %12.4g %11.5g %9.2g %9.5g %9.2g %9.2g %9.2g\n", r.model.c_str(), r.size.c_str(), r.seconds,
                r.alpha, r.sigma_alpha, r.c, r.sigma_c, ea, ec);
  }
  if (!rows_file.empty()) {
    // Tab-separated, for plotting: relative errors against the reference, and each row's own
    // relative standard error (0 where the model states none).
    std::FILE* out = std::fopen(rows_file.c_str(), "w");
    if (out == nullptr) {
      std::fprintf(stderr, "cannot write %s\n", rows_file.c_str());
      return 1;
    }
    std::fprintf(out, "# model\tsize\tseconds\terr_alpha\terr_c\trel_sigma_alpha\trel_sigma_c\n");
    for (const Row& r : rows) {
      const double ea = reference ? std::abs(r.alpha / reference->alpha - 1.0) : 0.0;
      const double ec = reference ? std::abs(r.c / reference->c - 1.0) : 0.0;
      std::fprintf(out, "%s\t%s\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\n", r.model.c_str(), r.size.c_str(), r.seconds, ea, ec,
                   r.sigma_alpha / r.alpha, r.sigma_c / r.c);
    }
    std::fclose(out);
  }
  return 0;
}
