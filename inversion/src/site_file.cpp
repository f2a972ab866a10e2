#include "sedwave/inversion/site_file.hpp"

#include <stdexcept>
#include <string>

#include "sedwave/io/toml_table.hpp"

namespace sedwave::inversion {
namespace {

using Error = std::invalid_argument;
using io::Range;
using Table = io::Table<Error>;

/// The value of `key` in table `t`, checked against `range`, with its FILE:LINE and key as origin.
SiteValue site_value(Table& t, const char* key, const Range& range, const std::string& origin) {
  const toml::value& v = t.at(key);
  const double x = t.number_value(v, t.name(key), range);
  return {x, io::where(v, origin) + ": key '" + t.name(key) + "'"};
}

}  // namespace

Site read_site_file(const std::filesystem::path& path) {
  const std::string origin = path.string();
  const toml::value root = io::parse<Error>(io::read_text<Error>(path, "site file"), origin);
  Table top(root, "", origin);
  top.allow_only({"grain_size", "porosity", "depth", "water", "restitution"});
  Site site;
  site.source = "site file " + origin;
  site.skip_missing_parameters = true;
  if (top.has("grain_size")) {
    Table t = top.sub("grain_size");
    t.allow_only({"phi", "phi_sd"});
    site.phi = site_value(t, "phi", Range::closed(-8.0, 12.0, "phi"), origin);
    site.phi_sd = site_value(t, "phi_sd", Range::above(0.0, 5.0, "phi"), origin);
  }
  if (top.has("porosity")) {
    Table t = top.sub("porosity");
    t.allow_only({"mean", "sd"});
    site.porosity = site_value(t, "mean", Range::open(0.0, 1.0), origin);
    site.porosity_sd = site_value(t, "sd", Range::above(0.0, 0.5), origin);
  }
  if (top.has("depth")) {
    Table t = top.sub("depth");
    t.allow_only({"metres", "kappa_sd_ln"});
    site.depth = site_value(t, "metres", Range::above(0.0, 1000.0, "m"), origin);
    site.kappa_sd_ln = site_value(t, "kappa_sd_ln", Range::above(0.0, 10.0), origin);
  }
  if (top.has("water")) {
    Table t = top.sub("water");
    t.allow_only({"temperature_c", "salinity_ppt"});
    site.water_temperature = site_value(t, "temperature_c", Range::closed(2.0, 30.0, "deg C"), origin);
    site.salinity = site_value(t, "salinity_ppt", Range::closed(25.0, 40.0, "ppt"), origin);
  }
  if (top.has("restitution")) {
    Table t = top.sub("restitution");
    t.allow_only({"lower", "upper"});
    site.restitution_lower = site_value(t, "lower", Range::above(0.0, 1.0), origin);
    site.restitution_upper = site_value(t, "upper", Range::above(0.0, 1.0), origin);
    if (!(site.restitution_upper->value > site.restitution_lower->value)) {
      throw Error(site.restitution_upper->origin + ": must exceed lower");
    }
  }
  return site;
}

}  // namespace sedwave::inversion
