#pragma once
// Grain state as a structure of arrays (SoA): each field is one contiguous array, so the force loop
// streams exactly the fields its contact laws read. The first n_local() entries are the grains this
// rank owns; the entries after them are ghosts: read-only copies of grains owned by a neighbouring
// rank, or periodic images (on one rank the same mechanism serves both). Periodic images are copies
// only while the neighbour list is built; after that, read them through their GhostSource.
//
// Units: the engine is unit-agnostic. Any consistent set works (SI, or the thesis's d = 1, rho = 1).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sedwave/forward/dem/vec3.hpp"

namespace sedwave::forward::dem {

/// Body index of a grain integrated on its own (flowing grains, probes). Grains with body k >= 1
/// belong to rigid body k-1 of the engine (walls) and move with it.
inline constexpr std::int32_t kFreeBody = 0;

/// One grain, complete: the unit of input, MPI migration and checkpoints (trivially copyable).
struct Grain {
  std::int64_t id = 0;        ///< stable global id (unique over all ranks)
  std::int32_t group = 0;     ///< user tag (e.g. 0 flow, 1 lower wall, 2 upper wall, 3 probes)
  std::int32_t body = kFreeBody;  ///< kFreeBody, or 1 + index of the rigid body carrying it
  double radius = 0.5;
  double mass = 1.0;
  Vec3 position;
  Vec3 velocity;
  Vec3 angular_velocity;  ///< ignored unless the contact model rotates grains
  Vec3 force;             ///< last total force (kept for restarts: velocity Verlet needs it)
  Vec3 torque;
};

/// Where a ghost's data live on this rank: a periodic image made here is its source grain (a local
/// one) plus a shift; a ghost received from another rank is itself, unshifted.
struct GhostSource {
  std::int32_t index = 0;
  Vec3 shift;
};

class GrainArrays {
 public:
  explicit GrainArrays(bool rotation = false) : rotation_(rotation) {}

  [[nodiscard]] bool rotation() const { return rotation_; }
  [[nodiscard]] std::size_t n_local() const { return n_local_; }
  [[nodiscard]] std::size_t n_ghost() const { return id.size() - n_local_; }
  [[nodiscard]] std::size_t n_total() const { return id.size(); }

  /// Appends an owned grain; only valid while there are no ghosts.
  void push_local(const Grain& g);
  /// Appends a ghost copy. Its force and torque start at zero: under "newton on" they collect the
  /// reactions of pairs computed here, which reverse communication sends to the owner.
  void push_ghost(const Grain& g);
  /// Drops all ghosts.
  void clear_ghosts();
  /// The complete state of entry i (local or ghost).
  [[nodiscard]] Grain grain(std::size_t i) const;
  /// Keeps the local grains whose keep flag is set, in order (ghosts must have been cleared).
  void keep_local(std::span<const std::uint8_t> keep);
  /// Reorders the local grains: new entry k is old entry order[k] (ghosts must have been cleared).
  void permute_local(std::span<const std::uint32_t> order);

  // Fields, n_total entries each (angular_velocity and torque only when rotation()).
  std::vector<Vec3> position;
  std::vector<Vec3> velocity;
  std::vector<Vec3> angular_velocity;  ///< empty unless rotation()
  std::vector<Vec3> force;
  std::vector<Vec3> torque;            ///< empty unless rotation()
  std::vector<double> radius;
  std::vector<double> mass;
  /// 1/m for free grains, 0 for rigid-body grains: a wall acts as infinitely heavy in a contact
  /// (effective mass 1/(1/m_i + 1/m_j) = m_free), as LAMMPS does for frozen grains.
  std::vector<double> inv_mass;
  std::vector<std::int64_t> id;
  std::vector<std::int32_t> group;
  std::vector<std::int32_t> body;

 private:
  void push_common(const Grain& g);
  bool rotation_;
  std::size_t n_local_ = 0;
};

}  // namespace sedwave::forward::dem
