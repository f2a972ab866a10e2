#pragma once
// The one pair-force loop, templated on the contact model (so the laws are inlined and absent laws
// cost nothing), on whether the guard watches overlaps this step, and on whether a pore fluid's
// lubrication acts between the grains (NoLubrication: not a single instruction of it is compiled in).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/fluid.hpp"
#include "sedwave/forward/dem/grains.hpp"
#include "sedwave/forward/dem/neighbor_list.hpp"

// On x86-64 the force loop is compiled twice, for the baseline ISA and for AVX+FMA, and the loader
// picks the second on CPUs that have it (GCC function multiversioning). The three-operand AVX forms
// and fused multiply-adds take about 20 % off the loop; a portable build (SEDWAVE_NATIVE off) keeps
// running everywhere. FMA rounds a*b+c once, so the two clones agree to round-off, not bit for bit.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__FMA__)
#define SEDWAVE_FMA_CLONES __attribute__((target_clones("fma", "default")))
#else
#define SEDWAVE_FMA_CLONES
#endif

namespace sedwave::forward::dem {

/// The lubrication argument of a dry force loop.
struct NoLubrication {};

/// Which listed pairs one call of the force loop evaluates. While the ghosts received from other
/// ranks travel, the engine evaluates the pairs among the grains it holds (kHeld: locals and
/// periodic images); once they have arrived, the pairs with them (kRemote). kAll = both, in one pass.
enum class PairSubset { kAll, kHeld, kRemote };

/// Largest overlap seen by a watched force evaluation.
struct OverlapWatch {
  double worst_ratio = 0.0;  ///< overlap / smaller radius
  double overlap = 0.0;
  std::int64_t id_i = -1;
  std::int64_t id_j = -1;
};

/// Fills the pair table for the current neighbour list: each listed pair's constants (the laws'
/// coefficients that depend on masses and radii), so that the force loop does not recompute them
/// at every step. Masses and radii do not change during a run; the table is rebuilt with the list.
template <class Model>
void tabulate_pairs(const Model& model, const GrainArrays& g, const NeighborList& list, PairTable<Model>& table) {
  // A few percent of headroom rather than std::vector's doubling: the list's length drifts a little
  // between rebuilds, and the table is part of the per-grain memory budget.
  if (list.n_pairs() > table.pairs.capacity()) table.pairs.reserve(list.n_pairs() + list.n_pairs() / 16);
  table.pairs.resize(list.n_pairs());
  const std::int32_t* partner = list.partners().data();
  for (std::size_t i = 0; i < list.n_rows(); ++i)
    for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k) {
      const auto j = static_cast<std::size_t>(partner[k]);
      // A rigid-wall grain has 1/m = 0 (infinitely heavy); the list never pairs two of them.
      table.pairs[k] = model.pair(1.0 / (g.inv_mass[i] + g.inv_mass[j]), g.radius[i], g.radius[j]);
    }
}

/// Fills `films` with each listed pair's FilmPair (parallel to the list's partners), for a
/// lubricated force loop's LubricationEvaluator.
inline void tabulate_films(const FluidSpec& fluid, const GrainArrays& g, const NeighborList& list,
                           std::vector<FilmPair>& films) {
  films.resize(list.n_pairs());
  const std::int32_t* partner = list.partners().data();
  for (std::size_t i = 0; i < list.n_rows(); ++i)
    for (std::uint32_t k = list.row_begin(i); k < list.row_end(i); ++k)
      films[k] = LubricationEvaluator::pair(fluid, g.radius[i], g.radius[static_cast<std::size_t>(partner[k])]);
}

/// Adds the contact forces (and torques) of all listed pairs to g.force (g.torque): +F on the local
/// row grain, -F on a local partner. A ghost partner gets -F too under "newton on" (reverse
/// communication delivers it); under "newton off" its owner computes its share. `table` is
/// tabulate_pairs() of the same list. `lubrication` (a LubricationEvaluator) adds the squeeze-film
/// force of every listed pair closer than its cut-off, touching or not; the list must then reach
/// that far (NeighborList::build's interaction_gap). `subset` picks the pairs (kHeld then kRemote
/// adds the same forces as kAll, summed in another order).
template <class Model, bool kWatch, class Lubrication = NoLubrication>
SEDWAVE_FMA_CLONES OverlapWatch accumulate_contact_forces(const Model& model, GrainArrays& g, const NeighborList& list,
                                       const PairTable<Model>& table, std::span<Vec3> history, double dt,
                                       [[maybe_unused]] const Lubrication& lubrication = {},
                                       PairSubset subset = PairSubset::kAll) {
  constexpr bool kFluid = !std::is_same_v<Lubrication, NoLubrication>;
  OverlapWatch watch;
  const Vec3* x = g.position.data();
  const Vec3* v = g.velocity.data();
  const double* radius = g.radius.data();
  Vec3* force = g.force.data();
  [[maybe_unused]] const Vec3* spin = Model::rotates ? g.angular_velocity.data() : nullptr;
  [[maybe_unused]] Vec3* torque = Model::rotates ? g.torque.data() : nullptr;
  const std::int32_t* partner = list.partners().data();
  const std::uint8_t* shift_code = list.shift_codes().data();
  const Vec3* shifts = list.shifts().data();
  const typename Model::Pair* pair = table.pairs.data();

  // One loop over the rows for every subset (a lambda per row, called from three loops, is not
  // inlined into this function's AVX + FMA clone: 40 % slower). kRemote visits only the rows that
  // have remote pairs; each row's pairs are [first, end).
  const std::span<const std::uint32_t> remote_rows = list.remote_rows();
  const bool remote_only = subset == PairSubset::kRemote;
  const std::size_t n_rows = remote_only ? remote_rows.size() : list.n_rows();
  for (std::size_t row = 0; row < n_rows; ++row) {
    const std::size_t i = remote_only ? remote_rows[row] : row;
    const std::uint32_t first = remote_only ? list.remote_begin(i) : list.row_begin(i);
    const std::uint32_t end = subset == PairSubset::kHeld ? list.remote_begin(i) : list.row_end(i);
    const Vec3 xi = x[i];
    const Vec3 vi = v[i];
    const double ri = radius[i];
    [[maybe_unused]] Vec3 wi;
    if constexpr (Model::rotates) wi = spin[i];
    Vec3 fi;
    [[maybe_unused]] Vec3 ti;

    // Force on i from listed pair k with partner j (shifted when a periodic image; local partners
    // have shift code 0, the zero shift). A rotating model also adds its torque on i to ti and
    // returns the torque on j in tj.
    auto pair_force = [&](std::uint32_t k, std::size_t j, [[maybe_unused]] Vec3& tj) -> Vec3 {
      const Vec3 d = xi - (x[j] + shifts[shift_code[k]]);
      const double r2 = norm2(d);
      const double reach = ri + radius[j];
      if constexpr (Model::rotates) {
        if (!(r2 < reach * reach)) {
          if constexpr (Model::needs_history) history[k] = Vec3{};
          tj = Vec3{};
          if constexpr (kFluid) {
            const double gap = std::sqrt(r2) - reach;
            return lubrication.multiple_of_d(k, gap, dot(vi - v[j], d) / r2) * d;
          }
          return {};
        }
      }
      // Non-rotating models evaluate every listed pair (all lie within the skin, so distance > 0)
      // and mask the result instead of branching: "touching?" is unpredictable, and without the
      // branch consecutive pairs overlap in the pipeline (about 2x faster for Hooke). The root's
      // latency dominates, so little waits for it: 1/r^2 is divided beside the sqrt, not after it;
      // the normal velocity is d . v_rel (ready before the root) times 1/distance; a non-rotating
      // model's force is a multiple of d, so the unit normal is never formed (27 % less time per
      // pair than n = d/|d| first, then v_n = v_rel . n, with m_eff divided after the root).
      const double distance = std::sqrt(r2);
      const double inv_r2 = 1.0 / r2;
      const double inv_distance = distance * inv_r2;
      const Vec3 v_rel = vi - v[j];
      const double approach = dot(v_rel, d);  // |d| v_n
      // A separated pair gets overlap 0 (laws such as Hertz take roots of it) and a masked result,
      // through a 0/1 factor: GCC compiles `touching ? x : 0.0` and std::max into jumps, which are
      // mispredicted half the time. The factor tests the distance itself, so the overlap is never
      // negative (r2 < reach^2 may hold while the rounded sqrt reaches `reach`).
      const double in_contact = static_cast<double>(distance < reach);
      const ContactPoint c{inv_distance * d, in_contact * (reach - distance), approach * inv_distance, ri, radius[j]};
      if constexpr (kWatch) {
        const double ratio = c.overlap / std::min(ri, radius[j]);
        if (ratio > watch.worst_ratio) watch = {ratio, c.overlap, g.id[i], g.id[j]};
      }
      if constexpr (!Model::rotates) {
        // F = (spring - dashpot v_n) n = (spring / |d| - dashpot (d . v_rel) / |d|^2) d. For Hooke
        // the dashpot term does not depend on the root at all.
        const auto& law = model.normal;
        const auto& p = pair[k].normal;
        const double spring = law.spring(c.overlap, p) * inv_distance;
        const double dashpot = law.dashpot_at(c.overlap, p) * approach * inv_r2;
        if constexpr (kFluid) {
          // The film's force, -C v_n / h on i, is (-C (d . v_rel) / |d|^2) / h times d, with h the
          // gap clamped at the roughness. 1/h = 1/(|d| - reach) = (|d| + reach) / (|d|^2 - reach^2)
          // has a denominator q that needs no root: clamped, q = max(|d|^2, (reach + h_r)^2) -
          // reach^2. Over the common denominator |d|^2 q, contact and film need one division, which
          // runs beside the root as the dry loop's does (after the root, its latency made
          // lubricated pairs 1.5x slower than dry ones):
          //   multiple of d = (q contact - C (d . v_rel) (max(|d|, reach + h_r) + reach)) / (|d|^2 q),
          // contact = spring |d| - dashpot (d . v_rel) (the dry loop's force times |d|^2).
          const FilmPair& f = lubrication.film(k);
          const double q = std::max(r2 - f.reach2, f.clamp);
          const double inverse = 1.0 / (r2 * q);
          const double in_range = static_cast<double>(r2 < f.cut2);
          const double contact = law.spring(c.overlap, p) * distance - law.dashpot_at(c.overlap, p) * approach;
          const double film =
              (in_range * f.film * approach) * (std::max(distance, reach + lubrication.roughness()) + reach);
          return ((q * (in_contact * contact) - film) * inverse) * d;
        }
        return (in_contact * (spring - dashpot)) * d;
      } else {
        Vec3 no_history;
        Vec3& slot = Model::needs_history ? history[k] : no_history;
        const PairResult r = model.evaluate(c, pair[k], v_rel, wi, spin[j], dt, slot);
        ti += r.torque_i;
        tj = r.torque_j;
        if constexpr (kFluid)
          return r.force + lubrication.multiple_of_d(k, distance - reach, approach * inv_r2) * d;
        return r.force;
      }
    };

    // Partners before `with_reaction` take -F: local ones, and ghosts under newton on (a periodic
    // image's reaction lands on its source grain, a remote ghost's is sent home by
    // Domain::reverse_forces). Under newton off the ghosts' owners compute their own share.
    const std::uint32_t with_reaction = list.newton() ? end : std::clamp(list.ghost_begin(i), first, end);
    Vec3 tj;
    for (std::uint32_t k = first; k < with_reaction; ++k) {
      const auto j = static_cast<std::size_t>(partner[k]);
      const Vec3 f = pair_force(k, j, tj);
      fi += f;
      force[j] -= f;
      if constexpr (Model::rotates) torque[j] += tj;
    }
    for (std::uint32_t k = with_reaction; k < end; ++k) fi += pair_force(k, static_cast<std::size_t>(partner[k]), tj);
    force[i] += fi;
    if constexpr (Model::rotates) torque[i] += ti;
  }
  return watch;
}

}  // namespace sedwave::forward::dem
