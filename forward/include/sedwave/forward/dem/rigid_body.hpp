#pragma once
// Rigid walls made of grains: a group of grains moving as one body, either along a prescribed path
// or under a constant applied force with its own mass (to impose a pressure). Walls translate; they
// do not rotate. Their grains count as infinitely heavy in contacts (see GrainArrays::inv_mass).
#include <array>
#include <functional>
#include <string>
#include <variant>

#include "sedwave/forward/dem/vec3.hpp"

namespace sedwave::forward::dem {

/// Does not move (LAMMPS fix freeze / move linear 0 0 0).
struct Frozen {};
/// Constant velocity.
struct LinearMotion {
  Vec3 velocity;
};
/// u(t) = amplitude sin(2 pi t / period) along one axis (LAMMPS fix move wiggle).
struct Wiggle {
  int axis = 2;
  double amplitude = 0.0;
  double period = 1.0;
};
/// Any displacement u(t) (with u(0) = 0).
struct PrescribedMotion {
  std::function<Vec3(double)> displacement;
};
/// Newton's law for the body: M V' = F_applied + (contact forces on its grains), on the free axes.
struct ConstantForce {
  Vec3 force;
  double mass = 1.0;
  std::array<bool, 3> free_axes{false, false, true};
};

using BodyMotion = std::variant<Frozen, LinearMotion, Wiggle, PrescribedMotion, ConstantForce>;

class RigidBody {
 public:
  RigidBody(std::string name, BodyMotion motion) : name_(std::move(name)), motion_(std::move(motion)) {}

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] const BodyMotion& motion() const { return motion_; }
  /// Total displacement since t = 0.
  [[nodiscard]] const Vec3& displacement() const { return displacement_; }
  /// Velocity given to its grains during the current step: a prescribed path's mean over the step
  /// (step_displacement() / dt), a constant-force body's half-step velocity.
  [[nodiscard]] const Vec3& velocity() const { return velocity_; }
  /// Total contact force on its grains (summed over ranks) at the last force evaluation.
  [[nodiscard]] const Vec3& contact_force() const { return contact_force_; }
  /// Displacement of the body during the step that is being taken.
  [[nodiscard]] const Vec3& step_displacement() const { return step_displacement_; }

  /// First half of velocity Verlet over [t, t + dt]: sets step_displacement() and velocity().
  void begin_step(double t, double dt);
  /// Second half, once contact_force() holds the forces at t + dt.
  void end_step(double dt);
  void set_contact_force(const Vec3& f) { contact_force_ = f; }

  /// Restores the state saved in a checkpoint.
  void restore(const Vec3& displacement, const Vec3& velocity, const Vec3& contact_force) {
    displacement_ = displacement;
    velocity_ = velocity;
    contact_force_ = contact_force;
  }

 private:
  [[nodiscard]] Vec3 acceleration() const;
  std::string name_;
  BodyMotion motion_;
  Vec3 displacement_;
  Vec3 velocity_;
  Vec3 contact_force_;
  Vec3 step_displacement_;
};

}  // namespace sedwave::forward::dem
