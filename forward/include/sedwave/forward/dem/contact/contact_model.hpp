#pragma once
// A contact model is a compile-time composition of one normal law, one tangential law and one
// rolling law. Absent laws are the empty policies NoTangential / NoRolling: `if constexpr` removes
// their code, so the thesis's frictionless, non-rotating Hooke model runs a force loop that does no
// tangential or rotational work at all (no spin arrays are even allocated).
//
// Scenes choose laws at run time through ContactSpec; make_contact_model() turns it into one
// alternative of AnyContactModel, and the engine std::visit-s once per run call, never per contact.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sedwave/forward/dem/contact/contact_point.hpp"
#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/dem/contact/hooke.hpp"
#include "sedwave/forward/dem/contact/rolling.hpp"
#include "sedwave/forward/dem/contact/tangential_history.hpp"

namespace sedwave::forward::dem {

struct NoTangential {
  static constexpr bool enabled = false;
  static constexpr bool needs_history = false;
  struct Pair {};
  [[nodiscard]] Pair pair(double /*effective_mass*/, double /*r_i*/, double /*r_j*/) const { return {}; }
};
struct NoRolling {
  static constexpr bool enabled = false;
  struct Pair {};
  [[nodiscard]] Pair pair(double /*effective_mass*/, double /*r_i*/, double /*r_j*/) const { return {}; }
};

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
    PairResult r;
    r.normal_force = normal.force(c, p.normal);
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
};

// ---- Run-time selection --------------------------------------------------------------------------

enum class NormalLawKind { hooke, hertz };
enum class TangentialLawKind { none, spring_history, coulomb_tanh };
enum class RollingLawKind { none, constant_torque };

/// Run-time description of a contact model (what a scene file states).
struct ContactSpec {
  NormalLawKind normal = NormalLawKind::hooke;
  double kn = 0.0;                 ///< Hooke stiffness [force/length]
  double effective_modulus = 0.0;  ///< Hertz E* [force/length^2]
  // Normal damping: set exactly one (none = undamped).
  std::optional<double> restitution;     ///< e_n in (0, 1]: exact for Hooke, tabulated map for Hertz
  std::optional<double> gamma;           ///< Hooke: dashpot [force time/length]; Hertz: alpha [-]
  std::optional<double> lammps_gamma_n;  ///< Hooke only: dashpot per unit m_eff [1/time]

  TangentialLawKind tangential = TangentialLawKind::none;
  double kt = 0.0;             ///< spring_history: tangential stiffness
  double gamma_t = 0.0;        ///< spring_history: dashpot per unit m_eff [1/time]
  double friction = 0.0;       ///< mu (both tangential laws)
  double tanh_velocity_scale = 0.0;  ///< coulomb_tanh: k_s [time/length]

  RollingLawKind rolling = RollingLawKind::none;
  double rolling_friction = 0.0;          ///< mu_r
  double rolling_regularisation = 1e-3;   ///< omega_reg [1/time]
};

using AnyContactModel = std::variant<
    ContactModel<HookeNormal, NoTangential, NoRolling>,
    ContactModel<HookeNormal, TangentialSpringHistory, NoRolling>,
    ContactModel<HookeNormal, CoulombTanhFriction, NoRolling>,
    ContactModel<HookeNormal, NoTangential, ConstantTorqueRolling>,
    ContactModel<HookeNormal, TangentialSpringHistory, ConstantTorqueRolling>,
    ContactModel<HookeNormal, CoulombTanhFriction, ConstantTorqueRolling>,
    ContactModel<HertzNormal, NoTangential, NoRolling>,
    ContactModel<HertzNormal, TangentialSpringHistory, NoRolling>,
    ContactModel<HertzNormal, CoulombTanhFriction, NoRolling>,
    ContactModel<HertzNormal, NoTangential, ConstantTorqueRolling>,
    ContactModel<HertzNormal, TangentialSpringHistory, ConstantTorqueRolling>,
    ContactModel<HertzNormal, CoulombTanhFriction, ConstantTorqueRolling>>;

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

/// Validates a spec and builds the matching compile-time model. Throws std::invalid_argument.
[[nodiscard]] AnyContactModel make_contact_model(const ContactSpec& spec);
/// Human-readable summary, e.g. "hooke+spring_history".
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

}  // namespace sedwave::forward::dem
