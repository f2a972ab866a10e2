#pragma once
// Keys that several contact parts read (a part's own keys live in its file). One declaration each,
// so a scene file and `sedwave dem` spell, document and bound them the same way.
#include "sedwave/forward/dem/contact/contact_spec.hpp"

namespace sedwave::forward::dem::keys {

inline constexpr ContactKey youngs_modulus{"youngs_modulus", "young", "Young's modulus E of the grains",
                                           io::Range::positive()};
// Stable isotropic materials have -1 < nu <= 0.5; the stiffness formulas divide by 1 - nu and 1 + nu.
inline constexpr ContactKey poisson_ratio{"poisson_ratio", "poisson", "Poisson's ratio nu (default 2/7)",
                                          io::Range::above(-1.0, 0.5)};
inline constexpr ContactKey restitution{"restitution", "restitution",
                                        "normal restitution e_n in (0, 1], exact for every pair",
                                        io::Range::above(0.0, 1.0)};
inline constexpr ContactKey gamma{"gamma", "gamma",
                                  "normal dashpot: hooke gamma [force time/length], hertz Tsuji's alpha [-]",
                                  io::Range::non_negative()};
inline constexpr ContactKey friction{"friction", "friction", "Coulomb friction coefficient mu",
                                     io::Range::non_negative(), "(Coulomb coefficient)"};
inline constexpr ContactKey gamma_t{"gamma_t", "gamma-t",
                                    "tangential dashpot per unit reduced mass [1/time] (LAMMPS gamma_t; default 0)",
                                    io::Range::non_negative()};

/// Poisson's ratio when a scene gives E alone (the thesis's grains).
inline constexpr double default_poisson_ratio = 2.0 / 7.0;

}  // namespace sedwave::forward::dem::keys
