#pragma once
// The contact parts this build supports, one list per role. A contact model takes one part of each
// list (contact_model.hpp); every combination is compiled into the force loop and selectable from
// a scene file and from `sedwave dem` by the part's name. Adding a part to a list is all it takes
// to offer it (docs/dem.md, "Adding a contact law").
#include "sedwave/forward/dem/contact/absent.hpp"
#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/dem/contact/hooke.hpp"
#include "sedwave/forward/dem/contact/mindlin.hpp"
#include "sedwave/forward/dem/contact/rolling.hpp"
#include "sedwave/forward/dem/contact/tangential_history.hpp"
#include "sedwave/forward/dem/contact/type_list.hpp"

namespace sedwave::forward::dem {

/// Normal elasticity with its own dashpot (the dashpot's form belongs to the law: the restitution
/// maps of Hooke and Hertz-Tsuji differ).
using NormalLaws = TypeList<HookeNormal, HertzNormal>;
using TangentialLaws = TypeList<NoTangential, TangentialSpringHistory, CoulombTanhFriction, MindlinTangential>;
using RollingLaws = TypeList<NoRolling, ConstantTorqueRolling>;

}  // namespace sedwave::forward::dem
