#include "sedwave/forward/dem/rigid_body.hpp"

#include <cmath>
#include <numbers>

namespace sedwave::forward::dem {
namespace {
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
}  // namespace

Vec3 RigidBody::acceleration() const {
  const auto* f = std::get_if<ConstantForce>(&motion_);
  Vec3 a;
  for (int k = 0; k < 3; ++k)
    if (f->free_axes[static_cast<std::size_t>(k)]) a[k] = (f->force[k] + contact_force_[k]) / f->mass;
  return a;
}

void RigidBody::begin_step(double t, double dt) {
  // Prescribed paths are evaluated, not integrated: the wall stays on its path without drift.
  auto path = [&](const Vec3& u_new, const Vec3& v_new) {
    step_displacement_ = u_new - displacement_;
    displacement_ = u_new;
    velocity_ = v_new;
  };
  std::visit(Overloaded{
                 [&](const Frozen&) { path({}, {}); },
                 [&](const LinearMotion& m) { path((t + dt) * m.velocity, m.velocity); },
                 [&](const Wiggle& m) {
                   const double w = 2.0 * std::numbers::pi / m.period;
                   Vec3 u, v;
                   u[m.axis] = m.amplitude * std::sin(w * (t + dt));
                   v[m.axis] = m.amplitude * w * std::cos(w * (t + dt));
                   path(u, v);
                 },
                 [&](const PrescribedMotion& m) { path(m.displacement(t + dt), m.velocity(t + dt)); },
                 [&](const ConstantForce&) {
                   velocity_ += (0.5 * dt) * acceleration();
                   step_displacement_ = dt * velocity_;
                   displacement_ += step_displacement_;
                 },
             },
             motion_);
}

void RigidBody::end_step(double dt) {
  if (std::holds_alternative<ConstantForce>(motion_)) velocity_ += (0.5 * dt) * acceleration();
}

}  // namespace sedwave::forward::dem
