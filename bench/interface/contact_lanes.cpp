// How fast can a planar Hertz + Coulomb-tanh contact (the interface's default grain contact) be
// evaluated? Three forms over the same contacts, each checked against the first:
//   engine:  one contact at a time through the DEM engine's parts (ContactModel::
//            evaluate_with_normal_force, Vec3 with z = 0), as GranularPlate::add_grain_pair does;
//   planar:  the same laws written for the plane, one contact at a time (std::sqrt, std::exp);
//   lanes:   the planar form over arrays with the branch-free tanh(x)/x (dem::tanh_over_x_in_lanes),
//            so that the compiler evaluates several contacts at a time in SIMD lanes;
//   library: the interface's kernel (interface::evaluate_planar_contacts), whose AVX2 clone is
//            chosen at run time where the processor has it, whatever the instruction set compiled for.
// No books, no scatter: the contact's force and torques alone, written to arrays.
//   bench/interface/contact_lanes.sh
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/dem/contact/tanh_over_x.hpp"
#include "sedwave/forward/interface/planar_contacts.hpp"

namespace dem = sedwave::forward::dem;

struct Contacts {  // structure of arrays: pair geometry and motion (i minus j)
  std::vector<double> dx, dy, dvx, dvy, spin_i, spin_j;
  double radius = 2.5e-3;
};
struct Out {
  std::vector<double> fx, fy, ti, tj;
  explicit Out(std::size_t n) : fx(n), fy(n), ti(n), tj(n) {}
};

struct Scratch {  // the library's input and output arrays
  std::vector<double> d2, radius, inertia, effective_radius, zero, reach, inverse_mass;
  std::vector<double> distance, nx, ny, overlap, normal_velocity, spring, dashpot, tangential, inverse_slip_mass,
      reach_energy;
  void fill(const Contacts& c) {
    const std::size_t n = c.dx.size();
    if (d2.size() == n) return;
    for (auto* v : {&d2, &radius, &inertia, &effective_radius, &zero, &reach, &inverse_mass, &distance, &nx, &ny,
                    &overlap, &normal_velocity, &spring, &dashpot, &tangential, &inverse_slip_mass, &reach_energy})
      v->assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      d2[k] = c.dx[k] * c.dx[k] + c.dy[k] * c.dy[k];
      radius[k] = c.radius, inertia[k] = 1.0, effective_radius[k] = 0.5 * c.radius, reach[k] = 2.0 * c.radius;
    }
  }
  sedwave::forward::interface::PlanarPairs pairs(const Contacts& c) const {
    return {d2.data(),     c.dx.data(),     c.dy.data(),     c.dvx.data(),          c.dvy.data(), c.spin_i.data(),
            c.spin_j.data(), radius.data(), radius.data(),   inertia.data(),        inertia.data(),
            effective_radius.data(), zero.data(), reach.data(), inverse_mass.data(), zero.data()};
  }
  sedwave::forward::interface::PlanarContacts contacts() {
    return {distance.data(), nx.data(),      ny.data(),         overlap.data(),           normal_velocity.data(),
            spring.data(),   dashpot.data(), tangential.data(), inverse_slip_mass.data(), reach_energy.data()};
  }
};

constexpr double kModulus = 200e9 / (2.0 * (1.0 - 0.09)), kFriction = 0.3, kScale = 100.0;

Contacts make(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> overlap(1e-8, 3e-6), angle(0.0, 2.0 * std::numbers::pi);
  std::normal_distribution<double> speed(0.0, 0.05), spin(0.0, 20.0);
  std::bernoulli_distribution sticking(0.3);
  Contacts c;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = 2.0 * c.radius - overlap(rng), a = angle(rng);
    c.dx.push_back(d * std::cos(a)), c.dy.push_back(d * std::sin(a));
    const double s = sticking(rng) ? 1e-3 : 1.0;  // slips below 1/k_s: the rational branch of tanh
    c.dvx.push_back(s * speed(rng)), c.dvy.push_back(s * speed(rng));
    c.spin_i.push_back(s * spin(rng)), c.spin_j.push_back(s * spin(rng));
  }
  return c;
}

void engine(const Contacts& c, Out& o) {
  const dem::ContactModel<dem::HertzNormal, dem::CoulombTanhFriction> model{{kModulus, 0.0}, {kFriction, kScale}, {}};
  const auto pair = model.pair(1.0, c.radius, c.radius);
  for (std::size_t k = 0; k < c.dx.size(); ++k) {
    const double d2 = c.dx[k] * c.dx[k] + c.dy[k] * c.dy[k];
    const double d = std::sqrt(d2), overlap = 2.0 * c.radius - d;
    const double nx = c.dx[k] / d, ny = c.dy[k] / d;
    const dem::Vec3 relative{c.dvx[k], c.dvy[k], 0.0};
    const double vn = relative.x * nx + relative.y * ny;
    const dem::ContactPoint point{{nx, ny, 0.0}, overlap, vn, c.radius, c.radius};
    const double spring = model.normal.spring(overlap, pair.normal);
    dem::Vec3 shear;
    const dem::PairResult r = model.evaluate_with_normal_force(spring, point, pair, relative, {0.0, 0.0, c.spin_i[k]},
                                                               {0.0, 0.0, c.spin_j[k]}, 0.0, shear);
    o.fx[k] = r.force.x, o.fy[k] = r.force.y, o.ti[k] = r.torque_i.z, o.tj[k] = r.torque_j.z;
  }
}

// The same laws in the plane. Tangent t = (-n_y, n_x); the engine's slip v_rel - v_n n +
// n x (arm_i w_i + arm_j w_j) z is t times v_rel . t - arm_i w_i - arm_j w_j; the torque on i is
// -arm_i (n x F_t) . z.
template <class TanhOverX>
inline void planar_contact(const Contacts& c, std::size_t k, Out& o, TanhOverX tanh_over_x) {
  const double r = c.radius, effective_radius = 0.5 * r;
  const double d2 = c.dx[k] * c.dx[k] + c.dy[k] * c.dy[k];
  const double d = std::sqrt(d2), overlap = 2.0 * r - d;
  const double inverse_d = 1.0 / d, nx = c.dx[k] * inverse_d, ny = c.dy[k] * inverse_d;
  const double fn = (4.0 / 3.0) * kModulus * std::sqrt(effective_radius * overlap) * overlap;
  const double arm = r - 0.5 * overlap;
  const double slip = -c.dvx[k] * ny + c.dvy[k] * nx - arm * (c.spin_i[k] + c.spin_j[k]);
  const double ft = -kFriction * fn * kScale * tanh_over_x(kScale * std::abs(slip)) * slip;  // along t
  o.fx[k] = fn * nx - ft * ny, o.fy[k] = fn * ny + ft * nx;
  o.ti[k] = -arm * ft, o.tj[k] = -arm * ft;
}

void planar(const Contacts& c, Out& o) {
  for (std::size_t k = 0; k < c.dx.size(); ++k) planar_contact(c, k, o, [](double x) { return dem::tanh_over_x(x); });
}

void lanes(const Contacts& c, Out& o) {
  const std::size_t n = c.dx.size();
#pragma omp simd
  for (std::size_t k = 0; k < n; ++k) planar_contact(c, k, o, [](double x) { return dem::tanh_over_x_in_lanes(x); });
}

// The library's lanes (interface/planar_contacts.hpp): the interface's own kernel, AVX2 chosen at run
// time where the processor has it, with the normal and inertia outputs the step limit reads too.
void library(const Contacts& c, Out& o) {
  static Scratch s;
  s.fill(c);
  const dem::HertzNormal normal{kModulus, 0.0};
  const dem::CoulombTanhFriction friction{kFriction, kScale};
  sedwave::forward::interface::evaluate_planar_contacts(normal, friction, false, true, s.pairs(c), s.contacts(),
                                                        c.dx.size());
  for (std::size_t k = 0; k < c.dx.size(); ++k) {
    const double ft = s.tangential[k], arm = c.radius - 0.5 * s.overlap[k];
    o.fx[k] = s.spring[k] * s.nx[k] - ft * s.ny[k], o.fy[k] = s.spring[k] * s.ny[k] + ft * s.nx[k];
    o.ti[k] = -arm * ft, o.tj[k] = -arm * ft;
  }
}

template <class F>
double ns_per_contact(F f, const Contacts& c, Out& o) {
  std::vector<double> times;
  for (int rep = 0; rep < 15; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    for (int it = 0; it < 2000; ++it) f(c, o);
    times.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
                    (2000.0 * static_cast<double>(c.dx.size())));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

int main() {
  const Contacts c = make(256);
  Out reference(256), o(256);
  engine(c, reference);
  // The largest difference from the engine's forces and torques, over the largest force (times r).
  double scale = 0.0;
  for (std::size_t k = 0; k < c.dx.size(); ++k)
    scale = std::max({scale, std::abs(reference.fx[k]), std::abs(reference.fy[k])});
  const auto worst = [&](const Out& a) {
    double w = 0.0;
    for (std::size_t k = 0; k < c.dx.size(); ++k)
      w = std::max({w, std::abs(a.fx[k] - reference.fx[k]) / scale, std::abs(a.fy[k] - reference.fy[k]) / scale,
                    std::abs(a.ti[k] - reference.ti[k]) / (scale * c.radius),
                    std::abs(a.tj[k] - reference.tj[k]) / (scale * c.radius)});
    return w;
  };
  std::printf("%-8s %16s %30s\n", "form", "ns per contact", "largest difference / largest force");
  std::printf("%-8s %16.2f %30s\n", "engine", ns_per_contact(engine, c, o), "(reference)");
  int status = 0;
  using Form = void (*)(const Contacts&, Out&);
  const std::pair<const char*, Form> forms[] = {{"planar", planar}, {"lanes", lanes}, {"library", library}};
  for (const auto& [name, form] : forms) {
    const double t = ns_per_contact(form, c, o), w = worst(o);
    std::printf("%-8s %16.2f %30.2g\n", name, t, w);
    if (!(w < 1e-12)) status = 1;  // a form that computes another contact is not a faster one
  }
  return status;
}
