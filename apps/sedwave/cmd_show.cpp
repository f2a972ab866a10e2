// `sedwave show`: a dispersion table as text, for reading and comparing tables without HDF5 tools:
// its provenance, then one CSV row per grid point (dimensionless values, as stored).
#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "sedwave/forward/table/table_file.hpp"

namespace sedwave::app {
namespace {

/// The shortest text that reads back as the same double (so two tables compare exactly as text).
std::string shortest(double x) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, r.ptr);
}

/// A CSV field's text with its double quotes doubled.
std::string csv_quoted(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out;
}

/// What is wrong with a point stored as ok, or nothing: every value must be finite, the attenuation
/// and the sigmas non-negative, the speed positive.
std::string implausible(const forward::table::PointResult& p) {
  const auto bad = [](const char* name, double x, bool positive) -> std::string {
    if (!std::isfinite(x)) return std::string(name) + " = " + shortest(x);
    if (positive ? !(x > 0.0) : x < 0.0) return std::string(name) + " = " + shortest(x) + (positive ? " <= 0" : " < 0");
    return {};
  };
  for (const std::string& why : {bad("alpha_hat", p.alpha_hat, false), bad("sigma_alpha_hat", p.sigma_alpha_hat, false),
                                 bad("c_hat", p.c_hat, true), bad("sigma_c_hat", p.sigma_c_hat, false)}) {
    if (!why.empty()) return why;
  }
  return {};
}

}  // namespace

Command add_show_command(CLI::App& app) {
  struct Options {
    std::string table;
    bool values_only = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "show", "Print a dispersion table (HDF5) as CSV: omega_hat, gamma_hat, status, alpha_hat, sigma, c_hat, sigma, "
              "wall seconds, reason (dimensionless; docs/tables.md)");
  cmd->add_option("table", o->table, "table file (HDF5)")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--values-only", o->values_only,
                "leave out the provenance lines and the wall seconds (to compare the values of two tables)");
  return {cmd, [o]() {
    const forward::table::DispersionTable t = forward::table::read_table(o->table);
    if (!o->values_only) {
      std::cout << "# table " << o->table << "\n# engine: " << t.metadata().engine << "\n# sedwave version: "
                << t.metadata().code_version << "\n# sigma: " << forward::table::sigma_meaning(t.metadata())
                << "\n# pore fluid: " << (t.metadata().pore_fluid.empty() ? "none" : t.metadata().pore_fluid) << "\n";
    }
    std::cout << "omega_hat,gamma_hat,status,alpha_hat,sigma_alpha_hat,c_hat,sigma_c_hat"
              << (o->values_only ? "" : ",wall_seconds") << ",reason\n";
    std::size_t flagged = 0;
    for (std::size_t g = 0; g < t.n_gamma(); ++g) {
      for (std::size_t w = 0; w < t.n_omega(); ++w) {
        const forward::table::PointResult& p = t.at(g, w);
        if (p.status == forward::table::PointStatus::ok) {
          if (const std::string why = implausible(p); !why.empty()) {
            ++flagged;
            std::cerr << "sedwave show: ! point omega_hat " << shortest(t.grid().omega_hat[w]) << ", gamma_hat "
                      << shortest(t.grid().gamma_hat[g]) << " is stored as ok but " << why << "\n";
          }
        }
        std::cout << shortest(t.grid().omega_hat[w]) << ',' << shortest(t.grid().gamma_hat[g]) << ','
                  << forward::table::to_string(p.status) << ',' << shortest(p.alpha_hat) << ','
                  << shortest(p.sigma_alpha_hat) << ',' << shortest(p.c_hat) << ',' << shortest(p.sigma_c_hat);
        if (!o->values_only) std::cout << ',' << shortest(p.wall_seconds);
        std::cout << ",\"" << csv_quoted(p.reason) << "\"\n";
      }
    }
    if (flagged > 0) {
      std::cerr << "sedwave show: ! " << flagged << " point(s) stored as ok hold impossible values (above); "
                << "do not use them\n";
      return kExitIncomplete;
    }
    return kExitOk;
  }};
}

}  // namespace sedwave::app
