#include "site_file.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "sedwave/io/toml_table.hpp"
#include "sedwave/sediment/site.hpp"

namespace sedwave::app {
namespace {

using Error = std::invalid_argument;
using io::Range;
using Table = io::Table<Error>;

constexpr double kQuartzDensity = 2650.0;  // for the depth's effective stress when the model has none
constexpr double kSeaWaterDensity = 1025.0;

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

}  // namespace

SiteFile read_site_file(const std::filesystem::path& path) {
  const std::string origin = path.string();
  const toml::value root = io::parse<Error>(io::read_text<Error>(path, "site file"), origin);
  Table top(root, "", origin);
  top.allow_only({"grain_size", "porosity", "depth", "water", "restitution"});
  SiteFile site{origin, {}};
  double porosity = 0.4;
  std::optional<double> diameter;
  if (top.has("grain_size")) {
    Table t = top.sub("grain_size");
    t.allow_only({"phi", "phi_sd"});
    const double phi = t.number_value(t.at("phi"), t.name("phi"), Range::closed(-8.0, 12.0, "phi"));
    const double sd = t.number_value(t.at("phi_sd"), t.name("phi_sd"), Range::above(0.0, 5.0, "phi"));
    diameter = sediment::diameter_from_phi(phi);
    site.entries.push_back({"d", "log-normal:" + number(*diameter) + "," + number(sd * std::numbers::ln2), *diameter});
  }
  if (top.has("porosity")) {
    Table t = top.sub("porosity");
    t.allow_only({"mean", "sd"});
    porosity = t.number_value(t.at("mean"), t.name("mean"), Range::open(0.0, 1.0));
    const double sd = t.number_value(t.at("sd"), t.name("sd"), Range::above(0.0, 0.5));
    site.entries.push_back({"porosity", "normal:" + number(porosity) + "," + number(sd), porosity});
  }
  if (top.has("depth")) {
    Table t = top.sub("depth");
    t.allow_only({"metres", "kappa_sd_ln"});
    const toml::value& metres = t.at("metres");
    const double z = t.number_value(metres, t.name("metres"), Range::above(0.0, 1000.0, "m"));
    const double sd = t.number_value(t.at("kappa_sd_ln"), t.name("kappa_sd_ln"), Range::above(0.0, 10.0));
    if (!diameter) {
      throw Error(io::where(metres, origin) +
                  ": key 'depth.metres': the Hertz stiffness needs the grain size: give [grain_size] too");
    }
    const double pressure = sediment::sand_pressure_at_depth(z, porosity, kQuartzDensity, kSeaWaterDensity);
    const double kappa = sediment::hertz_kappa_at_pressure(sediment::kQuartz, *diameter, pressure, porosity,
                                                           sediment::kDensePackCoordination);
    site.entries.push_back({"kappa", "log-normal:" + number(kappa) + "," + number(sd), kappa});
  }
  if (top.has("water")) {
    Table t = top.sub("water");
    t.allow_only({"temperature_c", "salinity_ppt"});
    const double temperature = t.number_value(t.at("temperature_c"), t.name("temperature_c"), Range::closed(2.0, 30.0, "deg C"));
    const double salinity = t.number_value(t.at("salinity_ppt"), t.name("salinity_ppt"), Range::closed(25.0, 40.0, "ppt"));
    site.entries.push_back({"rho_w", "", sediment::seawater_density(temperature, salinity)});
    site.entries.push_back({"K_w", "", sediment::seawater_bulk_modulus(temperature, salinity)});
    site.entries.push_back({"eta", "", sediment::seawater_viscosity(temperature, salinity)});
  }
  if (top.has("restitution")) {
    Table t = top.sub("restitution");
    t.allow_only({"lower", "upper"});
    const double lo = t.number_value(t.at("lower"), t.name("lower"), Range::above(0.0, 1.0));
    const toml::value& upper = t.at("upper");
    const double hi = t.number_value(upper, t.name("upper"), Range::above(0.0, 1.0));
    if (!(hi > lo)) throw Error(io::where(upper, origin) + ": key 'restitution.upper': must exceed lower");
    site.entries.push_back({"e_n", "uniform:" + number(lo) + "," + number(hi), 0.5 * (lo + hi)});
  }
  return site;
}

std::vector<std::string> apply_site(const SiteFile& site, inversion::FitParameters& parameters,
                                    std::vector<std::string>& notes) {
  std::vector<std::string> priors;
  for (const SiteEntry& e : site.entries) {
    int i = -1;
    for (int k = 0; k < parameters.size(); ++k) {
      if (parameters.spec[k].name == e.parameter) i = k;
    }
    if (i < 0) continue;  // the model does not have it
    inversion::ParameterSpec& spec = parameters.spec[i];
    if (spec.free && !e.prior.empty()) {
      priors.push_back(e.parameter + "=" + e.prior);
      spec.value = std::clamp(e.value, spec.lower, spec.upper);
      notes.push_back(e.parameter + ": prior " + e.prior + " (site file " + site.path + ")");
    } else {
      spec.value = e.value;
      notes.push_back(e.parameter + " = " + number(e.value) + " " + spec.unit + " (site file " + site.path + ")");
    }
  }
  return priors;
}

}  // namespace sedwave::app
