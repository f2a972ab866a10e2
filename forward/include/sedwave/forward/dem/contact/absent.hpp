#pragma once
// The "none" entries of the tangential and rolling lists: empty parts whose code `if constexpr`
// removes, so the thesis's frictionless, non-rotating Hooke model runs a force loop that does no
// tangential or rotational work at all (no spin arrays are even allocated).
#include <array>
#include <string_view>

#include "sedwave/forward/dem/contact/contact_spec.hpp"

namespace sedwave::forward::dem {

/// What every absent part is: no keys, no per-pair constants, nothing the linear engine lacks.
struct AbsentPart {
  static constexpr std::string_view name = "none";
  static constexpr std::string_view label = "";  ///< adds nothing to describe()
  static constexpr std::array<const ContactKey*, 0> keys{};
  static constexpr bool enabled = false;
  static constexpr bool linearised = true;
  struct Pair {};
  [[nodiscard]] Pair pair(double /*effective_mass*/, double /*r_i*/, double /*r_j*/) const { return {}; }
};

struct NoTangential : AbsentPart {
  static constexpr bool needs_history = false;
  static NoTangential from(const ContactValues& /*v*/, double /*normal_stiffness*/) { return {}; }
};

struct NoRolling : AbsentPart {
  static NoRolling from(const ContactValues& /*v*/) { return {}; }
};

}  // namespace sedwave::forward::dem
