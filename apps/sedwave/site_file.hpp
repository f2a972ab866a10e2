#pragma once
// A site file: what a user knows about the seabed, as priors on the parameters of any model
// (docs/inversion.md, "Site files"). TOML, every table optional, units stated per key:
//
//   [grain_size]  phi, phi_sd [phi units]           -> d: log-normal, median 2^-phi mm, sd of ln d = phi_sd ln 2
//   [porosity]    mean, sd [1]                       -> porosity: normal
//   [depth]       metres [m], kappa_sd_ln [ln units] -> kappa: log-normal about the Hertz stiffness of quartz
//                                                       grains of that d and porosity at that depth
//   [water]       temperature_c [deg C], salinity_ppt -> rho_w, K_w, eta: fixed at sea-water values
//   [restitution] lower, upper [1]                   -> e_n: uniform
//
// A free parameter gets the prior; a fixed one the prior's median as its value; a model without
// the parameter ignores the entry.
#include <filesystem>
#include <string>
#include <vector>

#include "sedwave/inversion/parameters.hpp"

namespace sedwave::app {

struct SiteEntry {
  std::string parameter;
  std::string prior;   ///< "KIND:A,B" (empty: a fixed value)
  double value = 0.0;  ///< the prior's median, or the fixed value [SI]
};

struct SiteFile {
  std::string path;
  std::vector<SiteEntry> entries;
};

/// Throws std::invalid_argument naming FILE:LINE and key for a syntax error, an unknown key, a
/// missing key of a table that is there, or a value outside its range.
[[nodiscard]] SiteFile read_site_file(const std::filesystem::path& path);

/// Applies the site to `parameters` (fixed ones get values; free ones keep theirs) and returns the
/// prior items for the free ones, with one line per entry used into `notes`.
[[nodiscard]] std::vector<std::string> apply_site(const SiteFile& site, inversion::FitParameters& parameters,
                                                  std::vector<std::string>& notes);

}  // namespace sedwave::app
