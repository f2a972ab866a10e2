#pragma once
// A site file: what a user knows about the seabed (docs/inversion.md, "Site files"), read into the
// same typed Site the command line's site options fill (sedwave/inversion/site.hpp converts it).
// TOML, every table optional, units stated per key:
//
//   [grain_size]  phi, phi_sd [phi units]            -> d: log-normal, median 2^-phi mm, sd of ln d = phi_sd ln 2
//   [porosity]    mean, sd [1]                        -> porosity: normal
//   [depth]       metres [m], kappa_sd_ln [ln units]  -> kappa: log-normal about the Hertz stiffness of quartz
//                                                        grains of that d and porosity at that depth
//   [water]       temperature_c [deg C], salinity_ppt -> rho_w, K_w, eta: fixed at sea-water values
//   [restitution] lower, upper [1]                    -> e_n: uniform
//
// A free parameter gets the prior; a fixed one the prior's median as its value; a model without
// the parameter ignores the entry.
#include <filesystem>

#include "sedwave/inversion/site.hpp"

namespace sedwave::inversion {

/// Throws std::invalid_argument naming FILE:LINE and key for a syntax error, an unknown key, a
/// missing key of a table that is there, or a value outside its range. Each value's origin is its
/// FILE:LINE and key, for the conversion's messages.
[[nodiscard]] Site read_site_file(const std::filesystem::path& path);

}  // namespace sedwave::inversion
