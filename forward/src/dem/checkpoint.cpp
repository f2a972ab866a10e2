// HDF5 checkpoint and restart of the DEM engine.
//
// File layout (all datasets in one file, format attribute "sedwave-dem-checkpoint", version 1):
//   /            attributes step, time, dt, ranks, rebuilds, user_state
//   /grains      id, group, body, radius, mass [N]; position, velocity, force [N,3];
//                angular_velocity, torque [N,3] when the model rotates grains
//   /history     a, b [M] (smaller, larger global id), shear [M,3] (seen from a)
//   /bodies      displacement, velocity, contact_force [B,3]
//   /domain      boundaries [ranks+1]; grain_rows [ranks+1]: rank r wrote rows
//                grain_rows[r] to grain_rows[r+1] of /grains
// Rank 0 gathers and writes (the only time one rank holds all grains). On restart every rank reads
// only its part: on the same number of ranks the rows it wrote, on another number an equal block
// of rows (then the slabs are cut anew); each reads an equal block of /history and sends every
// record to the ranks holding its grains.
#include <array>
#include <cstdio>
#include <map>
#include <string>
#include <unordered_map>

#include "sedwave/io/hdf5.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr std::int32_t kCheckpointVersion = 1;
constexpr std::size_t kReadChunk = 1 << 16;

/// The part [first, first + count) of `n` rows that rank `r` of `p` reads: equal blocks in order.
std::array<std::size_t, 2> block_of(std::size_t n, std::size_t r, std::size_t p) {
  const std::size_t first = r * (n / p) + std::min(r, n % p);
  return {first, n / p + (r < n % p ? 1 : 0)};
}

/// Rows [first, first + count) of /grains, as grains (read in chunks).
std::vector<Grain> read_grains(hid_t g, std::size_t first, std::size_t count, bool spins) {
  std::vector<Grain> out;
  out.reserve(count);
  for (std::size_t at = first; at < first + count; at += kReadChunk) {
    const std::size_t m = std::min(kReadChunk, first + count - at);
    const auto id = io::read_rows<std::int64_t>(g, "id", at, m);
    const auto group = io::read_rows<std::int32_t>(g, "group", at, m);
    const auto body = io::read_rows<std::int32_t>(g, "body", at, m);
    const auto radius = io::read_rows<double>(g, "radius", at, m);
    const auto mass = io::read_rows<double>(g, "mass", at, m);
    const auto x = io::read_rows<double>(g, "position", at, m, 3);
    const auto vel = io::read_rows<double>(g, "velocity", at, m, 3);
    const auto force = io::read_rows<double>(g, "force", at, m, 3);
    std::vector<double> w, torque;
    if (spins) {
      w = io::read_rows<double>(g, "angular_velocity", at, m, 3);
      torque = io::read_rows<double>(g, "torque", at, m, 3);
    }
    for (std::size_t k = 0; k < m; ++k) {
      const auto vec = [&](const std::vector<double>& a) { return Vec3{a[3 * k], a[3 * k + 1], a[3 * k + 2]}; };
      Grain grain{id[k], group[k], body[k], radius[k], mass[k], vec(x), vec(vel), {}, vec(force), {}};
      if (spins) {
        grain.angular_velocity = vec(w);
        grain.torque = vec(torque);
      }
      out.push_back(grain);
    }
  }
  return out;
}

/// Rows [first, first + count) of /history (read in chunks).
std::vector<HistoryEntry> read_history(hid_t h, std::size_t first, std::size_t count) {
  std::vector<HistoryEntry> out;
  out.reserve(count);
  for (std::size_t at = first; at < first + count; at += kReadChunk) {
    const std::size_t m = std::min(kReadChunk, first + count - at);
    const auto a = io::read_rows<std::int64_t>(h, "a", at, m);
    const auto b = io::read_rows<std::int64_t>(h, "b", at, m);
    const auto s = io::read_rows<double>(h, "shear", at, m, 3);
    for (std::size_t k = 0; k < m; ++k) out.push_back({a[k], b[k], {s[3 * k], s[3 * k + 1], s[3 * k + 2]}});
  }
  return out;
}

/// Sends every history record to the ranks holding its grain a or b (collective). No rank learns
/// where every grain is: rank id mod ranks keeps the holder of grain id (a directory spread over
/// the ranks), and records travel through the directory of each of their grains. A rank holding
/// both grains may receive a record twice; HistoryMap keeps one.
std::vector<HistoryEntry> route_history(MPI_Comm comm, const GrainArrays& g, const std::vector<HistoryEntry>& read) {
  const int me = parallel::rank(comm);
  const auto p = static_cast<std::int64_t>(parallel::size(comm));
  const auto directory = [p](std::int64_t id) { return static_cast<std::size_t>(((id % p) + p) % p); };
  std::vector<std::vector<std::array<std::int64_t, 2>>> held(static_cast<std::size_t>(p));
  for (std::size_t i = 0; i < g.n_local(); ++i) held[directory(g.id[i])].push_back({g.id[i], me});
  std::unordered_map<std::int64_t, int> holder;
  for (const auto& [id, rank] : parallel::all_to_all(comm, held)) holder.emplace(id, static_cast<int>(rank));

  std::vector<std::vector<HistoryEntry>> ask(static_cast<std::size_t>(p));
  for (const HistoryEntry& e : read) {
    ask[directory(e.a)].push_back(e);
    if (directory(e.b) != directory(e.a)) ask[directory(e.b)].push_back(e);
  }
  std::vector<std::vector<HistoryEntry>> deliver(static_cast<std::size_t>(p));
  for (const HistoryEntry& e : parallel::all_to_all(comm, ask)) {
    int first_holder = -1;
    for (const std::int64_t id : {e.a, e.b}) {
      if (directory(id) != static_cast<std::size_t>(me)) continue;
      const auto it = holder.find(id);
      if (it == holder.end() || it->second == first_holder) continue;
      deliver[static_cast<std::size_t>(it->second)].push_back(e);
      first_holder = it->second;
    }
  }
  return parallel::all_to_all(comm, deliver);
}

template <typename T, typename F>
std::vector<T> column(const std::vector<Grain>& grains, F field) {
  std::vector<T> out;
  out.reserve(grains.size());
  for (const Grain& g : grains) out.push_back(field(g));
  return out;
}

std::vector<double> vectors(const std::vector<Grain>& grains, Vec3 Grain::*field) {
  std::vector<double> out;
  out.reserve(3 * grains.size());
  for (const Grain& g : grains) {
    const Vec3& v = g.*field;
    out.insert(out.end(), {v.x, v.y, v.z});
  }
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

}  // namespace

void Engine::write_checkpoint(const std::string& path) {
  const std::vector<std::uint64_t> grain_counts = parallel::all_gather(domain_.comm(), std::uint64_t{n_local()});
  const std::vector<Grain> all = gather_grains(*this);
  const std::vector<HistoryEntry> history = parallel::gather_on_root(domain_.comm(), contact_history());
  std::string error;
  if (domain_.rank() == 0) {
    try {
      // A reader (or a restart after SIGKILL) sees the old or the new file, never half of one.
      io::write_file_atomically(path, [&](const io::Handle& file) {
        io::write_string_attribute(file, "format", "sedwave-dem-checkpoint");
        io::write_attribute(file, "version", kCheckpointVersion);
        io::write_attribute(file, "step", step_);
        io::write_attribute(file, "time", time_);
        io::write_attribute(file, "dt", dt_);
        io::write_attribute(file, "ranks", static_cast<std::int32_t>(domain_.size()));
        io::write_attribute(file, "rebuilds", rebuilds_);
        io::write_string_attribute(file, "user_state", user_state_);
        io::write_string_attribute(file, "contact_model", describe(settings_.contact));
        io::Handle inputs = io::create_group(file, "inputs");
        for (const auto& [name, value] : settings_.checkpoint.inputs) io::write_string_attribute(inputs, name, value);

        io::Handle g = io::create_group(file, "grains");
        const std::size_t n = all.size();
        io::write(g, "id", column<std::int64_t>(all, [](const Grain& x) { return x.id; }).data(), n);
        io::write(g, "group", column<std::int32_t>(all, [](const Grain& x) { return x.group; }).data(), n);
        io::write(g, "body", column<std::int32_t>(all, [](const Grain& x) { return x.body; }).data(), n);
        io::write(g, "radius", column<double>(all, [](const Grain& x) { return x.radius; }).data(), n);
        io::write(g, "mass", column<double>(all, [](const Grain& x) { return x.mass; }).data(), n);
        io::write(g, "position", vectors(all, &Grain::position).data(), n, 3);
        io::write(g, "velocity", vectors(all, &Grain::velocity).data(), n, 3);
        io::write(g, "force", vectors(all, &Grain::force).data(), n, 3);
        if (grains_.rotation()) {
          io::write(g, "angular_velocity", vectors(all, &Grain::angular_velocity).data(), n, 3);
          io::write(g, "torque", vectors(all, &Grain::torque).data(), n, 3);
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
        std::vector<std::int64_t> grain_rows{0};  // gathered in rank order
        for (const std::uint64_t c : grain_counts) grain_rows.push_back(grain_rows.back() + static_cast<std::int64_t>(c));
        io::write(d, "grain_rows", grain_rows.data(), grain_rows.size());
      });
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "write failed on rank 0";
    }
  }
  parallel::broadcast(domain_.comm(), error);  // every rank throws rank 0's error
  if (!error.empty()) throw std::runtime_error("DEM checkpoint: " + error);
}

void Engine::restore_checkpoint(const std::string& path) {
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
  const bool same_layout = ranks == domain_.size();
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

  // Grains: on the same ranks, the rows this rank wrote (older checkpoints without grain_rows:
  // as on other ranks); on other ranks an equal block of rows, the slabs cut anew below.
  io::Handle g(H5Gopen2(file, "grains", H5P_DEFAULT), H5Gclose, "open /grains");
  const std::size_t n = io::rows(g, "id");
  const bool spins = grains_.rotation();
  if (spins && !io::exists(g, "angular_velocity"))
    throw std::runtime_error("DEM restart: " + path + " has no spins but the contact model rotates grains");
  const auto r = static_cast<std::size_t>(domain_.rank());
  const auto p = static_cast<std::size_t>(domain_.size());
  std::array<std::size_t, 2> mine = block_of(n, r, p);
  if (same_layout && io::exists(d, "grain_rows")) {
    const auto rows = io::read_rows<std::int64_t>(d, "grain_rows", r, 2);
    if (rows[0] < 0 || rows[1] < rows[0] || static_cast<std::size_t>(rows[1]) > n)
      throw std::runtime_error("DEM restart: " + path + " has inconsistent /domain/grain_rows");
    mine = {static_cast<std::size_t>(rows[0]), static_cast<std::size_t>(rows[1] - rows[0])};
  }
  grains_ = GrainArrays(spins);
  for (const Grain& grain : read_grains(g, mine[0], mine[1], spins)) grains_.push_local(grain);

  // History records go to the ranks holding their grains (migration forwards them as grains move).
  pending_history_.clear();
  if (needs_history(model_)) {
    io::Handle h(H5Gopen2(file, "history", H5P_DEFAULT), H5Gclose, "open /history");
    const auto [first, count] = block_of(io::rows(h, "a"), r, p);
    pending_history_ = route_history(domain_.comm(), grains_, read_history(h, first, count));
  }
  if (!same_layout) domain_.partition_by_count(grains_, ghost_cutoff_);
  list_valid_ = false;
  history_.clear();
  force_rebuild_ = true;
  last_kinetic_energy_ = -1.0;
  update_global_grain_stats();
  ghost_cutoff_ = 2.0 * max_radius_ + skin_;
  if (settings_.time_step && *settings_.time_step != dt_)
    throw std::runtime_error("DEM restart: the scene's time step differs from the checkpoint's");
}

}  // namespace sedwave::forward::dem
