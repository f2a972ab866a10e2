#include "sedwave/forward/dem/contact/contact_model.hpp"

#include <stdexcept>

namespace sedwave::forward::dem {
namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("contact model: ") + what);
}

template <class N, class T>
AnyContactModel with_rolling(const N& normal, const T& tangential, const ContactSpec& s) {
  switch (s.rolling) {
    case RollingLawKind::none: return ContactModel<N, T, NoRolling>{normal, tangential, {}};
    case RollingLawKind::constant_torque:
      require(s.rolling_friction >= 0.0, "rolling_friction must be >= 0");
      require(s.rolling_regularisation > 0.0, "rolling_regularisation must be > 0");
      return ContactModel<N, T, ConstantTorqueRolling>{
          normal, tangential, ConstantTorqueRolling{s.rolling_friction, s.rolling_regularisation}};
  }
  throw std::invalid_argument("contact model: unknown rolling law");
}

template <class N>
AnyContactModel with_tangential(const N& normal, const ContactSpec& s) {
  switch (s.tangential) {
    case TangentialLawKind::none: return with_rolling(normal, NoTangential{}, s);
    case TangentialLawKind::spring_history:
      require(s.kt > 0.0, "spring_history needs kt > 0");
      require(s.gamma_t >= 0.0 && s.friction >= 0.0, "gamma_t and friction must be >= 0");
      return with_rolling(normal, TangentialSpringHistory{s.kt, s.gamma_t, s.friction}, s);
    case TangentialLawKind::coulomb_tanh:
      require(s.tanh_velocity_scale > 0.0, "coulomb_tanh needs tanh_velocity_scale > 0");
      require(s.friction >= 0.0, "friction must be >= 0");
      return with_rolling(normal, CoulombTanhFriction{s.friction, s.tanh_velocity_scale}, s);
  }
  throw std::invalid_argument("contact model: unknown tangential law");
}

int count_damping_choices(const ContactSpec& s) {
  return int(s.restitution.has_value()) + int(s.gamma.has_value()) + int(s.lammps_gamma_n.has_value());
}

}  // namespace

AnyContactModel make_contact_model(const ContactSpec& s) {
  require(count_damping_choices(s) <= 1, "give at most one of restitution, gamma, lammps_gamma_n");
  if (s.restitution)
    require(*s.restitution > 0.0 && *s.restitution <= 1.0, "restitution must lie in (0, 1]");
  if (s.normal == NormalLawKind::hooke) {
    require(s.kn > 0.0, "hooke needs kn > 0");
    LinearDashpot dashpot = LinearDashpot::constant(0.0);
    if (s.restitution) dashpot = LinearDashpot::from_restitution(*s.restitution);
    if (s.gamma) dashpot = LinearDashpot::constant(*s.gamma);
    if (s.lammps_gamma_n) dashpot = LinearDashpot::lammps_gamma_n(*s.lammps_gamma_n);
    require(dashpot.coefficient() >= 0.0, "damping must be >= 0");
    return with_tangential(HookeNormal{s.kn, dashpot}, s);
  }
  require(s.effective_modulus > 0.0, "hertz needs effective_modulus > 0");
  require(!s.lammps_gamma_n, "lammps_gamma_n applies to hooke only");
  double alpha = 0.0;
  if (s.restitution) alpha = hertz_alpha_from_restitution(*s.restitution);
  if (s.gamma) alpha = *s.gamma;
  require(alpha >= 0.0, "damping must be >= 0");
  return with_tangential(HertzNormal{s.effective_modulus, alpha}, s);
}

std::string describe(const ContactSpec& s) {
  std::string out = s.normal == NormalLawKind::hooke ? "hooke" : "hertz";
  if (s.tangential == TangentialLawKind::spring_history) out += "+spring_history";
  if (s.tangential == TangentialLawKind::coulomb_tanh) out += "+coulomb_tanh";
  if (s.rolling == RollingLawKind::constant_torque) out += "+rolling";
  return out;
}

}  // namespace sedwave::forward::dem
