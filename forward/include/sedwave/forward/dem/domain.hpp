#pragma once
// Spatial domain decomposition along z (the long axis of the channels) in slabs.
//
// Rank r owns the grains with boundaries[r] <= z < boundaries[r+1]. Along an open z axis the end
// slabs reach to -inf / +inf, so no grain is ever lost; along a periodic z axis they end at the box.
// Every rank spans the whole box in x and y.
//
// Ghosts are built in LAMMPS's swap order: x images, then y images (of locals and x images, which
// covers the edges), then z copies from the neighbouring slabs (periodic images across the z ends,
// or self-images on one rank). One Swap records what was sent where with which periodic shift, so
// the per-step ghost update replays the same swaps with fresh positions and velocities.
//
// A periodic image made on this rank is a copy only while the neighbour list is built: the list
// then refers to its source grain plus the image's shift (ghost_sources), so images are never
// refreshed and never collect forces. In a W = 3 channel that is 2.8 images per grain which the
// per-step update and the force loop no longer touch. Ghosts received from other ranks stay copies.
//
// Under "newton on" a pair across a rank boundary is computed on one side only; reverse_forces()
// sends the reaction collected on the ghost back along the same swaps in reverse order.
//
// Migration sends departing grains (and the contact history records that involve them) straight to
// their owner with one all-to-all, so any displacement, setup scatter and restart is the same path.
// Load balancing moves the slab boundaries so that the measured work per rank is equal.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "sedwave/forward/dem/box.hpp"
#include "sedwave/forward/dem/contact_history.hpp"
#include "sedwave/forward/dem/grains.hpp"

namespace sedwave::forward::dem {

class Domain {
 public:
  Domain(MPI_Comm comm, const Box& box);

  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] const Box& box() const { return box_; }
  [[nodiscard]] Box& box() { return box_; }
  [[nodiscard]] const std::vector<double>& boundaries() const { return boundaries_; }
  [[nodiscard]] double slab_lo() const { return boundaries_[rank_]; }
  [[nodiscard]] double slab_hi() const { return boundaries_[rank_ + 1]; }
  /// Rank owning height z.
  [[nodiscard]] int owner(double z) const;

  /// Sets the interior boundaries (size()+1 values; the ends are reset to the box or +-inf).
  void set_boundaries(std::vector<double> boundaries);
  /// Equal-count slabs from a histogram of the grains' heights (collective).
  void partition_by_count(const GrainArrays& g, double min_thickness);
  /// Moves boundaries to equalise work (collective): each rank's work is spread uniformly over its
  /// slab, the cumulative work is inverted, and the boundaries move halfway to the result.
  void balance(double my_work, const GrainArrays& g, double min_thickness);

  /// Wraps local grains into the periodic box and sends those outside the slab to their owners,
  /// with the history records that involve them (collective; ghosts must have been cleared).
  void migrate(GrainArrays& g, std::vector<HistoryEntry>& history);
  /// Rebuilds the ghosts within `cutoff` of each face (collective).
  void build_ghosts(GrainArrays& g, double cutoff);
  /// Where each ghost's data live on this rank, indexed by ghost number (grain index - n_local).
  /// Valid until the next build_ghosts.
  [[nodiscard]] const std::vector<GhostSource>& ghost_sources() const { return ghost_sources_; }
  /// Sets the forces (and torques) that the force loop accumulates to zero: the owned grains' and
  /// those of ghosts received from other ranks (periodic images made here never collect any).
  void clear_forces(GrainArrays& g) const;
  /// Refreshes the ghosts received from other ranks (positions, velocities, spins); periodic images
  /// made on this rank are left as built (read them through ghost_sources). Collective.
  void update_ghosts(GrainArrays& g);
  /// update_ghosts() in two halves: start_ghost_update() packs what changed of every sent grain and
  /// posts all messages (to both neighbours at once) without waiting; finish_ghost_update() waits
  /// for them and writes the ghosts. Between the two, the ghosts received from other ranks hold old
  /// values and nothing may start another exchange; the rest of the grains may be used.
  void start_ghost_update(const GrainArrays& g);
  void finish_ghost_update(GrainArrays& g);
  /// "Newton on": sends the forces (and torques) collected on ghosts received from other ranks back
  /// to their owners, which add them to the source grains (collective).
  void reverse_forces(GrainArrays& g);
  /// reverse_forces() in two halves, as for the ghost update: the ghosts' forces are read when
  /// starting, the owners' forces are added when finishing.
  void start_reverse_forces(const GrainArrays& g);
  void finish_reverse_forces(GrainArrays& g);

  /// Bytes this rank has sent to other ranks since construction: by the per-step halo exchange
  /// (ghost updates and returned forces), and when rebuilding (migration and new ghosts).
  [[nodiscard]] std::uint64_t halo_bytes_sent() const { return halo_bytes_sent_; }
  [[nodiscard]] std::uint64_t rebuild_bytes_sent() const { return rebuild_bytes_sent_; }

 private:
  struct Swap {
    std::vector<std::int32_t> send;  // indices sent (locals or earlier ghosts)
    Vec3 shift;                      // periodic shift applied to sent positions
    int send_to = MPI_PROC_NULL;     // rank_ itself for a local image swap
    int recv_from = MPI_PROC_NULL;
    std::size_t recv_first = 0;
    std::size_t recv_count = 0;
    // Message buffers of the per-step exchange (kept between steps: no allocation per step).
    std::vector<double> send_values;  // about the sent grains: their state out, their forces back
    std::vector<double> recv_values;  // about the received ghosts: their state in, their forces out
  };
  void image_swaps(GrainArrays& g, int axis, double cutoff);
  /// The z swaps with the slabs below and above (ghosts from the one above first, then below).
  void neighbour_swaps(GrainArrays& g, std::size_t n_candidates, double cutoff);
  void clamp_thickness(double min_thickness);
  /// Posts a non-blocking receive and send (counted in halo_bytes_sent) for wait_for_messages().
  void post(std::vector<double>& send, int to, std::vector<double>& receive, int from, int tag);
  void wait_for_messages();
  /// The grain whose data grain i mirrors on this rank, and the shift to add to its position.
  [[nodiscard]] GhostSource source_of(const GrainArrays& g, std::size_t i) const {
    if (i < g.n_local()) return {static_cast<std::int32_t>(i), Vec3{}};
    return ghost_sources_[i - g.n_local()];
  }
  [[nodiscard]] static bool is_image(const Swap& s, int rank) { return s.send_to == rank && s.recv_from == rank; }

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  Box box_;
  std::vector<double> boundaries_;
  std::vector<Swap> swaps_;
  std::vector<GhostSource> ghost_sources_;
  std::vector<MPI_Request> requests_;  // the exchange under way
  std::uint64_t halo_bytes_sent_ = 0;
  std::uint64_t rebuild_bytes_sent_ = 0;
};

}  // namespace sedwave::forward::dem
