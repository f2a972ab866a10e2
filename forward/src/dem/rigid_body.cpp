#include "sedwave/forward/dem/rigid_body.hpp"

#include <cmath>
#include <numbers>

namespace sedwave::forward::dem {
namespace {
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// C++20 deduces this from the braces alone; Clang 14 does not implement that yet.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;
}  // namespace

Vec3 RigidBody::acceleration() const {
  const auto* f = std::get_if<ConstantForce>(&motion_);
  Vec3 a;
  for (int k = 0; k < 3; ++k)
    if (f->free_axes[static_cast<std::size_t>(k)]) a[k] = (f->force[k] + contact_force_[k]) / f->mass;
  return a;
}

void RigidBody::begin_step(double t, double dt) {
  // Prescribed paths are evaluated, not integrated: the wall stays on its path without drift. Its
  // grains move during the step with the step's mean velocity, as a free grain's half-step velocity
  // equals its step displacement / dt: dashpots see walls and free grains at the same instant, and a
  // tangential spring's history (which integrates velocities) follows the wall's path exactly. The
  // end-of-step velocity (LAMMPS fix move) would lead the path by half a step: for a sinusoid, a
  // phase error omega dt / 2 in every spring history touching the wall.
  auto path = [&](const Vec3& u_new) {
    step_displacement_ = u_new - displacement_;
    displacement_ = u_new;
    velocity_ = (1.0 / dt) * step_displacement_;
  };
  std::visit(Overloaded{
                 [&](const Frozen&) { path({}); },
                 [&](const LinearMotion& m) {
                   path((t + dt) * m.velocity);
                   velocity_ = m.velocity;  // the same mean, without the round-off of the difference
                 },
                 [&](const Wiggle& m) {
                   Vec3 u;
                   u[m.axis] = m.amplitude * std::sin(2.0 * std::numbers::pi / m.period * (t + dt));
                   path(u);
                 },
                 [&](const PrescribedMotion& m) { path(m.displacement(t + dt)); },
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
