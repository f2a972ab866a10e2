#include "sedwave/forward/experiment/run_file.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/io/hdf5.hpp"
#include "run_file_parts.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/dem/pieces.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/io/fingerprint.hpp"
#include "sedwave/version.hpp"

namespace sedwave::forward::experiment {

using namespace channel;  // the files hold the channel's packings and measurements

namespace {

/// The grains' columns as a packing file stores them (position as rows of x y z).
struct GrainColumns {
  std::vector<std::int64_t> id;
  std::vector<std::int32_t> group, body;
  std::vector<double> radius, mass, position;
  explicit GrainColumns(std::span<const dem::Grain> grains) {
    for (const dem::Grain& g : grains) {
      id.push_back(g.id);
      group.push_back(g.group);
      body.push_back(g.body);
      radius.push_back(g.radius);
      mass.push_back(g.mass);
      position.insert(position.end(), {g.position.x, g.position.y, g.position.z});
    }
  }
};

/// Rows [row, row + grains.size()) of the /grains datasets under `grains_group`, created beforehand.
void write_grain_rows(hid_t grains_group, hsize_t row, std::span<const dem::Grain> grains) {
  const hsize_t count = grains.size();
  if (count == 0) return;
  const GrainColumns c(grains);
  io::write_block(grains_group, "id", {row}, {count}, c.id.data());
  io::write_block(grains_group, "group", {row}, {count}, c.group.data());
  io::write_block(grains_group, "body", {row}, {count}, c.body.data());
  io::write_block(grains_group, "radius", {row}, {count}, c.radius.data());
  io::write_block(grains_group, "mass", {row}, {count}, c.mass.data());
  io::write_block(grains_group, "position", {row, 0}, {count, 3}, c.position.data());
}

/// /grains with `rows` rows, to be filled by write_grain_rows.
io::Handle create_grain_datasets(hid_t file, std::size_t rows) {
  io::Handle grains = io::create_group(file, "grains");
  io::create_dataset<std::int64_t>(grains, "id", rows);
  io::create_dataset<std::int32_t>(grains, "group", rows);
  io::create_dataset<std::int32_t>(grains, "body", rows);
  io::create_dataset<double>(grains, "radius", rows);
  io::create_dataset<double>(grains, "mass", rows);
  io::create_dataset<double>(grains, "position", rows, 3);
  return grains;
}

/// A packing file's attributes, /box and /preparation; `grains` writes /grains.
template <class Grains>
void fill_packing_file(hid_t file, const PreparedChannel& p, const std::string& scene_text, Grains&& grains) {
  io::write_string_attribute(file, "sedwave_version", kVersion);
  io::write_string_attribute(file, "scene", scene_text);
  io::write_string_attribute(file, "units", "lengths in mean grain diameters; masses and forces in scene units");
  grains();
  io::Handle box = io::create_group(file, "box");
  const double bounds[6] = {p.box.lo.x, p.box.lo.y, p.box.lo.z, p.box.hi.x, p.box.hi.y, p.box.hi.z};
  io::write(box, "bounds", bounds, 2, 3);
  const std::int32_t periodic[3] = {p.box.periodic[0], p.box.periodic[1], p.box.periodic[2]};
  io::write(box, "periodic", periodic, 3);
  io::Handle stats = io::create_group(file, "preparation");
  write_stats(stats, p.report);
}

/// One file, built on rank 0 from every rank's grains in turn.
void write_packing_whole(MPI_Comm comm, const std::filesystem::path& path, const PreparedChannel& p,
                         const std::string& scene_text, std::size_t rows) {
  parallel::on_root_with_pieces(comm, std::span(p.grains), 1, [&](auto&& pieces) {
    io::write_file_atomically(path, [&](hid_t file) {
      fill_packing_file(file, p, scene_text, [&] {
        const io::Handle grains = create_grain_datasets(file, rows);
        hsize_t row = 0;
        pieces([&](std::span<const dem::Grain> chunk) {
          write_grain_rows(grains, row, chunk);
          row += chunk.size();
        });
      });
    });
    dem::remove_stale_pieces(path, "");  // of an earlier file at this path written in pieces
  });
}

/// Every rank's grains in piece files of its own, joined by PATH (dem/pieces.hpp).
void write_packing_in_pieces(MPI_Comm comm, const std::filesystem::path& path, const PreparedChannel& p,
                             const std::string& scene_text, const std::vector<std::int64_t>& rows,
                             std::int64_t piece_rows) {
  const std::vector<dem::Piece> pieces = dem::piece_layout({rows}, piece_rows);
  const std::string token = dem::fresh_piece_token(comm);
  const int rank = parallel::rank(comm);
  const std::string pieces_error = parallel::failure_of(
      [&] {
        std::size_t first = 0;
        for (const dem::Piece& piece : pieces) {
          if (piece.rank != rank) continue;
          const auto count = static_cast<std::size_t>(piece.rows[0]);
          io::write_file_atomically(path.parent_path() / dem::piece_name(path, token, piece), [&](hid_t file) {
            write_grain_rows(create_grain_datasets(file, count), 0, std::span(p.grains).subspan(first, count));
          });
          first += count;
        }
      },
      "cannot write a piece of " + path.string());
  parallel::throw_first_failure(comm, pieces_error);
  std::string error;
  if (rank == 0) {
    error = parallel::failure_of(
        [&] {
          io::write_file_atomically(path, [&](hid_t file) {
            fill_packing_file(file, p, scene_text, [&] {
              for (const dem::RowDataset& d : dem::grain_datasets()) dem::join_pieces(file, d, pieces, path, token);
            });
          });
          dem::remove_stale_pieces(path, token);
        },
        "cannot write " + path.string());
  }
  parallel::throw_first_failure(comm, error);
}

}  // namespace

void write_packing(MPI_Comm comm, const std::filesystem::path& path, const PreparedChannel& p,
                   const std::string& scene_text, PackingPieces pieces) {
  const std::vector<std::int64_t> rows = parallel::all_gather(comm, static_cast<std::int64_t>(p.grains.size()));
  std::int64_t total = 0;
  for (const std::int64_t n : rows) total += n;
  if (total <= pieces.whole_rows) {
    write_packing_whole(comm, path, p, scene_text, static_cast<std::size_t>(total));
  } else {
    write_packing_in_pieces(comm, path, p, scene_text, rows, std::max<std::int64_t>(pieces.piece_rows, 1));
  }
  std::filesystem::path data = path;
  data.replace_extension(".data");
  write_packing_lammps_data(comm, data, p);
}

void write_packing(const std::filesystem::path& path, const PreparedChannel& p, const std::string& scene_text) {
  write_packing(MPI_COMM_SELF, path, p, scene_text);
}

void write_packing_lammps_data(MPI_Comm comm, const std::filesystem::path& path, const PreparedChannel& p) {
  std::vector<dem::Grain> typed = p.grains;
  for (dem::Grain& g : typed) g.group += 1;  // LAMMPS types start at 1: 1 flow, 2 lower, 3 upper wall
  dem::write_lammps_data(comm, path.string(), p.box, typed);
}

void write_packing_lammps_data(const std::filesystem::path& path, const PreparedChannel& p) {
  write_packing_lammps_data(MPI_COMM_SELF, path, p);
}

std::string packing_fingerprint(MPI_Comm comm, const PreparedChannel& packing) {
  // The ranks' grains in rank order are the packing in id order: the hash's state passes from rank
  // to rank, and no grain moves. The box (as rank 0 holds it) comes last.
  const dem::Box box = broadcast_box(comm, packing.box);
  const std::uint64_t grains = parallel::fold_in_turn(comm, io::Fingerprint().state(), [&](std::uint64_t state) {
    io::Fingerprint f(state);
    for (const dem::Grain& g : packing.grains) {
      f.add_value(g.id).add_value(g.group).add_value(g.body).add_value(g.radius).add_value(g.mass);
      f.add_value(g.position.x).add_value(g.position.y).add_value(g.position.z);
    }
    return f.state();
  });
  io::Fingerprint f(grains);
  for (int a = 0; a < 3; ++a) f.add_value(box.lo[a]).add_value(box.hi[a]).add_value(static_cast<bool>(box.periodic[a]));
  return f.hex();
}

std::string packing_fingerprint(const PreparedChannel& packing) { return packing_fingerprint(MPI_COMM_SELF, packing); }

namespace {

PreparedChannel read_packing_share(MPI_Comm comm, const std::filesystem::path& path) {
  io::Handle file = io::open_file(path.string());
  io::Handle grains = io::open_group(file, "grains");
  dem::require_pieces(io::open_dataset(grains, "id"), path, "packing");
  const std::size_t rows = io::rows(grains, "id");
  // This rank's share of the rows: contiguous, in file order.
  const auto share = [&](int r) {
    return static_cast<std::size_t>(static_cast<unsigned long long>(rows) * static_cast<unsigned>(r) /
                                    static_cast<unsigned>(parallel::size(comm)));
  };
  const int rank = parallel::rank(comm);
  const std::size_t first = share(rank), n = share(rank + 1) - first;
  PreparedChannel p;
  p.grains = dem::read_grain_rows(grains, first, n);
  io::Handle box = io::open_group(file, "box");
  const auto bounds = io::read_rows<double>(box, "bounds", 0, 2, 3);
  const auto periodic = io::read_rows<std::int32_t>(box, "periodic", 0, 3);
  p.box.lo = {bounds[0], bounds[1], bounds[2]};
  p.box.hi = {bounds[3], bounds[4], bounds[5]};
  p.box.periodic = {periodic[0] != 0, periodic[1] != 0, periodic[2] != 0};
  io::Handle stats = io::open_group(file, "preparation");
  p.report.pressure = io::read_attribute<double>(stats, "pressure");
  p.report.converged = io::read_attribute<std::int32_t>(stats, "converged") != 0;
  p.report.residual_ratio = io::read_attribute<double>(stats, "residual_ratio");
  p.report.stats.packing_fraction = io::read_attribute<double>(stats, "packing_fraction");
  p.report.stats.coordination = io::read_attribute<double>(stats, "coordination");
  return p;
}

}  // namespace

PreparedChannel read_packing(MPI_Comm comm, const std::filesystem::path& path) {
  // Each rank reads its own rows, so one can fail where the others do not: they agree first.
  PreparedChannel p;
  parallel::throw_first_failure(
      comm, parallel::failure_of([&] { p = read_packing_share(comm, path); }, "cannot read the packing " + path.string()));
  return p;
}

PreparedChannel read_packing(const std::filesystem::path& path) { return read_packing(MPI_COMM_SELF, path); }

namespace {

/// A pulse run's results per frequency: one row each, columns as named datasets; the problems as
/// one line per frequency (empty where measured).
void write_spectrum(hid_t results, const std::vector<SpectralResult>& spectrum) {
  io::Handle group = io::create_group(results, "spectrum");
  auto column = [&](const std::string& name, auto value, const std::string& unit) {
    std::vector<double> values;
    for (const SpectralResult& p : spectrum) values.push_back(value(p));
    io::write(group, name, values.data(), values.size());
    io::write_string_attribute(group, name + "_unit", unit);
  };
  column("omega_hat", [](const SpectralResult& p) { return p.omega_hat; }, "1");
  column("alpha_hat", [](const SpectralResult& p) { return p.fit.alpha; }, "Np per d");
  column("sigma_alpha_hat", [](const SpectralResult& p) { return p.fit.sigma_alpha; }, "Np per d");
  column("c_hat", [](const SpectralResult& p) { return p.fit.c; }, "d sqrt(kappa/m)");
  column("sigma_c_hat", [](const SpectralResult& p) { return p.fit.sigma_c; }, "d sqrt(kappa/m)");
  column("layers_used", [](const SpectralResult& p) { return static_cast<double>(p.layers_used); }, "1");
  std::string problems;
  for (const SpectralResult& p : spectrum) problems += p.problem + "\n";
  io::write_string_attribute(group, "problems", problems);
  io::write_string_attribute(group, "about",
                             "broadband (pulse) drive: alpha_hat and c_hat per frequency from the layer records' "
                             "Fourier transforms; a row with a non-empty line in 'problems' was not measured");
}

/// Equal-length time series, one per probe, as a [probes][samples] dataset with its unit.
void write_records(hid_t group, const std::string& name, const std::vector<std::vector<double>>& records,
                   const std::string& unit) {
  std::vector<double> series;
  const std::size_t samples = records.empty() ? 0 : records.front().size();
  for (const auto& record : records) series.insert(series.end(), record.begin(), record.end());
  io::write(group, name, series.data(), records.size(), samples);
  io::write_string_attribute(group, name + "_unit", unit);
}

}  // namespace

void write_run_file(const std::filesystem::path& path, const ChannelScene& scene, const PreparationReport& preparation,
                    const AcousticResult& r) {
  io::write_file_atomically(path, [&](hid_t file) {
    write_run_header(file, scene.text);
    io::Handle packing = io::create_group(file, "packing");
    write_stats(packing, preparation);

    io::Handle probes = io::create_group(file, "probes");
    io::write(probes, "layer_z", r.layer_z.data(), r.layer_z.size());
    io::write_string_attribute(probes, "layer_z_unit", "d, from the driven wall's mean surface");
    io::write(probes, "layer_grains", r.layer_grains.data(), r.layer_grains.size());
    write_records(probes, "displacement", r.displacement, "d; mean over the layer, along the drive axis");
    number(probes, "sample_dt", r.sample_dt, "sqrt(m/kappa)");
    if (!r.windows.empty()) {
      // The lock-in windows (sinusoidal drive): per layer, begin and end; 0 periods where none.
      std::vector<double> begin, end, periods;
      for (const ProbeWindow& w : r.windows) {
        begin.push_back(w.valid() ? w.window.begin : 0.0);
        end.push_back(w.valid() ? w.window.end : 0.0);
        periods.push_back(w.valid() ? static_cast<double>(w.periods) : 0.0);
      }
      io::write(probes, "window_begin", begin.data(), begin.size());
      io::write(probes, "window_end", end.data(), end.size());
      io::write_string_attribute(probes, "window_unit", "sqrt(m/kappa), from the start of the drive");
      io::write(probes, "window_periods", periods.data(), periods.size());
      io::write_string_attribute(probes, "window_periods_unit", "whole drive periods in the lock-in window (0: none)");
    }
    if (r.single_grains) {
      const SingleGrainProbes& p = *r.single_grains;
      io::Handle grains = io::create_group(probes, "single_grains");
      io::write(grains, "id", p.id.data(), p.id.size());
      io::write_string_attribute(grains, "id_unit", "grain id, one per layer (-1: the layer holds no flow grain)");
      io::write(grains, "z", p.z.data(), p.z.size());
      io::write_string_attribute(grains, "z_unit", "d, from the driven wall's mean surface");
      write_records(grains, "displacement", p.displacement, "d; of the one grain, along the drive axis");
    }

    io::Handle results = io::create_group(file, "results");
    number(results, "omega_hat", r.omega_hat, "1");
    number(results, "gamma_hat", r.gamma_hat, "1");
    number(results, "amplitude", r.amplitude, "d");
    write_fit(results, r.fit);
    number(results, "k_hat", r.fit.k, "rad per d");
    number(results, "sigma_k_hat", r.fit.sigma_k, "rad per d");
    number(results, "first_peak_alpha_hat", r.first_peak.alpha, "Np per d");
    number(results, "first_peak_c_hat", r.first_peak.speed, "d sqrt(kappa/m)");
    number(results, "wave_speed_estimate", r.wave_speed_estimate, "d sqrt(kappa/m)");
    // The same in the scene's own units (lengths in d, the scene's mass and stiffness).
    const double t0 = std::sqrt(r.grain_mass / r.kappa);
    number(results, "omega", r.omega_hat / t0, "rad per scene time unit");
    number(results, "alpha", r.fit.alpha / r.mean_diameter, "Np per scene length unit");
    number(results, "c", r.fit.c * r.mean_diameter / t0, "scene length per scene time unit");
    io::write_attribute(results, "layers_used", static_cast<std::int32_t>(r.layers_used));
    io::write_attribute(results, "steps", r.steps);
    io::write_attribute(results, "extensions", static_cast<std::int32_t>(r.extensions));
    number(results, "wall_seconds", r.wall_seconds, "s");
    io::write_string_attribute(results, "problem", r.problem);
    io::write_string_attribute(results, "warning", r.warning);
    if (!r.spectrum.empty()) write_spectrum(results, r.spectrum);
    if (r.single_grains) {
      const SingleGrainProbes& p = *r.single_grains;
      io::Handle grains = io::create_group(results, "single_grains");
      write_fit(grains, p.fit);
      io::write_attribute(grains, "probes_used", static_cast<std::int32_t>(p.probes_used));
      io::write_string_attribute(grains, "problem", p.problem);
      io::write_string_attribute(grains, "about",
                                 "the same measurement from one grain per layer (/probes/single_grains) instead "
                                 "of the layer averages: the thesis's probes, for comparison");
      if (!p.spectrum.empty()) write_spectrum(grains, p.spectrum);
    }
  });
}

}  // namespace sedwave::forward::experiment
