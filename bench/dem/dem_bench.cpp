// Benchmark driver for the thesis scene (see bench/dem/run_vs_lammps.sh and docs/performance.md).
//   dem_bench prepare N file.data   builds a compressed polydisperse packing (d = 1 +- 0.2, density
//                                   1) in a W = 3 periodic channel and writes a LAMMPS data file
//   dem_bench run file.data STEPS   runs the thesis physics (frictionless Hooke, E = 1000,
//                                   nu = 2/7, e_n = 0.9, LAMMPS kn/gamma_n, dt = 0.01 t_col) and
//                                   prints "ns_per_grain_step=... " on rank 0
//   dem_bench params                prints kn gamma_n dt for the LAMMPS input
//   dem_bench stack in.data K out.data
//                                   K copies of a packing periodic along z, one above the other
//                                   (ids renumbered), for larger packings than are worth relaxing
//   dem_bench channel cell.data K STEPS CHECKPOINT [restart]
//                                   K copies of the z-periodic packing cell.data tiled into a channel
//                                   with frozen walls, each rank building only its own copies (or,
//                                   with `restart`, the state of CHECKPOINT restored, on any rank
//                                   count); runs STEPS and writes CHECKPOINT (pieces per rank)
//   dem_bench read file.data [whole] reads the data file on every rank, each its share of the bytes
//                                   (`whole`: each the whole file, keeping every size-th grain), and
//                                   prints the slowest rank's seconds, the grains per rank and every
//                                   rank's peak resident memory (MB, and its growth during the read)
//   dem_bench loop file.data [CUT]  times the force loop alone on one rank, positions frozen after
//                                   200 steps, dry and with a pore fluid's lubrication (cut-off
//                                   CUT d, default 0.05) in alternating batches: median and fastest
//                                   of 20 batches, in ns per grain and per listed pair
// DEM_BENCH_NEWTON=off runs sedwave with newton off (default on); DEM_BENCH_VERBOSE=1 prints the
// engine's timing table and list statistics. DEM_BENCH_BALANCE_EVERY=K (`run` only) rebuilds the
// lists every K steps and balances the slabs at every rebuild on the measured force-loop time, which
// also evens out ranks on slower cores (default: the engine's balancing on listed pairs, at the
// rebuilds the motion asks for).
//
// `run` prints one line of key=value pairs on rank 0: the time per grain-step, the split of a step
// into force, neighbour, communication and integration (mean and slowest rank, ms per step; the
// communication time includes waiting for slower ranks), the halo-exchange volume per step and
// every rank's peak resident memory (smallest, median, largest, rank 0's; MB) and the seconds the
// slowest rank took to read its share of the data file.
#include <mpi.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <variant>

#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/units.hpp"

namespace dem = sedwave::forward::dem;
namespace fw = sedwave::forward;

namespace {

constexpr double kYoung = 1000.0, kPoisson = 2.0 / 7.0, kRestitution = 0.9, kSkin = 0.1;

struct ThesisPhysics {
  double kn, gamma_n, dt;
};

ThesisPhysics thesis_physics() {
  const double min_mass = fw::grain_mass(1.0, 0.8);  // the smallest grain, d = 0.8
  const double m_eff = 0.5 * min_mass;
  const fw::LammpsHooke h = fw::lammps_hooke_from_material(kYoung, kPoisson, kRestitution, m_eff);
  const double t_col = fw::hooke_collision_time(h.kn, m_eff, fw::gamma_from_lammps(h.gamma_n, m_eff));
  return {h.kn, h.gamma_n, 0.01 * t_col};
}

dem::EngineSettings settings(const dem::Box& box, bool prepare) {
  const ThesisPhysics p = thesis_physics();
  dem::EngineSettings s;
  s.box = box;
  s.box.periodic = {true, true, true};
  s.contact["kn"] = p.kn;
  s.contact["lammps_gamma_n"] = p.gamma_n;
  s.time_step = p.dt;
  s.skin = kSkin;
  // DEM_BENCH_NEWTON=off computes pairs across boundaries on both sides (LAMMPS newton off).
  const char* newton = std::getenv("DEM_BENCH_NEWTON");
  s.newton = newton == nullptr || std::string(newton) != "off";
  if (prepare) {
    s.viscous_damping = 2.0;
    s.guard.max_overlap_fraction = 0.6;  // the lattice start overlaps; relaxation removes it
  }
  return s;
}

long peak_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

int prepare(long n, const std::string& path) {
  // Jittered FCC at packing fraction ~0.64 for the mean grain volume, two cells (W ~ 3) across.
  const double spacing = 1.0636, a = spacing * std::numbers::sqrt2;
  const long layers = (n + 15) / 16;
  std::mt19937_64 rng(20240501);
  std::uniform_real_distribution<double> diameter(0.8, 1.2), jitter(-0.02, 0.02);
  std::vector<dem::Grain> grains;
  const dem::Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (long iz = 0; iz < layers; ++iz)
    for (int ix = 0; ix < 2; ++ix)
      for (int iy = 0; iy < 2; ++iy)
        for (const dem::Vec3& b : basis) {
          if (static_cast<long>(grains.size()) == n) break;
          dem::Grain g;
          g.id = static_cast<std::int64_t>(grains.size()) + 1;
          g.group = 1;
          const double d = diameter(rng);
          g.radius = 0.5 * d;
          g.mass = fw::grain_mass(1.0, d);
          g.position = a * dem::Vec3{ix + b.x + 0.25 + jitter(rng), iy + b.y + 0.25 + jitter(rng),
                                     static_cast<double>(iz) + b.z + 0.25 + jitter(rng)};
          grains.push_back(g);
        }
  dem::Box box;
  box.lo = {0, 0, 0};
  box.hi = {2 * a, 2 * a, static_cast<double>(layers) * a};
  dem::Engine engine(MPI_COMM_SELF, settings(box, true), grains);
  engine.run(4000);  // relax the overlaps under strong viscous damping
  std::vector<dem::Grain> out;
  std::normal_distribution<double> thermal(0.0, 1e-3);
  for (std::size_t i = 0; i < engine.n_local(); ++i) {
    dem::Grain g = engine.grains().grain(i);
    g.velocity = {thermal(rng), thermal(rng), thermal(rng)};
    out.push_back(g);
  }
  std::sort(out.begin(), out.end(), [](const dem::Grain& x, const dem::Grain& y) { return x.id < y.id; });
  dem::write_lammps_data(path, engine.domain().box(), out);
  std::printf("prepared %zu grains, box %g x %g x %g, KE %.3g\n", out.size(), box.hi.x, box.hi.y, box.hi.z,
              engine.kinetic_energy());
  return 0;
}

/// Peak resident memory of every rank in MB, sorted, and rank 0's (valid on rank 0).
struct RankMemory {
  std::vector<double> sorted_mb;
  double rank0_mb = 0.0;
};

RankMemory gather_peak_memory(int rank, int size) {
  const double mine = static_cast<double>(peak_rss_kib()) / 1024.0;
  RankMemory m;
  m.sorted_mb.resize(static_cast<std::size_t>(size));
  MPI_Gather(&mine, 1, MPI_DOUBLE, m.sorted_mb.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (rank == 0) {
    m.rank0_mb = m.sorted_mb[0];
    std::sort(m.sorted_mb.begin(), m.sorted_mb.end());
  }
  return m;
}

/// A phase's time per step in ms: the mean over ranks and the slowest rank's.
struct PhaseTime {
  double mean_ms, max_ms;
};

PhaseTime phase_per_step(double seconds, long steps, int size) {
  double sum = 0.0, max = 0.0;
  MPI_Allreduce(&seconds, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&seconds, &max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const double per_step_ms = 1e3 / static_cast<double>(steps);
  return {per_step_ms * sum / size, per_step_ms * max};
}

int run(const std::string& path, long steps) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const long rss_before = peak_rss_kib();
  // Each rank reads its share of the file's bytes, as `sedwave dem` does, so no rank holds it whole;
  // the engine then sends each grain to its slab's owner.
  const double read_start = MPI_Wtime();
  dem::LammpsData data = dem::read_lammps_data(MPI_COMM_WORLD, path);
  double read_s = MPI_Wtime() - read_start;  // the slowest rank's
  MPI_Allreduce(MPI_IN_PLACE, &read_s, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  dem::EngineSettings s = settings(data.box, false);
  s.guard.check_interval = 1000;
  s.progress.enabled = std::getenv("DEM_BENCH_VERBOSE") != nullptr;
  const char* balance_every = std::getenv("DEM_BENCH_BALANCE_EVERY");
  const long rebuild_every = balance_every != nullptr ? std::stol(balance_every) : 0;
  if (rebuild_every > 0) s.balance = {1, true};
  dem::Engine engine(MPI_COMM_WORLD, s, data.grains);
  data.grains.clear();
  data.grains.shrink_to_fit();
  // Steps in chunks of rebuild_every, each ending with a requested rebuild (and so a balance).
  const auto advance = [&](long n) {
    if (rebuild_every <= 0) return engine.run(n);
    for (long done = 0; done < n; done += rebuild_every) {
      engine.run(std::min(rebuild_every, n - done));
      engine.request_rebuild();
    }
  };
  advance(std::min(steps / 10, 200L));  // warm-up
  MPI_Barrier(MPI_COMM_WORLD);
  const dem::Timings before = engine.timings();
  const auto halo_before = engine.domain().halo_bytes_sent();
  const double t0 = MPI_Wtime();
  advance(steps);
  MPI_Barrier(MPI_COMM_WORLD);
  const double seconds = MPI_Wtime() - t0;
  const dem::Timings& after = engine.timings();
  const PhaseTime force = phase_per_step(after.force - before.force, steps, size);
  const PhaseTime neighbour = phase_per_step(after.neighbor - before.neighbor, steps, size);
  const PhaseTime communication = phase_per_step(after.communication - before.communication, steps, size);
  const PhaseTime integration = phase_per_step(after.integrate - before.integrate, steps, size);
  // Sent by all ranks together per step.
  double halo_bytes = static_cast<double>(engine.domain().halo_bytes_sent() - halo_before) / static_cast<double>(steps);
  MPI_Allreduce(MPI_IN_PLACE, &halo_bytes, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const RankMemory memory = gather_peak_memory(rank, size);
  double bytes = static_cast<double>(engine.memory_bytes());
  MPI_Allreduce(MPI_IN_PLACE, &bytes, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  long rss_growth = peak_rss_kib() - rss_before;
  MPI_Allreduce(MPI_IN_PLACE, &rss_growth, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  const double n = static_cast<double>(engine.n_global());
  if (rank == 0 && std::getenv("DEM_BENCH_VERBOSE"))
    std::printf("listed pairs per local grain (rank 0): %.2f, ghosts per local grain: %.2f\n",
                double(engine.neighbor_list().n_pairs()) / double(engine.n_local()),
                double(engine.grains().n_ghost()) / double(engine.n_local()));
  if (rank == 0) {
    const std::vector<double>& mb = memory.sorted_mb;
    std::printf("ns_per_grain_step=%.2f ranks=%d grains=%.0f steps=%ld engine_bytes_per_grain=%.0f "
                "rss_growth_bytes_per_grain=%.0f dt=%.6g ms_per_step=%.4f "
                "force_ms=%.4f/%.4f neighbour_ms=%.4f/%.4f communication_ms=%.4f/%.4f integration_ms=%.4f/%.4f "
                "halo_bytes_per_step=%.0f peak_rss_mb_min=%.1f peak_rss_mb_median=%.1f peak_rss_mb_max=%.1f "
                "peak_rss_mb_rank0=%.1f read_s=%.3f\n",
                1e9 * seconds / (n * static_cast<double>(steps)), size, n, steps, bytes / n,
                1024.0 * static_cast<double>(rss_growth) / n, engine.time_step(),
                1e3 * seconds / static_cast<double>(steps), force.mean_ms, force.max_ms, neighbour.mean_ms,
                neighbour.max_ms, communication.mean_ms, communication.max_ms, integration.mean_ms,
                integration.max_ms, halo_bytes, mb.front(), mb[mb.size() / 2], mb.back(), memory.rank0_mb, read_s);
  }
  return 0;
}

/// Reads a data file on every rank and prints, on rank 0, the slowest rank's seconds, the grains per
/// rank and every rank's peak resident memory. `whole`: every rank parses the whole file and keeps
/// every size-th grain (the way before byte ranges), for comparison in the same run.
int read(const std::string& path, bool whole) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const long rss_before = peak_rss_kib();
  MPI_Barrier(MPI_COMM_WORLD);
  const double start = MPI_Wtime();
  std::size_t index = 0;
  const dem::LammpsData data =
      whole ? dem::read_lammps_data(path, [&](const dem::Grain&) { return static_cast<int>(index++ % static_cast<std::size_t>(size)) == rank; })
            : dem::read_lammps_data(MPI_COMM_WORLD, path);
  double seconds = MPI_Wtime() - start;
  MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  long counts[2] = {static_cast<long>(data.grains.size()), -static_cast<long>(data.grains.size())};
  long total = counts[0];
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  double growth_mb = static_cast<double>(peak_rss_kib() - rss_before) / 1024.0;
  double growth[2] = {growth_mb, -growth_mb};
  MPI_Allreduce(MPI_IN_PLACE, growth, 2, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  const RankMemory memory = gather_peak_memory(rank, size);
  if (rank == 0) {
    const std::vector<double>& mb = memory.sorted_mb;
    std::printf("mode=%s ranks=%d grains=%ld read_s=%.3f grains_per_rank_min=%ld grains_per_rank_max=%ld "
                "peak_rss_mb_min=%.1f peak_rss_mb_median=%.1f peak_rss_mb_max=%.1f read_growth_mb_min=%.1f "
                "read_growth_mb_max=%.1f\n",
                whole ? "whole" : "ranges", size, total, seconds, counts[0], -counts[1], mb.front(), mb[mb.size() / 2],
                mb.back(), growth[0], -growth[1]);
  }
  return 0;
}

/// K copies of a z-periodic packing stacked along z; ids renumbered copy by copy.
int stack(const std::string& in, long copies, const std::string& out) {
  if (copies < 1) throw std::invalid_argument("stack: the number of copies must be at least 1");
  const dem::LammpsData data = dem::read_lammps_data(in, [](const dem::Grain&) { return true; });
  const double height = data.box.length(2);
  std::int64_t max_id = 0;
  for (const dem::Grain& g : data.grains) max_id = std::max(max_id, g.id);
  std::vector<dem::Grain> grains;
  grains.reserve(data.grains.size() * static_cast<std::size_t>(copies));
  for (long k = 0; k < copies; ++k)
    for (dem::Grain g : data.grains) {
      g.id += k * max_id;
      g.position.z += static_cast<double>(k) * height;
      grains.push_back(g);
    }
  dem::Box box = data.box;
  box.hi.z = box.lo.z + static_cast<double>(copies) * height;
  dem::write_lammps_data(out, box, grains);
  std::printf("stacked %ld copies: %zu grains, box height %g\n", copies, grains.size(), box.length(2));
  return 0;
}

/// A channel of `copies` stacked images of the z-periodic packing `cell_path`, tiled on every rank
/// (each builds its own copies; channel/periodic_cell.hpp), its end grains frozen into walls;
/// `restart`: restored from `checkpoint` instead (the scene is tiled again first, as `sedwave dem`
/// rebuilds its scene). Runs `steps`, writes `checkpoint` (pieces per rank) and prints one line of
/// key=value pairs on rank 0: the seconds to tile, to restore, per step and to checkpoint; the
/// exchange per step; every rank's peak resident memory, in MB and in bytes per grain it owns.
int channel_run(const std::string& cell_path, long copies, long steps, const std::string& checkpoint, bool restart) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  namespace ch = fw::channel;
  const double t_start = MPI_Wtime();
  ch::PreparedChannel cell;
  {
    dem::LammpsData data = dem::read_lammps_data(cell_path, [&](const dem::Grain&) { return rank == 0; });
    cell.box = data.box;
    cell.box.periodic = {true, true, true};  // as `prepare` relaxed it
    for (dem::Grain& g : data.grains) {
      g.group = ch::kFlowGroup;
      g.body = dem::kFreeBody;
    }
    cell.grains = std::move(data.grains);
  }
  dem::EngineSettings s = settings(cell.box, false);
  ch::PreparedChannel tiled = ch::tile_periodic_cell(MPI_COMM_WORLD, cell, s.contact, static_cast<int>(copies), 1.5);
  const double tile_s = MPI_Wtime() - t_start;
  // DEM_BENCH_LOOSE=F: uneven work. Each flow grain in the upper half of the channel is removed with
  // probability F (decided by its id, so alike on any rank count): a jammed half beside a loose one.
  if (const char* loose = std::getenv("DEM_BENCH_LOOSE")) {
    const double fraction = std::stod(loose), middle = 0.5 * (tiled.box.lo.z + tiled.box.hi.z);
    std::erase_if(tiled.grains, [&](const dem::Grain& g) {
      const std::uint64_t h = std::hash<std::uint64_t>{}(static_cast<std::uint64_t>(g.id) * 0x9E3779B97F4A7C15ull);
      return g.group == ch::kFlowGroup && g.position.z > middle && static_cast<double>(h % 1000000) < 1e6 * fraction;
    });
  }
  // DEM_BENCH_VERBOSE: rank 0's peak memory after each phase, in bytes per grain of the channel's share.
  const bool verbose = std::getenv("DEM_BENCH_VERBOSE") != nullptr;
  const double share = static_cast<double>(copies) * static_cast<double>(cell.grains.size()) / size;
  const auto phase = [&](const char* name) {
    if (verbose && rank == 0) std::printf("peak after %s: %.0f B per grain\n", name, 1024.0 * static_cast<double>(peak_rss_kib()) / share);
  };
  phase("tiling");
  s.box = tiled.box;
  s.guard.check_interval = 1000;
  s.checkpoint.path = checkpoint;
  // DEM_BENCH_PIECE_ROWS=K: checkpoint pieces of at most K rows (default the engine's).
  if (const char* rows = std::getenv("DEM_BENCH_PIECE_ROWS")) s.checkpoint.piece_rows = std::stoul(rows);
  // DEM_BENCH_REBUILD_EVERY=K: lists rebuilt every K steps; DEM_BENCH_SLABS=fixed keeps the first
  // slabs, =pairs balances them on listed pairs at every rebuild (default: the engine's settings).
  const char* rebuild_every_text = std::getenv("DEM_BENCH_REBUILD_EVERY");
  const long rebuild_every = rebuild_every_text != nullptr ? std::stol(rebuild_every_text) : 0;
  if (const char* slabs = std::getenv("DEM_BENCH_SLABS")) s.balance = {std::string(slabs) == "fixed" ? 0 : 1, false};
  const std::vector<dem::RigidBody> walls{dem::RigidBody("lower_wall", dem::Frozen{}),
                                          dem::RigidBody("upper_wall", dem::Frozen{})};
  dem::Engine engine(MPI_COMM_WORLD, s, tiled.grains, walls);
  std::vector<dem::Grain>().swap(tiled.grains);
  phase("building the engine");
  double restore_s = 0.0;
  if (restart) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    engine.restore_checkpoint(checkpoint);
    MPI_Barrier(MPI_COMM_WORLD);
    restore_s = MPI_Wtime() - t0;
  }
  if (restart) phase("restoring");
  const long first_step = static_cast<long>(engine.step_count());
  MPI_Barrier(MPI_COMM_WORLD);
  const dem::Timings before = engine.timings();
  const auto halo_before = engine.domain().halo_bytes_sent();
  const double t0 = MPI_Wtime();
  for (long done = 0; done < steps; done += rebuild_every > 0 ? rebuild_every : steps) {
    engine.run(rebuild_every > 0 ? std::min(rebuild_every, steps - done) : steps);
    if (rebuild_every > 0) engine.request_rebuild();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const double seconds = MPI_Wtime() - t0;
  phase("running");
  // Work per rank at the end: listed pairs + owned grains (what balancing on pairs evens out).
  double work = static_cast<double>(engine.neighbor_list().n_pairs() + engine.n_local()), work_max = work;
  MPI_Allreduce(MPI_IN_PLACE, &work, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &work_max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const double work_imbalance = work_max / (work / size);
  const dem::Timings& after = engine.timings();
  const PhaseTime force = phase_per_step(after.force - before.force, steps, size);
  const PhaseTime communication = phase_per_step(after.communication - before.communication, steps, size);
  double halo_bytes = static_cast<double>(engine.domain().halo_bytes_sent() - halo_before) / static_cast<double>(steps);
  MPI_Allreduce(MPI_IN_PLACE, &halo_bytes, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const double t1 = MPI_Wtime();
  engine.write_checkpoint(checkpoint);
  MPI_Barrier(MPI_COMM_WORLD);
  const double checkpoint_s = MPI_Wtime() - t1;
  phase("running and checkpointing");
  if (verbose && rank == 0) std::printf("engine's own structures: %.0f B per grain\n", static_cast<double>(engine.memory_bytes()) / share);
  // Peak memory per owned grain, each rank against the grains it holds at the end.
  const RankMemory memory = gather_peak_memory(rank, size);
  double per_grain = 1024.0 * static_cast<double>(peak_rss_kib()) / static_cast<double>(std::max<std::size_t>(engine.n_local(), 1));
  double per_grain_min = per_grain;
  MPI_Allreduce(MPI_IN_PLACE, &per_grain, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &per_grain_min, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  if (rank == 0) {
    const std::vector<double>& mb = memory.sorted_mb;
    std::printf("ranks=%d grains=%lld steps=%ld..%ld tile_s=%.2f restore_s=%.2f ms_per_step=%.1f force_ms=%.1f/%.1f "
                "communication_ms=%.2f/%.2f halo_bytes_per_step=%.0f checkpoint_s=%.2f peak_rss_mb_min=%.0f "
                "peak_rss_mb_median=%.0f peak_rss_mb_max=%.0f peak_bytes_per_owned_grain_min=%.0f "
                "peak_bytes_per_owned_grain_max=%.0f work_imbalance=%.3f force_imbalance=%.3f\n",
                size, static_cast<long long>(engine.n_global()), first_step, first_step + steps, tile_s, restore_s,
                1e3 * seconds / static_cast<double>(steps), force.mean_ms, force.max_ms, communication.mean_ms,
                communication.max_ms, halo_bytes, checkpoint_s, mb.front(), mb[mb.size() / 2], mb.back(),
                per_grain_min, per_grain, work_imbalance, force.max_ms / force.mean_ms);
  }
  return 0;
}

/// The times of one force loop, batch by batch.
struct LoopTimes {
  std::vector<double> seconds;
  [[nodiscard]] double median() const { return quantile(0.5); }
  [[nodiscard]] double fastest() const { return *std::min_element(seconds.begin(), seconds.end()); }
  /// The p-quantile (nearest rank) of the recorded values.
  [[nodiscard]] double quantile(double p) const {
    std::vector<double> s = seconds;
    std::sort(s.begin(), s.end());
    return s[static_cast<std::size_t>(p * static_cast<double>(s.size() - 1) + 0.5)];
  }
};

/// One engine's force loop on its own list, positions frozen after 200 steps, callable batch by batch.
class FrozenLoop {
 public:
  using Model = dem::ContactModel<dem::HookeNormal>;
  FrozenLoop(const dem::LammpsData& data, const std::optional<dem::FluidSpec>& fluid)
      : engine_(MPI_COMM_SELF, with_fluid(settings(data.box, false), fluid), data.grains), grains_(true) {
    engine_.run(200);
    grains_ = engine_.grains();
    dem::tabulate_pairs(model(), grains_, engine_.neighbor_list(), table_);
    if (fluid) dem::tabulate_films(*fluid, grains_, engine_.neighbor_list(), films_);
  }
  [[nodiscard]] const Model& model() const { return std::get<Model>(engine_.contact_model()); }
  [[nodiscard]] const dem::NeighborList& list() const { return engine_.neighbor_list(); }
  /// Seconds per force evaluation, over `repeats` evaluations.
  double batch(int repeats) {
    const std::optional<dem::FluidSpec>& fluid = engine_.settings().fluid;
    const double t0 = MPI_Wtime();
    for (int r = 0; r < repeats; ++r) {
      std::fill(grains_.force.begin(), grains_.force.end(), dem::Vec3{});
      if (fluid)
        (void)dem::accumulate_contact_forces<Model, false>(model(), grains_, list(), table_, {}, engine_.time_step(),
                                                           dem::LubricationEvaluator(*fluid, films_));
      else
        (void)dem::accumulate_contact_forces<Model, false>(model(), grains_, list(), table_, {}, engine_.time_step());
    }
    return (MPI_Wtime() - t0) / repeats;
  }

 private:
  static dem::EngineSettings with_fluid(dem::EngineSettings s, const std::optional<dem::FluidSpec>& fluid) {
    s.fluid = fluid;
    return s;
  }
  dem::Engine engine_;
  dem::GrainArrays grains_;
  dem::PairTable<Model> table_;
  std::vector<dem::FilmPair> films_;
};

/// The dry force loop and the lubricated one (a fluid with lubrication cut-off `cutoff` d: its list
/// also holds the pairs that far apart), timed in alternating batches on the same grains.
int loop(const std::string& path, double cutoff) {
  const dem::LammpsData data = dem::read_lammps_data(path, [](const dem::Grain&) { return true; });
  dem::FluidSpec fluid;
  fluid.viscosity = 1e-4;  // mu_hat ~ 5e-6 for kn = 726, m = 0.52: water around 0.3 mm sand
  fluid.roughness = 1e-3;
  fluid.cutoff = cutoff;
  FrozenLoop dry(data, std::nullopt), wet(data, fluid);
  constexpr int kBatches = 40, kPerBatch = 50;
  LoopTimes dry_times, wet_times, ratios;
  for (int b = 0; b < kBatches; ++b) {
    dry_times.seconds.push_back(dry.batch(kPerBatch));
    wet_times.seconds.push_back(wet.batch(kPerBatch));
    ratios.seconds.push_back(wet_times.seconds.back() / dry_times.seconds.back());
  }
  const auto report = [](const char* name, const FrozenLoop& l, const LoopTimes& t) {
    const double n = static_cast<double>(l.list().n_rows());
    std::printf("%-28s %8.2f %8.2f %10.2f %12.2f\n", name, 1e9 * t.median() / n, 1e9 * t.fastest() / n,
                static_cast<double>(l.list().n_pairs()) / n, 1e9 * t.median() / static_cast<double>(l.list().n_pairs()));
  };
  std::printf("force loop, %zu grains, alternating batches of %d evaluations (%d each)\n", dry.list().n_rows(),
              kPerBatch, kBatches);
  std::printf("%-28s %8s %8s %10s %12s\n", "loop", "median", "fastest", "pairs", "median");
  std::printf("%-28s %8s %8s %10s %12s\n", "", "ns/grain", "ns/grain", "per grain", "ns/pair");
  report("dry", dry, dry_times);
  char name[64];
  std::snprintf(name, sizeof name, "lubricated (cutoff %.3g d)", cutoff);
  report(name, wet, wet_times);
  // Side by side: each lubricated batch against the dry batch just before it, so that a host that
  // slows down for a while slows both.
  std::printf("ratio lubricated / dry: median of the %d batch pairs %.3f (quartiles %.3f, %.3f); of the medians %.3f\n",
              kBatches, ratios.median(), ratios.quantile(0.25), ratios.quantile(0.75), wet_times.median() / dry_times.median());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 2;
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "prepare" && argc == 4) status = prepare(std::stol(argv[2]), argv[3]);
    else if (mode == "run" && argc == 4) status = run(argv[2], std::stol(argv[3]));
    else if (mode == "stack" && argc == 5) status = stack(argv[2], std::stol(argv[3]), argv[4]);
    else if (mode == "channel" && (argc == 6 || (argc == 7 && std::string(argv[6]) == "restart")))
      status = channel_run(argv[2], std::stol(argv[3]), std::stol(argv[4]), argv[5], argc == 7);
    else if (mode == "read" && (argc == 3 || (argc == 4 && std::string(argv[3]) == "whole")))
      status = read(argv[2], argc == 4);
    else if (mode == "loop" && (argc == 3 || argc == 4)) status = loop(argv[2], argc == 4 ? std::stod(argv[3]) : 0.05);
    else if (mode == "params") {
      const ThesisPhysics p = thesis_physics();
      std::printf("%.17g %.17g %.17g\n", p.kn, p.gamma_n, p.dt);
      status = 0;
    } else {
      std::cerr << "usage: dem_bench prepare N file | run file steps | stack file K out | channel cell K steps checkpoint "
                   "[restart] | read file [whole] | loop file [cutoff] | params\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "dem_bench: " << e.what() << '\n';
    status = 1;
  }
  MPI_Finalize();
  return status;
}
