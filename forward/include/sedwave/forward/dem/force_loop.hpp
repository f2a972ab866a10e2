#pragma once
// The one pair-force loop, templated on the contact model (so the laws are inlined and absent laws
// cost nothing) and on whether the guard watches overlaps this step.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/dem/neighbor_list.hpp"

namespace sedwave::forward::dem {

/// Largest overlap seen by a watched force evaluation.
struct OverlapWatch {
  double worst_ratio = 0.0;  ///< overlap / smaller radius
  double overlap = 0.0;
  std::int64_t id_i = -1;
  std::int64_t id_j = -1;
};

/// Adds the contact forces (and torques) of all listed pairs to g.force (g.torque): +F on the local
/// row grain, -F on a local partner. A ghost partner gets -F too under "newton on" (reverse
/// communication delivers it); under "newton off" its owner computes its share.
template <class Model, bool kWatch>
OverlapWatch accumulate_contact_forces(const Model& model, GrainArrays& g, const NeighborList& list,
                                       std::span<Vec3> history, double dt) {
  OverlapWatch watch;
  const Vec3* x = g.position.data();
  const Vec3* v = g.velocity.data();
  const double* radius = g.radius.data();
  const double* inv_mass = g.inv_mass.data();
  Vec3* force = g.force.data();
  [[maybe_unused]] const Vec3* spin = Model::rotates ? g.angular_velocity.data() : nullptr;
  [[maybe_unused]] Vec3* torque = Model::rotates ? g.torque.data() : nullptr;
  const std::int32_t* partner = list.partners().data();
  const std::uint8_t* shift_code = list.shift_codes().data();
  const Vec3* shifts = list.shifts().data();
  Vec3 no_history;

  for (std::size_t i = 0; i < list.n_rows(); ++i) {
    const Vec3 xi = x[i];
    const Vec3 vi = v[i];
    const double ri = radius[i];
    const double inv_mi = inv_mass[i];
    [[maybe_unused]] Vec3 wi;
    if constexpr (Model::rotates) wi = spin[i];
    Vec3 fi;
    [[maybe_unused]] Vec3 ti;

    // Returns the pair result, or nothing when the grains do not touch. `xj`: the partner's position,
    // shifted when it is a periodic image.
    auto contact = [&](std::uint32_t k, std::size_t j, const Vec3& xj, PairResult& out) -> bool {
      const Vec3 d = xi - xj;
      const double r2 = norm2(d);
      const double reach = ri + radius[j];
      const bool touching = r2 < reach * reach;
      if constexpr (Model::rotates) {
        if (!touching) {
          if constexpr (Model::needs_history) history[k] = Vec3{};
          return false;
        }
      }
      // Non-rotating models evaluate every listed pair (all lie within the skin, so distance > 0)
      // and mask the result instead of branching: "touching?" is unpredictable, and without the
      // branch consecutive pairs overlap in the pipeline (about 2x faster for Hooke).
      const double distance = std::sqrt(r2);
      // One division for both 1/distance and m_eff = 1/(1/m_i + 1/m_j).
      const double inv_mass_sum = inv_mi + inv_mass[j];
      const double inv_product = 1.0 / (distance * inv_mass_sum);
      const Vec3 n = (inv_product * inv_mass_sum) * d;
      const Vec3 v_rel = vi - v[j];
      // A separated pair gets overlap 0 (laws such as Hertz take roots of it) and a masked result,
      // through a 0/1 factor: GCC compiles `touching ? x : 0.0` and std::max into jumps, which are
      // mispredicted half the time. The factor tests the distance itself, so the overlap is never
      // negative (r2 < reach^2 may hold while the rounded sqrt reaches `reach`).
      const double in_contact = static_cast<double>(distance < reach);
      const double overlap = in_contact * (reach - distance);
      const ContactPoint c{n, overlap, dot(v_rel, n), inv_product * distance, ri, radius[j]};
      if constexpr (kWatch) {
        const double ratio = c.overlap / std::min(ri, radius[j]);
        if (ratio > watch.worst_ratio) watch = {ratio, c.overlap, g.id[i], g.id[j]};
      }
      Vec3 wj;
      if constexpr (Model::rotates) wj = spin[j];
      Vec3& slot = Model::needs_history ? history[k] : no_history;
      out = model.evaluate(c, v_rel, wi, wj, dt, slot);
      if constexpr (!Model::rotates) {
        out.force *= in_contact;
        return true;
      }
      return touching;
    };

    // Local partners (unshifted) take -F; so do ghost partners under newton on (a periodic image's
    // reaction lands on its source grain, a remote ghost's is sent home by Domain::reverse_forces).
    const std::uint32_t ghosts = list.ghost_begin(i);
    const std::uint32_t with_reaction = list.newton() ? list.row_end(i) : ghosts;
    const std::uint32_t end = list.row_end(i);
    PairResult r;
    auto with_reaction_on_j = [&](std::size_t j) {
      fi += r.force;
      force[j] -= r.force;
      if constexpr (Model::rotates) {
        ti += r.torque_i;
        torque[j] += r.torque_j;
      }
    };
    for (std::uint32_t k = list.row_begin(i); k < ghosts; ++k) {
      const auto j = static_cast<std::size_t>(partner[k]);
      if (contact(k, j, x[j], r)) with_reaction_on_j(j);
    }
    for (std::uint32_t k = ghosts; k < with_reaction; ++k) {
      const auto j = static_cast<std::size_t>(partner[k]);
      if (contact(k, j, x[j] + shifts[shift_code[k]], r)) with_reaction_on_j(j);
    }
    for (std::uint32_t k = with_reaction; k < end; ++k) {
      const auto j = static_cast<std::size_t>(partner[k]);
      if (!contact(k, j, x[j] + shifts[shift_code[k]], r)) continue;
      fi += r.force;
      if constexpr (Model::rotates) ti += r.torque_i;
    }
    force[i] += fi;
    if constexpr (Model::rotates) torque[i] += ti;
  }
  return watch;
}

}  // namespace sedwave::forward::dem
