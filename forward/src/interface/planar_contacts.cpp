#include "sedwave/forward/interface/planar_contacts.hpp"

#include <cmath>

#include "sedwave/forward/dem/contact/tanh_over_x.hpp"

namespace sedwave::forward::interface {

namespace {

// Two clones of the loop, chosen by the processor when the program loads (GCC's function
// multiversioning). AVX2 without FMA: a fused multiply-add would round differently from the baseline.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SEDWAVE_LANE_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define SEDWAVE_LANE_CLONES
#endif
// GCC does not take the restrict pointers below as proof that the arrays do not overlap; ivdep says
// so (other compilers vectorise on restrict or not at all).
#if defined(__GNUC__) && !defined(__clang__)
#define SEDWAVE_ARRAYS_APART _Pragma("GCC ivdep")
#else
#define SEDWAVE_ARRAYS_APART
#endif

// `Damped` a template argument: a dashpot evaluated on a condition would be a branch in the loop.
// `turning` (1 or 0) multiplies what turning adds to the slip's inverse mass, for the same reason.
template <bool Damped>
SEDWAVE_LANE_CLONES void contacts_in_lanes(const dem::HertzNormal& normal, const dem::CoulombTanhFriction& friction,
                                           double turning, const PlanarPairs& in, const PlanarContacts& out,
                                           std::size_t count) {
  const double *__restrict d2 = in.d2, *__restrict dx = in.dx, *__restrict dy = in.dy, *__restrict dvx = in.dvx,
                           *__restrict dvy = in.dvy, *__restrict spin_i = in.spin_i, *__restrict spin_j = in.spin_j,
                           *__restrict radius_i = in.radius_i, *__restrict radius_j = in.radius_j,
                           *__restrict inertia_i = in.inertia_i, *__restrict inertia_j = in.inertia_j,
                           *__restrict effective_radius = in.effective_radius, *__restrict damping = in.damping,
                           *__restrict reach = in.reach, *__restrict inverse_mass = in.inverse_mass,
                           *__restrict closing_factor = in.closing_factor;
  double *__restrict distance = out.distance, *__restrict nx_out = out.nx, *__restrict ny_out = out.ny,
                     *__restrict overlap_out = out.overlap, *__restrict vn_out = out.normal_velocity,
                     *__restrict spring_out = out.spring, *__restrict dashpot_out = out.dashpot,
                     *__restrict tangential = out.tangential, *__restrict inverse_slip_mass = out.inverse_slip_mass,
                     *__restrict reach_out = out.reach_energy;
  // Arrays apart and no control flow: the compiler runs this loop in SIMD lanes.
  SEDWAVE_ARRAYS_APART
  for (std::size_t c = 0; c < count; ++c) {
    const double d = std::sqrt(d2[c]);
    const double overlap = reach[c] - d;
    const double nx = dx[c] / d, ny = dy[c] / d;
    const double vn = dvx[c] * nx + dvy[c] * ny;
    const dem::HertzNormal::Pair pair{effective_radius[c], damping[c]};
    const double spring = normal.spring(overlap, pair);
    const double dashpot = Damped ? normal.dashpot_at(overlap, pair) : 0.0;
    const double normal_force = spring - dashpot * vn;
    const double arm_i = radius_i[c] - 0.5 * overlap, arm_j = radius_j[c] - 0.5 * overlap;
    const double slip = -dvx[c] * ny + dvy[c] * nx - (arm_i * spin_i[c] + arm_j * spin_j[c]);
    tangential[c] =
        -friction.drag(std::abs(slip), normal_force, [](double x) { return dem::tanh_over_x_in_lanes(x); }) * slip;
    distance[c] = d, nx_out[c] = nx, ny_out[c] = ny, overlap_out[c] = overlap, vn_out[c] = vn;
    spring_out[c] = spring, dashpot_out[c] = dashpot;
    inverse_slip_mass[c] = inverse_mass[c] + turning * (turning_inverse_mass(arm_i, inertia_i[c]) +
                                                        turning_inverse_mass(arm_j, inertia_j[c]));
    reach_out[c] = reach_energy(overlap, vn, closing_factor[c]);
  }
}

}  // namespace

void evaluate_planar_contacts(const dem::HertzNormal& normal, const dem::CoulombTanhFriction& friction, bool damped,
                              bool turning, const PlanarPairs& pairs, const PlanarContacts& contacts,
                              std::size_t count) {
  const double turns = turning ? 1.0 : 0.0;
  if (damped)
    contacts_in_lanes<true>(normal, friction, turns, pairs, contacts, count);
  else
    contacts_in_lanes<false>(normal, friction, turns, pairs, contacts, count);
}

}  // namespace sedwave::forward::interface
