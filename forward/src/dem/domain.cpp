#include "sedwave/forward/dem/domain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "sedwave/forward/parallel/collectives.hpp"

namespace sedwave::forward::dem {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

Domain::Domain(MPI_Comm comm, const Box& box) : comm_(comm), box_(box) {
  rank_ = parallel::rank(comm_);
  size_ = parallel::size(comm_);
  std::vector<double> b(static_cast<std::size_t>(size_) + 1);
  for (int r = 0; r <= size_; ++r) b[r] = box.lo.z + box.length(2) * r / size_;
  set_boundaries(std::move(b));
}

void Domain::set_boundaries(std::vector<double> boundaries) {
  if (boundaries.size() != static_cast<std::size_t>(size_) + 1)
    throw std::invalid_argument("Domain: need size()+1 boundaries");
  boundaries_ = std::move(boundaries);
  boundaries_.front() = box_.periodic[2] ? box_.lo.z : -kInf;
  boundaries_.back() = box_.periodic[2] ? box_.hi.z : kInf;
}

int Domain::owner(double z) const {
  const auto it = std::upper_bound(boundaries_.begin() + 1, boundaries_.end() - 1, z);
  return static_cast<int>(it - (boundaries_.begin() + 1));
}

void Domain::clamp_thickness(double min_thickness) {
  // Interior slabs must be at least one ghost cutoff thick (ghosts come from adjacent slabs only).
  const auto n = static_cast<std::size_t>(size_);
  if (n < 2) return;
  const bool periodic = box_.periodic[2];
  if (periodic && box_.length(2) < static_cast<double>(n) * min_thickness)
    throw std::runtime_error("Domain: box too short for " + std::to_string(size_) +
                             " slabs of thickness >= the ghost cutoff " + std::to_string(min_thickness));
  for (std::size_t k = periodic ? 1 : 2; k < n; ++k)
    boundaries_[k] = std::max(boundaries_[k], boundaries_[k - 1] + min_thickness);
  if (periodic) {
    for (std::size_t k = n - 1; k >= 1; --k)
      boundaries_[k] = std::min(boundaries_[k], boundaries_[k + 1] - min_thickness);
  }
}

void Domain::partition_by_count(const GrainArrays& g, double min_thickness) {
  if (size_ == 1) return;
  double lo = kInf, hi = -kInf;
  for (std::size_t i = 0; i < g.n_local(); ++i) {
    lo = std::min(lo, g.position[i].z);
    hi = std::max(hi, g.position[i].z);
  }
  lo = parallel::min(comm_, lo);
  hi = parallel::max(comm_, hi);
  if (box_.periodic[2]) {
    lo = box_.lo.z;
    hi = box_.hi.z;
  }
  constexpr int bins = 8192;
  std::vector<double> histogram(bins, 0.0);
  const double width = std::max(hi - lo, 1e-300) / bins;
  for (std::size_t i = 0; i < g.n_local(); ++i)
    histogram[std::clamp(static_cast<int>((g.position[i].z - lo) / width), 0, bins - 1)] += 1.0;
  parallel::sum(comm_, std::span(histogram));
  const double total = std::accumulate(histogram.begin(), histogram.end(), 0.0);
  std::vector<double> b(boundaries_);
  double cumulative = 0.0;
  int next = 1;
  for (int k = 0; k < bins && next < size_; ++k) {
    cumulative += histogram[k];
    while (next < size_ && cumulative >= total * next / size_) b[next++] = lo + (k + 1) * width;
  }
  for (; next < size_; ++next) b[next] = hi;
  set_boundaries(std::move(b));
  clamp_thickness(min_thickness);
}

void Domain::balance(double my_work, const GrainArrays& g, double min_thickness) {
  if (size_ == 1) return;
  const std::vector<double> work = parallel::all_gather(comm_, my_work);
  // Work is assumed uniform within each slab; open end slabs are cut at the grains' extent.
  double lo = boundaries_.front(), hi = boundaries_.back();
  if (!box_.periodic[2]) {
    double z_lo = kInf, z_hi = -kInf;
    for (std::size_t i = 0; i < g.n_local(); ++i) {
      z_lo = std::min(z_lo, g.position[i].z);
      z_hi = std::max(z_hi, g.position[i].z);
    }
    lo = parallel::min(comm_, z_lo);
    hi = parallel::max(comm_, z_hi);
  }
  std::vector<double> edge(boundaries_);
  edge.front() = std::min(lo, edge[1]);
  edge.back() = std::max(hi, edge[edge.size() - 2]);
  const double total = std::accumulate(work.begin(), work.end(), 0.0);
  if (!(total > 0.0)) return;
  std::vector<double> b(boundaries_);
  double cumulative = 0.0;
  int slab = 0;
  for (int k = 1; k < size_; ++k) {
    const double target = total * k / size_;
    while (slab < size_ - 1 && cumulative + work[slab] < target) cumulative += work[slab++];
    const double fraction = work[slab] > 0.0 ? (target - cumulative) / work[slab] : 0.5;
    const double ideal = edge[slab] + std::clamp(fraction, 0.0, 1.0) * (edge[slab + 1] - edge[slab]);
    b[k] = boundaries_[k] + 0.5 * (ideal - boundaries_[k]);  // half steps: no oscillation
  }
  set_boundaries(std::move(b));
  clamp_thickness(min_thickness);
}

void Domain::migrate(GrainArrays& g, std::vector<HistoryEntry>& history) {
  if (g.n_ghost() != 0) throw std::logic_error("Domain::migrate with ghosts present");
  const std::size_t n = g.n_local();
  for (std::size_t i = 0; i < n; ++i) box_.wrap(g.position[i]);
  if (size_ == 1) return;
  std::vector<std::vector<Grain>> grains_out(static_cast<std::size_t>(size_));
  std::vector<std::uint8_t> keep(n, 1);
  std::unordered_map<std::int64_t, int> departing;  // id -> destination
  for (std::size_t i = 0; i < n; ++i) {
    const int dest = owner(g.position[i].z);
    if (dest == rank_) continue;
    keep[i] = 0;
    grains_out[dest].push_back(g.grain(i));
    departing.emplace(g.id[i], dest);
  }
  std::vector<std::vector<HistoryEntry>> history_out(static_cast<std::size_t>(size_));
  if (!departing.empty())
    for (const HistoryEntry& e : history) {
      const auto a = departing.find(e.a);
      const auto b = departing.find(e.b);
      if (a != departing.end()) history_out[a->second].push_back(e);
      if (b != departing.end() && (a == departing.end() || b->second != a->second))
        history_out[b->second].push_back(e);
    }
  for (int r = 0; r < size_; ++r)
    rebuild_bytes_sent_ += grains_out[r].size() * sizeof(Grain) + history_out[r].size() * sizeof(HistoryEntry);
  g.keep_local(keep);
  for (const Grain& grain : parallel::all_to_all(comm_, grains_out)) g.push_local(grain);
  const std::vector<HistoryEntry> arrived = parallel::all_to_all(comm_, history_out);
  history.insert(history.end(), arrived.begin(), arrived.end());
}

void Domain::image_swaps(GrainArrays& g, int axis, double cutoff) {
  if (box_.length(axis) < cutoff)
    throw std::runtime_error("Domain: periodic length along axis " + std::to_string(axis) +
                             " is shorter than the ghost cutoff " + std::to_string(cutoff));
  const std::size_t candidates = g.n_total();
  for (const int side : {0, 1}) {
    Swap s;
    s.send_to = s.recv_from = rank_;
    s.shift[axis] = side == 0 ? box_.length(axis) : -box_.length(axis);
    for (std::size_t i = 0; i < candidates; ++i) {
      const double c = g.position[i][axis];
      if (side == 0 ? c < box_.lo[axis] + cutoff : c >= box_.hi[axis] - cutoff)
        s.send.push_back(static_cast<std::int32_t>(i));
    }
    s.recv_first = g.n_total();
    s.recv_count = s.send.size();
    for (const std::int32_t i : s.send) {
      Grain ghost = g.grain(static_cast<std::size_t>(i));
      ghost.position += s.shift;
      g.push_ghost(ghost);
      // An image of an image (an edge or corner) resolves to the local grain behind both.
      const GhostSource behind = source_of(g, static_cast<std::size_t>(i));
      ghost_sources_.push_back({behind.index, behind.shift + s.shift});
    }
    swaps_.push_back(std::move(s));
  }
}

namespace {

/// What a neighbouring slab needs of a grain to hold it as a ghost: 104 bytes rather than the 152 of
/// a whole Grain (no force, no torque, which a ghost starts without).
struct GhostRecord {
  std::int64_t id;
  std::int32_t group;
  std::int32_t body;
  double radius;
  double mass;
  Vec3 position;
  Vec3 velocity;
  Vec3 angular_velocity;
};

static_assert(sizeof(GhostRecord) == 104 && sizeof(Grain) == 152, "docs/dem.md quotes both sizes");

Grain ghost_from(const GhostRecord& r) {
  Grain g;
  g.id = r.id;
  g.group = r.group;
  g.body = r.body;
  g.radius = r.radius;
  g.mass = r.mass;
  g.position = r.position;
  g.velocity = r.velocity;
  g.angular_velocity = r.angular_velocity;
  return g;
}

constexpr int kGhostBuildTag = 12;

}  // namespace

void Domain::neighbour_swaps(GrainArrays& g, std::size_t n_candidates, double cutoff) {
  const bool periodic = box_.periodic[2];
  const int below = rank_ > 0 ? rank_ - 1 : (periodic ? size_ - 1 : MPI_PROC_NULL);
  const int above = rank_ < size_ - 1 ? rank_ + 1 : (periodic ? 0 : MPI_PROC_NULL);
  const parallel::RecordType<GhostRecord> record;
  // Both directions are posted before either is received; each receive learns its length from the
  // message itself (probe), so no count travels ahead of the records.
  std::vector<GhostRecord> out[2];
  MPI_Request sent[2];
  const std::size_t first_swap = swaps_.size();
  for (const int side : {0, 1}) {
    const bool downwards = side == 0;
    Swap s;
    s.send_to = downwards ? below : above;
    s.recv_from = downwards ? above : below;
    if (downwards && rank_ == 0 && periodic) s.shift.z = box_.length(2);
    if (!downwards && rank_ == size_ - 1 && periodic) s.shift.z = -box_.length(2);
    if (s.send_to != MPI_PROC_NULL)
      for (std::size_t i = 0; i < n_candidates; ++i) {
        const double z = g.position[i].z;
        if (downwards ? z < slab_lo() + cutoff : z >= slab_hi() - cutoff) s.send.push_back(static_cast<std::int32_t>(i));
      }
    out[side].reserve(s.send.size());
    for (const std::int32_t i : s.send) {
      const auto k = static_cast<std::size_t>(i);
      out[side].push_back({g.id[k], g.group[k], g.body[k], g.radius[k], g.mass[k], g.position[k] + s.shift,
                           g.velocity[k], g.rotation() ? g.angular_velocity[k] : Vec3{}});
    }
    if (s.send_to != MPI_PROC_NULL) rebuild_bytes_sent_ += out[side].size() * sizeof(GhostRecord);
    MPI_Isend(out[side].data(), parallel::mpi_count(out[side].size()), record.get(), s.send_to, kGhostBuildTag + side,
              comm_, &sent[side]);
    swaps_.push_back(std::move(s));
  }
  for (const int side : {0, 1}) {
    Swap& s = swaps_[first_swap + static_cast<std::size_t>(side)];
    MPI_Status status;
    MPI_Probe(s.recv_from, kGhostBuildTag + side, comm_, &status);
    int count = 0;
    MPI_Get_count(&status, record.get(), &count);
    std::vector<GhostRecord> in(static_cast<std::size_t>(count));
    MPI_Recv(in.data(), count, record.get(), s.recv_from, kGhostBuildTag + side, comm_, MPI_STATUS_IGNORE);
    s.recv_first = g.n_total();
    s.recv_count = in.size();
    for (const GhostRecord& r : in) {
      ghost_sources_.push_back({static_cast<std::int32_t>(g.n_total()), Vec3{}});
      g.push_ghost(ghost_from(r));
    }
  }
  MPI_Waitall(2, sent, MPI_STATUSES_IGNORE);
}

void Domain::build_ghosts(GrainArrays& g, double cutoff) {
  g.clear_ghosts();
  swaps_.clear();
  ghost_sources_.clear();
  for (int axis = 0; axis < 2; ++axis)
    if (box_.periodic[axis]) image_swaps(g, axis, cutoff);
  if (size_ == 1) {
    if (box_.periodic[2]) image_swaps(g, 2, cutoff);
    return;
  }
  for (int r = 1; r < size_; ++r)
    if (boundaries_[r + 1] - boundaries_[r] < cutoff && r + 1 < size_)
      throw std::runtime_error("Domain: slab " + std::to_string(r) + " is thinner than the ghost cutoff");
  neighbour_swaps(g, g.n_total(), cutoff);  // candidates: locals and x/y images, not z ghosts
}

void Domain::clear_forces(GrainArrays& g) const {
  auto clear = [&g](std::size_t first, std::size_t count) {
    std::fill_n(g.force.begin() + static_cast<std::ptrdiff_t>(first), count, Vec3{});
    if (g.rotation()) std::fill_n(g.torque.begin() + static_cast<std::ptrdiff_t>(first), count, Vec3{});
  };
  clear(0, g.n_local());
  for (const Swap& s : swaps_)
    if (!is_image(s, rank_)) clear(s.recv_first, s.recv_count);
}

// Message tags: one per swap, so that two swaps between the same pair of ranks (two ranks along a
// periodic z) cannot take each other's messages.
constexpr int kGhostTag = 100;
constexpr int kForceTag = 100000;

void Domain::post(std::vector<double>& send, int to, std::vector<double>& receive, int from, int tag) {
  requests_.emplace_back();
  MPI_Irecv(receive.data(), parallel::mpi_count(receive.size()), MPI_DOUBLE, from, tag, comm_, &requests_.back());
  requests_.emplace_back();
  MPI_Isend(send.data(), parallel::mpi_count(send.size()), MPI_DOUBLE, to, tag, comm_, &requests_.back());
  if (to != MPI_PROC_NULL) halo_bytes_sent_ += send.size() * sizeof(double);
}

void Domain::wait_for_messages() {
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  requests_.clear();
}

void Domain::start_ghost_update(const GrainArrays& g) {
  if (!requests_.empty()) throw std::logic_error("Domain: a halo exchange is already under way");
  const bool spin = g.rotation();
  const std::size_t per = spin ? 9 : 6;
  for (std::size_t n = 0; n < swaps_.size(); ++n) {
    Swap& s = swaps_[n];
    if (is_image(s, rank_)) continue;  // read through ghost_sources instead
    s.send_values.resize(s.send.size() * per);
    for (std::size_t k = 0; k < s.send.size(); ++k) {
      // A sent image is read from its source: the image itself is not refreshed.
      const GhostSource from = source_of(g, static_cast<std::size_t>(s.send[k]));
      const auto i = static_cast<std::size_t>(from.index);
      double* out = s.send_values.data() + k * per;
      const Vec3 p = g.position[i] + from.shift + s.shift;
      const Vec3& v = g.velocity[i];
      out[0] = p.x; out[1] = p.y; out[2] = p.z;
      out[3] = v.x; out[4] = v.y; out[5] = v.z;
      if (spin) {
        const Vec3& w = g.angular_velocity[i];
        out[6] = w.x; out[7] = w.y; out[8] = w.z;
      }
    }
    s.recv_values.resize(s.recv_count * per);
    post(s.send_values, s.send_to, s.recv_values, s.recv_from, kGhostTag + static_cast<int>(n));
  }
}

void Domain::finish_ghost_update(GrainArrays& g) {
  wait_for_messages();
  const bool spin = g.rotation();
  const std::size_t per = spin ? 9 : 6;
  for (const Swap& s : swaps_) {
    if (is_image(s, rank_)) continue;
    for (std::size_t k = 0; k < s.recv_count; ++k) {
      const double* in = s.recv_values.data() + k * per;
      const std::size_t j = s.recv_first + k;
      g.position[j] = {in[0], in[1], in[2]};
      g.velocity[j] = {in[3], in[4], in[5]};
      if (spin) g.angular_velocity[j] = {in[6], in[7], in[8]};
    }
  }
}

void Domain::update_ghosts(GrainArrays& g) {
  start_ghost_update(g);
  finish_ghost_update(g);
}

void Domain::start_reverse_forces(const GrainArrays& g) {
  if (!requests_.empty()) throw std::logic_error("Domain: a halo exchange is already under way");
  const bool spin = g.rotation();
  const std::size_t per = spin ? 6 : 3;
  for (std::size_t n = 0; n < swaps_.size(); ++n) {
    Swap& s = swaps_[n];
    if (is_image(s, rank_)) continue;
    // The ghosts received from recv_from return their forces to it; ours arrive from send_to.
    s.recv_values.resize(s.recv_count * per);  // now the outgoing forces
    for (std::size_t k = 0; k < s.recv_count; ++k) {
      double* out = s.recv_values.data() + k * per;
      const Vec3& f = g.force[s.recv_first + k];
      out[0] = f.x; out[1] = f.y; out[2] = f.z;
      if (spin) {
        const Vec3& t = g.torque[s.recv_first + k];
        out[3] = t.x; out[4] = t.y; out[5] = t.z;
      }
    }
    s.send_values.resize(s.send.size() * per);  // now the returning forces
    post(s.recv_values, s.recv_from, s.send_values, s.send_to, kForceTag + static_cast<int>(n));
  }
}

void Domain::finish_reverse_forces(GrainArrays& g) {
  wait_for_messages();
  const bool spin = g.rotation();
  const std::size_t per = spin ? 6 : 3;
  // Periodic images made here collect nothing (the list applies their reactions to the source
  // grains); a force returned for a grain that was sent as an image goes to its source. The swaps
  // are summed in reverse order of their building, as they always were.
  for (auto swap = swaps_.rbegin(); swap != swaps_.rend(); ++swap) {
    const Swap& s = *swap;
    if (is_image(s, rank_)) continue;
    for (std::size_t k = 0; k < s.send.size(); ++k) {
      const double* in = s.send_values.data() + k * per;
      const auto i = static_cast<std::size_t>(source_of(g, static_cast<std::size_t>(s.send[k])).index);
      g.force[i] += Vec3{in[0], in[1], in[2]};
      if (spin) g.torque[i] += Vec3{in[3], in[4], in[5]};
    }
  }
}

void Domain::reverse_forces(GrainArrays& g) {
  start_reverse_forces(g);
  finish_reverse_forces(g);
}

}  // namespace sedwave::forward::dem
