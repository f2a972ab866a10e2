// The default grain contact evaluated in SIMD lanes (interface/planar_contacts.hpp) against the DEM
// engine's own composition of the same laws in three dimensions at z = 0 (dem::ContactModel), one
// contact at a time: sliding and sticking contacts, spinning grains of unequal radii, with and
// without the Hertz dashpot; and the slip's inverse mass and the step limit's reach against their
// definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/interface/planar_contacts.hpp"

namespace {

namespace dem = sedwave::forward::dem;
using sedwave::forward::interface::evaluate_planar_contacts;
using sedwave::forward::interface::PlanarContacts;
using sedwave::forward::interface::PlanarPairs;

using Law = dem::ContactModel<dem::HertzNormal, dem::CoulombTanhFriction, dem::NoRolling>;

struct Inputs {  // one array per field of PlanarPairs
  std::vector<double> d2, dx, dy, dvx, dvy, spin_i, spin_j, radius_i, radius_j, inertia_i, inertia_j;
  std::vector<double> effective_radius, damping, reach, inverse_mass, closing_factor, mass_i, mass_j;
};
struct Outputs {  // one array per field of PlanarContacts
  explicit Outputs(std::size_t n)
      : distance(n), nx(n), ny(n), overlap(n), normal_velocity(n), spring(n), dashpot(n), tangential(n),
        inverse_slip_mass(n), reach_energy(n) {}
  std::vector<double> distance, nx, ny, overlap, normal_velocity, spring, dashpot, tangential, inverse_slip_mass,
      reach_energy;
};

/// Steel beads of 2-3 mm radius pressed 10 nm to 3 um together; a third of them nearly sticking
/// (slips below 1/k_s, tanh's rational branch), every one spinning; 257 pairs, so that the lanes'
/// remainder loop runs too.
Inputs random_pairs(const Law& law, std::size_t n) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> radius(2e-3, 3e-3), overlap(1e-8, 3e-6), angle(0.0, 2.0 * std::numbers::pi);
  std::normal_distribution<double> speed(0.0, 0.05), spin(0.0, 20.0);
  std::bernoulli_distribution sticking(1.0 / 3.0);
  Inputs in;
  for (std::size_t k = 0; k < n; ++k) {
    const double ri = radius(rng), rj = radius(rng), a = angle(rng);
    const double d = ri + rj - overlap(rng);
    const double mi = 7850.0 * 4.0 / 3.0 * std::numbers::pi * ri * ri * ri;
    const double mj = 7850.0 * 4.0 / 3.0 * std::numbers::pi * rj * rj * rj;
    const double s = sticking(rng) ? 1e-4 : 1.0;
    in.dx.push_back(d * std::cos(a)), in.dy.push_back(d * std::sin(a));
    in.d2.push_back(in.dx.back() * in.dx.back() + in.dy.back() * in.dy.back());
    in.dvx.push_back(speed(rng)), in.dvy.push_back(speed(rng));
    in.spin_i.push_back(s * spin(rng)), in.spin_j.push_back(s * spin(rng));
    if (s < 1.0) {  // nearly no slip: the relative velocity along the tangent cancels the spins' part
      const double tx = -std::sin(a), ty = std::cos(a);
      const double along = in.dvx.back() * tx + in.dvy.back() * ty;
      const double target = ri * in.spin_i.back() + rj * in.spin_j.back();
      in.dvx.back() += (target - along) * tx, in.dvy.back() += (target - along) * ty;
    }
    in.radius_i.push_back(ri), in.radius_j.push_back(rj);
    in.mass_i.push_back(mi), in.mass_j.push_back(mj);
    in.inertia_i.push_back(0.4 * mi * ri * ri), in.inertia_j.push_back(0.4 * mj * rj * rj);
    const auto pair = law.pair(mi * mj / (mi + mj), ri, rj);
    in.effective_radius.push_back(pair.normal.effective_radius), in.damping.push_back(pair.normal.damping);
    in.reach.push_back(ri + rj), in.inverse_mass.push_back(1.0 / mi + 1.0 / mj);
    const double stiffness = dem::HertzNormal::stiffness(law.normal.effective_modulus, pair.normal.effective_radius);
    in.closing_factor.push_back(1.25 * (mi * mj / (mi + mj)) / stiffness);
  }
  return in;
}

Outputs evaluate(const Law& law, bool damped, bool turning, const Inputs& in) {
  Outputs out(in.d2.size());
  evaluate_planar_contacts(law.normal, law.tangential, damped, turning,
                           PlanarPairs{in.d2.data(), in.dx.data(), in.dy.data(), in.dvx.data(), in.dvy.data(),
                                       in.spin_i.data(), in.spin_j.data(), in.radius_i.data(), in.radius_j.data(),
                                       in.inertia_i.data(), in.inertia_j.data(), in.effective_radius.data(),
                                       in.damping.data(), in.reach.data(), in.inverse_mass.data(),
                                       in.closing_factor.data()},
                           PlanarContacts{out.distance.data(), out.nx.data(), out.ny.data(), out.overlap.data(),
                                          out.normal_velocity.data(), out.spring.data(), out.dashpot.data(),
                                          out.tangential.data(), out.inverse_slip_mass.data(),
                                          out.reach_energy.data()},
                           in.d2.size());
  return out;
}

Law steel_law(double restitution) {
  const double modulus = 200e9 / (2.0 * (1.0 - 0.09));
  const double alpha = restitution < 1.0 ? dem::hertz_alpha_from_restitution(restitution) : 0.0;
  return Law{{modulus, alpha}, {0.3, 100.0}, {}};
}

TEST(PlanarContacts, ForcesAndTorquesAreTheEnginesCompositionInThePlane) {
  for (const double restitution : {1.0, 0.6}) {
    const Law law = steel_law(restitution);
    const bool damped = restitution < 1.0;
    const Inputs in = random_pairs(law, 257);
    const Outputs out = evaluate(law, damped, true, in);
    double largest = 0.0, worst = 0.0, worst_sticking = 0.0;
    for (std::size_t k = 0; k < in.d2.size(); ++k) largest = std::max(largest, std::abs(out.spring[k]));
    for (std::size_t k = 0; k < in.d2.size(); ++k) {
      // The engine: unit normal, overlap and normal velocity from the same offset, in three dimensions.
      const double d = std::sqrt(in.dx[k] * in.dx[k] + in.dy[k] * in.dy[k]);
      const dem::Vec3 n{in.dx[k] / d, in.dy[k] / d, 0.0}, relative{in.dvx[k], in.dvy[k], 0.0};
      const double overlap = in.reach[k] - d, vn = dot(relative, n);
      const dem::ContactPoint point{n, overlap, vn, in.radius_i[k], in.radius_j[k]};
      const Law::Pair pair{{in.effective_radius[k], in.damping[k]}, {}, {}};
      dem::Vec3 unused;
      const dem::PairResult r = law.evaluate(point, pair, relative, {0.0, 0.0, in.spin_i[k]},
                                             {0.0, 0.0, in.spin_j[k]}, 0.0, unused);
      // The lanes' contact: (spring - dashpot v_n) n + F_t t, torques -a F_t about z.
      const double normal_force = out.spring[k] - out.dashpot[k] * out.normal_velocity[k];
      const double tx = -out.ny[k], ty = out.nx[k], ft = out.tangential[k];
      const double fx = normal_force * out.nx[k] + ft * tx, fy = normal_force * out.ny[k] + ft * ty;
      const double arm_i = in.radius_i[k] - 0.5 * out.overlap[k], arm_j = in.radius_j[k] - 0.5 * out.overlap[k];
      const double error =
          std::max({std::abs(fx - r.force.x), std::abs(fy - r.force.y), std::abs(normal_force - r.normal_force),
                    std::abs(-arm_i * ft - r.torque_i.z) / arm_i, std::abs(-arm_j * ft - r.torque_j.z) / arm_j}) /
          largest;
      worst = std::max(worst, error);
      if (std::abs(in.spin_i[k]) < 0.1) worst_sticking = std::max(worst_sticking, error);
      EXPECT_EQ(r.torque_i.x, 0.0);  // the engine's torques are about z alone in the plane
      EXPECT_EQ(r.torque_i.y, 0.0);
    }
    EXPECT_LT(worst, 1e-13) << "restitution " << restitution;
    EXPECT_LT(worst_sticking, 1e-13) << "restitution " << restitution;
    EXPECT_GT(largest, 0.0);
  }
}

TEST(PlanarContacts, SlipInertiaAndReachAreTheirDefinitions) {
  const Law law = steel_law(1.0);
  const Inputs in = random_pairs(law, 33);
  for (const bool turning : {true, false}) {
    const Outputs out = evaluate(law, false, turning, in);
    for (std::size_t k = 0; k < in.d2.size(); ++k) {
      // 1/m_t = 1/m_i + 1/m_j (+ a_i^2/I_i + a_j^2/I_j), with I = (2/5) m r^2 and a = r - delta/2.
      const double delta = in.reach[k] - std::sqrt(in.d2[k]);
      const double ai = in.radius_i[k] - 0.5 * delta, aj = in.radius_j[k] - 0.5 * delta;
      double expected = 1.0 / in.mass_i[k] + 1.0 / in.mass_j[k];
      if (turning) expected += ai * ai / (0.4 * in.mass_i[k] * in.radius_i[k] * in.radius_i[k]) +
                               aj * aj / (0.4 * in.mass_j[k] * in.radius_j[k] * in.radius_j[k]);
      EXPECT_NEAR(out.inverse_slip_mass[k], expected, 1e-13 * expected);
      // delta_max^(5/2) = delta^(5/2) + (5/4)(m/k) v_n^2 when closing.
      const double vn = out.normal_velocity[k];
      const double reach = std::pow(delta, 2.5) + (vn < 0.0 ? in.closing_factor[k] * vn * vn : 0.0);
      EXPECT_NEAR(out.reach_energy[k], reach, 1e-13 * reach);
    }
  }
}

}  // namespace
