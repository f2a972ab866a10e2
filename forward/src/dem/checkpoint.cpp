// HDF5 checkpoint and restart of the DEM engine.
//
// File layout (format attribute "sedwave-dem-checkpoint", version 1):
//   /            attributes step, time, dt, ranks, rebuilds, user_state
//   /grains      id, group, body, radius, mass [N]; position, velocity, force [N,3];
//                angular_velocity, torque [N,3] when the model rotates grains
//   /history     a, b [M] (smaller, larger global id), shear [M,3] (seen from a)
//   /bodies      displacement, velocity, contact_force [B,3]
//   /domain      boundaries [ranks+1]; grain_rows, history_rows [ranks]: each rank's rows, in rank order
// No rank holds all grains, writing or reading. A small checkpoint on one rank is one file of
// ordinary datasets. Otherwise every rank writes its rows in pieces of its own (dem/pieces.hpp: at
// most CheckpointSettings::piece_rows rows each, so a checkpoint adds one piece's memory to a
// rank's, whatever it holds), and /grains and /history of PATH are virtual datasets that join them;
// PATH is replaced last, which is what switches a restart to the new state. A kill at any moment
// leaves the old checkpoint or the new one whole.
// Reading, each rank reads its own rows: with the same rank count, the rows it wrote (and its slab
// boundaries); with another, an equal share of rows, and the engine then repartitions; each contact-
// history record read then goes to the ranks holding its grains.
#include <algorithm>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <unordered_map>

#include "sedwave/io/hdf5.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/dem/pieces.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr std::int32_t kCheckpointVersion = 1;
constexpr std::size_t kReadChunk = 1 << 16;

/// Rows [first, first + count) of one of the grains' fields.
template <typename T>
const T* rows_of(const std::vector<T>& field, std::size_t first) {
  return field.data() + first;
}

/// Rows [first, first + count) of a vector field, as count x 3 doubles.
std::vector<double> vectors(const std::vector<Vec3>& field, std::size_t first, std::size_t count) {
  std::vector<double> out;
  out.reserve(3 * count);
  for (std::size_t i = first; i < first + count; ++i) out.insert(out.end(), {field[i].x, field[i].y, field[i].z});
  return out;
}

/// The run's inputs as a checkpoint recorded them (empty when it recorded none).
std::map<std::string, std::string> recorded_inputs(hid_t file) {
  std::map<std::string, std::string> inputs;
  if (!io::exists(file, "inputs")) return inputs;
  io::Handle group(H5Gopen2(file, "inputs", H5P_DEFAULT), H5Gclose, "open /inputs");
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  io::check(H5Aiterate2(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "list /inputs");
  for (const std::string& name : names) inputs[name] = io::read_string_attribute(group, name);
  return inputs;
}

/// Throws naming every input that differs between the checkpoint and this run.
void require_same_inputs(const std::map<std::string, std::string>& recorded,
                         const std::map<std::string, std::string>& now, const std::string& path) {
  std::string changes;
  const auto value = [](const std::map<std::string, std::string>& m, const std::string& key) {
    const auto it = m.find(key);
    return it == m.end() ? std::string("(not recorded)") : it->second;
  };
  std::map<std::string, std::string> all = recorded;
  all.insert(now.begin(), now.end());
  for (const auto& [name, ignored] : all) {
    if (value(recorded, name) != value(now, name))
      changes += "\n  " + name + ": " + value(recorded, name) + " in the checkpoint, " + value(now, name) + " now";
  }
  if (!changes.empty()) {
    throw std::runtime_error("DEM restart: " + path + " was written from other inputs:" + changes +
                             "\n(restart with the original inputs, or pass --allow-changed-inputs to continue anyway)");
  }
}


/// Rows of this rank's grains and contact history, written under `file` (a checkpoint or a piece).
void write_rows(hid_t file, const GrainArrays& grains, std::size_t first, std::size_t n,
                std::span<const HistoryEntry> history) {
  io::Handle g = io::create_group(file, "grains");
  io::write(g, "id", rows_of(grains.id, first), n);
  io::write(g, "group", rows_of(grains.group, first), n);
  io::write(g, "body", rows_of(grains.body, first), n);
  io::write(g, "radius", rows_of(grains.radius, first), n);
  io::write(g, "mass", rows_of(grains.mass, first), n);
  io::write(g, "position", vectors(grains.position, first, n).data(), n, 3);
  io::write(g, "velocity", vectors(grains.velocity, first, n).data(), n, 3);
  io::write(g, "force", vectors(grains.force, first, n).data(), n, 3);
  if (grains.rotation()) {
    io::write(g, "angular_velocity", vectors(grains.angular_velocity, first, n).data(), n, 3);
    io::write(g, "torque", vectors(grains.torque, first, n).data(), n, 3);
  }
  io::Handle h = io::create_group(file, "history");
  std::vector<std::int64_t> a, b;
  std::vector<double> shear;
  for (const HistoryEntry& e : history) {
    a.push_back(e.a);
    b.push_back(e.b);
    shear.insert(shear.end(), {e.shear.x, e.shear.y, e.shear.z});
  }
  io::write(h, "a", a.data(), a.size());
  io::write(h, "b", b.data(), b.size());
  io::write(h, "shear", shear.data(), a.size(), 3);
}

/// The datasets of write_rows: grains (kind 0) and contact-history records (kind 1).
std::vector<RowDataset> row_datasets(bool spins) {
  std::vector<RowDataset> out = grain_datasets();
  out.push_back({"grains", "velocity", H5T_NATIVE_DOUBLE, 3, 0});
  out.push_back({"grains", "force", H5T_NATIVE_DOUBLE, 3, 0});
  if (spins) {
    out.push_back({"grains", "angular_velocity", H5T_NATIVE_DOUBLE, 3, 0});
    out.push_back({"grains", "torque", H5T_NATIVE_DOUBLE, 3, 0});
  }
  out.push_back({"history", "a", H5T_NATIVE_INT64, 0, 1});
  out.push_back({"history", "b", H5T_NATIVE_INT64, 0, 1});
  out.push_back({"history", "shear", H5T_NATIVE_DOUBLE, 3, 1});
  return out;
}

/// Throws parallel::AgreedFailure on every rank when any rank has an `error` (the lowest such rank's
/// message, after `prefix`), so no rank goes on into a collective that the failed one never reaches.
void agree_on_failure(MPI_Comm comm, const std::string& error, const std::string& prefix = "DEM checkpoint: ") {
  parallel::throw_first_failure(comm, error.empty() ? std::string() : prefix + error);
}

/// Rows [first, first + count) of /grains, as grains (spins when the model rotates them).
void read_grains(hid_t g, std::size_t first, std::size_t count, bool spins, GrainArrays& out) {
  std::vector<Grain> grains = read_grain_rows(g, first, count);
  const auto vel = io::read_rows<double>(g, "velocity", first, count, 3);
  const auto force = io::read_rows<double>(g, "force", first, count, 3);
  std::vector<double> w, torque;
  if (spins) {
    w = io::read_rows<double>(g, "angular_velocity", first, count, 3);
    torque = io::read_rows<double>(g, "torque", first, count, 3);
  }
  for (std::size_t k = 0; k < count; ++k) {
    const auto at = [&](const std::vector<double>& a) { return Vec3{a[3 * k], a[3 * k + 1], a[3 * k + 2]}; };
    Grain& grain = grains[k];
    grain.velocity = at(vel);
    grain.force = at(force);
    if (spins) {
      grain.angular_velocity = at(w);
      grain.torque = at(torque);
    }
    out.push_local(grain);
  }
}

/// Sends the contact-history records that this rank read (its equal share of a checkpoint written on
/// another rank count) to the ranks holding their grains, so that no rank reads them all
/// (collective). Rank id mod P learns which rank holds grain `id`; a record passes through the one
/// of its grain a, which adds a's holder, then through the one of its grain b, which sends it to
/// both holders (once where they are one rank). A record none of whose grains is held is dropped.
std::vector<HistoryEntry> route_to_holders(MPI_Comm comm, const GrainArrays& g, std::vector<HistoryEntry> records) {
  const int ranks = parallel::size(comm), me = parallel::rank(comm);
  const auto teller = [&](std::int64_t id) { return parallel::rank_for_key(id, ranks); };
  struct Holder {
    std::int64_t id, rank;
  };
  std::vector<std::vector<Holder>> holders_out(static_cast<std::size_t>(ranks));
  for (std::size_t i = 0; i < g.n_local(); ++i) holders_out[teller(g.id[i])].push_back({g.id[i], me});
  std::unordered_map<std::int64_t, std::int64_t> holder;
  for (const Holder& h : parallel::all_to_all(comm, holders_out)) holder.emplace(h.id, h.rank);
  holders_out = {};
  const auto holder_of = [&](std::int64_t id) {
    const auto it = holder.find(id);
    return it == holder.end() ? std::int64_t{-1} : it->second;
  };
  std::vector<std::vector<HistoryEntry>> to_a(static_cast<std::size_t>(ranks));
  for (const HistoryEntry& e : records) to_a[teller(e.a)].push_back(e);
  records = {};
  struct WithHolder {
    HistoryEntry entry;
    std::int64_t holder_a;
  };
  std::vector<std::vector<WithHolder>> to_b(static_cast<std::size_t>(ranks));
  for (const HistoryEntry& e : parallel::all_to_all(comm, to_a)) to_b[teller(e.b)].push_back({e, holder_of(e.a)});
  to_a = {};
  std::vector<std::vector<HistoryEntry>> to_holders(static_cast<std::size_t>(ranks));
  for (const WithHolder& w : parallel::all_to_all(comm, to_b)) {
    const std::int64_t holder_b = holder_of(w.entry.b);
    if (w.holder_a >= 0) to_holders[static_cast<std::size_t>(w.holder_a)].push_back(w.entry);
    if (holder_b >= 0 && holder_b != w.holder_a) to_holders[static_cast<std::size_t>(holder_b)].push_back(w.entry);
  }
  return parallel::all_to_all(comm, to_holders);
}

}  // namespace

void Engine::write_checkpoint(const std::string& path) {
  MPI_Comm comm = domain_.comm();
  const int rank = domain_.rank(), ranks = domain_.size();
  const std::vector<HistoryEntry> history = contact_history();
  const std::size_t n = grains_.n_local();
  const std::vector<std::int64_t> grain_rows = parallel::all_gather(comm, static_cast<std::int64_t>(n));
  const std::vector<std::int64_t> history_rows = parallel::all_gather(comm, static_cast<std::int64_t>(history.size()));
  const std::vector<Piece> pieces = piece_layout(
      {grain_rows, history_rows}, static_cast<std::int64_t>(std::max<std::size_t>(settings_.checkpoint.piece_rows, 1)));
  const bool in_pieces = pieces.size() > 1;

  // A fresh token per checkpoint: the pieces of the previous one stay intact until PATH names these.
  const std::string token = fresh_piece_token(comm);
  const std::filesystem::path target(path);

  std::string error;
  if (in_pieces) {
    try {
      // Part by part: the memory a checkpoint adds is that of one piece, not of the rank's grains.
      std::int64_t first_grain = 0, first_record = 0;
      for (const Piece& p : pieces) {
        if (p.rank != rank) continue;
        io::write_file_atomically(target.parent_path() / piece_name(target, token, p), [&](const io::Handle& file) {
          write_rows(file, grains_, static_cast<std::size_t>(first_grain), static_cast<std::size_t>(p.rows[0]),
                     std::span(history).subspan(static_cast<std::size_t>(first_record),
                                                static_cast<std::size_t>(p.rows[1])));
        });
        first_grain += p.rows[0];
        first_record += p.rows[1];
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
    agree_on_failure(comm, error);
  }
  if (rank == 0) {
    try {
      // A reader (or a restart after SIGKILL) sees the old or the new file, never half of one.
      io::write_file_atomically(path, [&](const io::Handle& file) {
        io::write_string_attribute(file, "format", "sedwave-dem-checkpoint");
        io::write_attribute(file, "version", kCheckpointVersion);
        io::write_attribute(file, "step", step_);
        io::write_attribute(file, "time", time_);
        io::write_attribute(file, "dt", dt_);
        io::write_attribute(file, "ranks", static_cast<std::int32_t>(ranks));
        io::write_attribute(file, "rebuilds", rebuilds_);
        io::write_string_attribute(file, "user_state", user_state_);
        io::write_string_attribute(file, "contact_model", describe(settings_.contact));
        io::Handle inputs = io::create_group(file, "inputs");
        for (const auto& [name, value] : settings_.checkpoint.inputs) io::write_string_attribute(inputs, name, value);

        if (in_pieces) {
          for (const RowDataset& d : row_datasets(grains_.rotation())) join_pieces(file, d, pieces, target, token);
        } else {
          write_rows(file, grains_, 0, n, history);
        }

        io::Handle bodies = io::create_group(file, "bodies");
        std::vector<double> u, v, f;
        for (const RigidBody& body : bodies_) {
          for (const Vec3* x : {&body.displacement(), &body.velocity(), &body.contact_force()}) {
            std::vector<double>& out = x == &body.displacement() ? u : (x == &body.velocity() ? v : f);
            out.insert(out.end(), {x->x, x->y, x->z});
          }
        }
        io::write(bodies, "displacement", u.data(), bodies_.size(), 3);
        io::write(bodies, "velocity", v.data(), bodies_.size(), 3);
        io::write(bodies, "contact_force", f.data(), bodies_.size(), 3);

        io::Handle d = io::create_group(file, "domain");
        io::write(d, "boundaries", domain_.boundaries().data(), domain_.boundaries().size());
        io::write(d, "grain_rows", grain_rows.data(), grain_rows.size());
        io::write(d, "history_rows", history_rows.data(), history_rows.size());
      });
      remove_stale_pieces(target, in_pieces ? token : "");
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  agree_on_failure(comm, error);
}

void Engine::restore_checkpoint(const std::string& path) {
  // Each rank reads only its own part, so one rank can fail where the others do not (a piece it
  // cannot read): the outcome is agreed before the collectives below, or the others would wait in
  // them for ever. Returns whether the ranks keep the rows and slabs they wrote.
  const auto read_own_part = [&]() -> bool {
    io::Handle file = io::open_file(path);
    if (io::read_string_attribute(file, "format") != "sedwave-dem-checkpoint")
      throw std::runtime_error("DEM restart: " + path + " is not a sedwave DEM checkpoint");
    if (io::read_attribute<std::int32_t>(file, "version") != kCheckpointVersion)
      throw std::runtime_error("DEM restart: unsupported checkpoint version in " + path);
    if (!settings_.checkpoint.allow_changed_inputs)
      require_same_inputs(recorded_inputs(file), settings_.checkpoint.inputs, path);
    // The laws decide which state exists (spins, history): a checkpoint only continues the same kind.
    const std::string model = io::read_string_attribute(file, "contact_model");
    if (model != describe(settings_.contact))
      throw std::runtime_error("DEM restart: " + path + " was written with contact model " + model +
                               ", the scene uses " + describe(settings_.contact));
    step_ = io::read_attribute<std::int64_t>(file, "step");
    time_ = io::read_attribute<double>(file, "time");
    dt_ = io::read_attribute<double>(file, "dt");
    rebuilds_ = io::read_attribute<std::int64_t>(file, "rebuilds");
    user_state_ = io::read_string_attribute(file, "user_state");
    const int ranks = io::read_attribute<std::int32_t>(file, "ranks");

    io::Handle d(H5Gopen2(file, "domain", H5P_DEFAULT), H5Gclose, "open /domain");
    // The rows each rank wrote (files from before they were recorded are read as another layout).
    const bool same_layout = ranks == domain_.size() && io::exists(d, "grain_rows");
    if (same_layout) {
      domain_.set_boundaries(io::read_rows<double>(d, "boundaries", 0, static_cast<std::size_t>(ranks) + 1));
    }

    io::Handle bodies(H5Gopen2(file, "bodies", H5P_DEFAULT), H5Gclose, "open /bodies");
    if (io::rows(bodies, "displacement") != bodies_.size())
      throw std::runtime_error("DEM restart: the scene has a different number of rigid bodies than " + path);
    const auto u = io::read_rows<double>(bodies, "displacement", 0, bodies_.size(), 3);
    const auto v = io::read_rows<double>(bodies, "velocity", 0, bodies_.size(), 3);
    const auto f = io::read_rows<double>(bodies, "contact_force", 0, bodies_.size(), 3);
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      bodies_[b].restore({u[3 * b], u[3 * b + 1], u[3 * b + 2]}, {v[3 * b], v[3 * b + 1], v[3 * b + 2]},
                         {f[3 * b], f[3 * b + 1], f[3 * b + 2]});

    // This rank's rows: those it wrote (its grains at the checkpoint; the next rebuild migrates any
    // that left the slab since), or an equal share of them all.
    const auto rank_rows = [&](const std::string& written, std::size_t n) -> std::pair<std::size_t, std::size_t> {
      const auto r = static_cast<std::size_t>(domain_.rank());
      if (same_layout) {
        const auto rows = io::read_rows<std::int64_t>(d, written, 0, static_cast<std::size_t>(ranks));
        std::size_t first = 0;
        for (std::size_t k = 0; k < r; ++k) first += static_cast<std::size_t>(rows[k]);
        return {first, static_cast<std::size_t>(rows[r])};
      }
      const auto p = static_cast<std::size_t>(domain_.size());
      return {r * n / p, (r + 1) * n / p - r * n / p};
    };
    io::Handle g(H5Gopen2(file, "grains", H5P_DEFAULT), H5Gclose, "open /grains");
    require_pieces(io::Handle(H5Dopen2(g, "id", H5P_DEFAULT), H5Dclose, "open /grains/id"), path, "DEM restart");
    const bool spins = grains_.rotation();
    if (spins && !io::exists(g, "angular_velocity"))
      throw std::runtime_error("DEM restart: " + path + " has no spins but the contact model rotates grains");
    grains_ = GrainArrays(spins);
    const auto [first_grain, grain_count] = rank_rows("grain_rows", io::rows(g, "id"));
    for (std::size_t done = 0; done < grain_count; done += kReadChunk)
      read_grains(g, first_grain + done, std::min(kReadChunk, grain_count - done), spins, grains_);

    // History: the records this rank wrote, or an equal share of them all (sent on to the ranks
    // holding their grains below; migration forwards them as grains move).
    pending_history_.clear();
    if (needs_history(model_)) {
      io::Handle h(H5Gopen2(file, "history", H5P_DEFAULT), H5Gclose, "open /history");
      require_pieces(io::Handle(H5Dopen2(h, "a", H5P_DEFAULT), H5Dclose, "open /history/a"), path, "DEM restart");
      const auto [first_record, record_count] = rank_rows("history_rows", io::rows(h, "a"));
      for (std::size_t done = 0; done < record_count; done += kReadChunk) {
        const std::size_t first = first_record + done, count = std::min(kReadChunk, record_count - done);
        const auto a = io::read_rows<std::int64_t>(h, "a", first, count);
        const auto b = io::read_rows<std::int64_t>(h, "b", first, count);
        const auto s = io::read_rows<double>(h, "shear", first, count, 3);
        for (std::size_t k = 0; k < count; ++k)
          pending_history_.push_back({a[k], b[k], {s[3 * k], s[3 * k + 1], s[3 * k + 2]}});
      }
    }
    return same_layout;
  };
  std::string error;
  bool same_layout = false;
  try {
    same_layout = read_own_part();
  } catch (const std::exception& e) {
    error = e.what();
  }
  agree_on_failure(domain_.comm(), error, "");
  if (!same_layout && needs_history(model_))
    pending_history_ = route_to_holders(domain_.comm(), grains_, std::move(pending_history_));
  if (!same_layout) domain_.partition_by_count(grains_, ghost_cutoff_);
  list_valid_ = false;
  history_.clear();
  force_rebuild_ = true;
  last_kinetic_energy_ = -1.0;
  update_global_grain_stats();
  ghost_cutoff_ = 2.0 * max_radius_ + skin_;
  if (settings_.time_step && *settings_.time_step != dt_)
    throw parallel::AgreedFailure(domain_.comm(), "DEM restart: the scene's time step differs from the checkpoint's");
}

}  // namespace sedwave::forward::dem
