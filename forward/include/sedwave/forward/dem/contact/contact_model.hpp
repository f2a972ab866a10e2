#pragma once
// A contact model is a compile-time composition of one part from each list of contact/laws.hpp:
// a normal law (with its dashpot), a tangential law and a rolling law. Each part is one small
// evaluator inlined into the single force loop (force_loop.hpp); absent parts (NoTangential,
// NoRolling) are removed by `if constexpr`.
//
// Scenes choose parts at run time by name (ContactSpec); make_contact_model() turns a spec into
// one alternative of AnyContactModel, a std::variant generated from the lists, and the engine
// std::visit-s once per run call, never per contact.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/contact_spec.hpp"
#include "sedwave/forward/dem/contact/laws.hpp"

namespace sedwave::forward::dem {

/// Force on i (the force on j is its opposite) and the torques on both grains of one contact.
struct PairResult {
  Vec3 force;
  Vec3 torque_i;
  Vec3 torque_j;
  double normal_force = 0.0;
};

template <class Normal, class Tangential = NoTangential, class Rolling = NoRolling>
struct ContactModel {
  using NormalLaw = Normal;
  using TangentialLaw = Tangential;
  using RollingLaw = Rolling;
  static constexpr bool has_tangential = Tangential::enabled;
  static constexpr bool has_rolling = Rolling::enabled;
  static constexpr bool rotates = has_tangential || has_rolling;
  static constexpr bool needs_history = Tangential::needs_history;
  /// Whether the linear engine can represent every part (as stiffness and damping blocks).
  static constexpr bool linearised = Tangential::linearised && Rolling::linearised;

  Normal normal;
  Tangential tangential{};
  Rolling rolling{};

  /// What the laws need of one pair beyond its geometry and motion: constants of its masses and
  /// radii, each law's own. The force loop reads them from a table built with the neighbour list
  /// (PairTable), so no law divides by masses or takes their roots at every step. Absent laws take
  /// no space: the thesis's model tabulates one double per pair.
  struct Pair {
    typename Normal::Pair normal;
    [[no_unique_address]] typename Tangential::Pair tangential;
    [[no_unique_address]] typename Rolling::Pair rolling;
  };
  /// effective_mass = 1 / (1/m_i + 1/m_j) (a rigid-wall grain counts as infinitely heavy).
  [[nodiscard]] Pair pair(double effective_mass, double r_i, double r_j) const {
    return {normal.pair(effective_mass, r_i, r_j), tangential.pair(effective_mass, r_i, r_j),
            rolling.pair(effective_mass, r_i, r_j)};
  }

  /// One touching pair. v_rel = v_i - v_j; spins are ignored unless the model rotates; `shear` is the
  /// pair's history slot (ignored unless needs_history). `p` is this pair's pair(...).
  [[nodiscard]] PairResult evaluate(const ContactPoint& c, const Pair& p, const Vec3& v_rel,
                                    const Vec3& spin_i, const Vec3& spin_j, double dt, Vec3& shear) const {
    return evaluate_with_normal_force(normal.force(c, p.normal), c, p, v_rel, spin_i, spin_j, dt, shear);
  }
  /// The same where the caller has already evaluated the normal law (its spring and dashpot apart).
  [[nodiscard]] PairResult evaluate_with_normal_force(double normal_force, const ContactPoint& c, const Pair& p,
                                                      const Vec3& v_rel, const Vec3& spin_i, const Vec3& spin_j,
                                                      double dt, Vec3& shear) const {
    PairResult r;
    r.normal_force = normal_force;
    r.force = r.normal_force * c.normal;
    if constexpr (has_tangential) {
      // Lever arms to the middle of the overlap: arm_i + arm_j = |x_i - x_j|, so the contact
      // conserves angular momentum exactly (LAMMPS uses the radii, which differs by O(delta/r)).
      const double arm_i = c.radius_i - 0.5 * c.overlap;
      const double arm_j = c.radius_j - 0.5 * c.overlap;
      const Vec3 slip = v_rel - c.normal_velocity * c.normal +
                        cross(c.normal, arm_i * spin_i + arm_j * spin_j);
      const Vec3 ft = tangential.force(c, p.tangential, slip, r.normal_force, dt, shear);
      r.force += ft;
      const Vec3 lever = cross(c.normal, ft);
      r.torque_i = -arm_i * lever;
      r.torque_j = -arm_j * lever;
    }
    if constexpr (has_rolling) {
      const Vec3 m = rolling.torque(c, p.rolling, spin_i - spin_j, r.normal_force);
      r.torque_i += m;
      r.torque_j -= m;
    }
    return r;
  }

  /// Elastic energy of a pair at the given overlap; `shear` is its history slot (read only by laws
  /// that keep one).
  [[nodiscard]] double energy(double overlap, double r_i, double r_j, const Vec3& shear) const {
    double e = normal.energy(overlap, r_i, r_j);
    if constexpr (has_tangential) e += tangential.energy(overlap, r_i, r_j, shear);
    return e;
  }
};

/// Every combination of the lists of laws.hpp.
using AnyContactModel = VariantOfProduct<ContactModel, NormalLaws, TangentialLaws, RollingLaws>::type;

/// Per listed pair, the model's Pair constants (parallel to the neighbour list's partners).
template <class Model>
struct PairTable {
  std::vector<typename Model::Pair> pairs;
};
template <class AnyModel>
struct PairTableFor;
template <class... Models>
struct PairTableFor<std::variant<Models...>> {
  using type = std::variant<PairTable<Models>...>;
};
/// The pair table of whichever model a run uses.
using AnyPairTable = PairTableFor<AnyContactModel>::type;

/// Validates a spec (every key within its bounds and read by a chosen part) and builds the
/// matching compile-time model. Throws std::invalid_argument.
[[nodiscard]] AnyContactModel make_contact_model(const ContactSpec& spec);
/// The spec without its normal dashpot (no dashpot key given: undamped); the linear engine and the
/// drive set their own through the key gamma.
[[nodiscard]] ContactSpec without_dashpot(ContactSpec spec);
/// The model of a spec without its normal dashpot: its traits, springs and tangential blocks, built
/// without mapping a restitution (which for Hertz integrates a collision).
[[nodiscard]] inline AnyContactModel undamped_contact_model(const ContactSpec& spec) {
  return make_contact_model(without_dashpot(spec));
}
/// Human-readable summary, e.g. "hooke+spring_history" (stored in checkpoints).
[[nodiscard]] std::string describe(const ContactSpec& spec);

/// Normal force of a pair at rest at the given overlap (the dashpot does not act): the static
/// contact force, for equilibrium and linearisation.
template <class NormalLaw>
[[nodiscard]] double static_normal_force(const NormalLaw& law, double overlap, double r_i, double r_j) {
  return law.force(ContactPoint{Vec3{}, overlap, 0.0, r_i, r_j}, law.pair(1.0, r_i, r_j));
}
[[nodiscard]] inline double static_normal_force(const AnyContactModel& m, double overlap, double r_i, double r_j) {
  return std::visit([&](const auto& model) { return static_normal_force(model.normal, overlap, r_i, r_j); }, m);
}

/// Whether a model rotates grains (allocates spins and torques).
[[nodiscard]] inline bool rotates(const AnyContactModel& m) {
  return std::visit([](const auto& model) { return std::decay_t<decltype(model)>::rotates; }, m);
}
[[nodiscard]] inline bool needs_history(const AnyContactModel& m) {
  return std::visit([](const auto& model) { return std::decay_t<decltype(model)>::needs_history; }, m);
}
[[nodiscard]] inline bool has_tangential(const AnyContactModel& m) {
  return std::visit([](const auto& model) { return std::decay_t<decltype(model)>::has_tangential; }, m);
}
/// Whether the linear engine can represent the model (no rolling torque, no Coulomb-tanh slip).
[[nodiscard]] inline bool linearised(const AnyContactModel& m) {
  return std::visit([](const auto& model) { return std::decay_t<decltype(model)>::linearised; }, m);
}
/// The normal law's stiffness at zero overlap (0 for Hertz).
[[nodiscard]] inline double stiffness_at_contact(const AnyContactModel& m) {
  return std::visit([](const auto& model) { return model.normal.stiffness_at_contact(); }, m);
}
/// The tangential law's linear block at a static overlap, none without a tangential law. Throws
/// std::invalid_argument for a law the linear engine cannot represent.
[[nodiscard]] std::optional<TangentialBlock> tangential_block(const AnyContactModel& m, double overlap, double r_i,
                                                              double r_j);

}  // namespace sedwave::forward::dem
