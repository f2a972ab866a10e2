#pragma once
// Pieces shared by the packing and run files of both engines (private to experiment/): atomic
// writing, the run files' root attributes, a number with its unit, a propagation fit, and the
// packing statistics of a preparation report.
#include <filesystem>
#include <string>

#include "sedwave/io/hdf5.hpp"
#include "sedwave/forward/channel/measurement.hpp"
#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/version.hpp"

namespace sedwave::forward::experiment {

using channel::PackingStats;
using channel::PreparationReport;
using channel::PropagationFit;

/// Root attributes of a run file (either engine): code version, scene text, units.
inline void write_run_header(hid_t file, const std::string& scene_text) {
  io::write_string_attribute(file, "sedwave_version", kVersion);
  io::write_string_attribute(file, "scene", scene_text);
  io::write_string_attribute(file, "units",
                             "dimensionless: lengths in mean grain diameters d, times in sqrt(m/kappa) with m the "
                             "mass of a grain of diameter d and kappa the contact stiffness");
}

inline void number(hid_t parent, const std::string& name, double value, const std::string& unit) {
  io::write_attribute(parent, name, value);
  io::write_string_attribute(parent, name + "_unit", unit);
}

/// alpha_hat, c_hat and their standard errors from a steady-state fit over layers.
inline void write_fit(hid_t group, const PropagationFit& fit) {
  number(group, "alpha_hat", fit.alpha, "Np per d");
  number(group, "sigma_alpha_hat", fit.sigma_alpha, "Np per d");
  number(group, "c_hat", fit.c, "d sqrt(kappa/m)");
  number(group, "sigma_c_hat", fit.sigma_c, "d sqrt(kappa/m)");
}

inline void write_stats(hid_t parent, const PreparationReport& r) {
  const PackingStats& s = r.stats;
  number(parent, "pressure", r.pressure, "kappa/d (force per d^2)");
  number(parent, "target_wall_force", r.target_wall_force, "kappa d");
  number(parent, "residual_ratio", r.residual_ratio, "max |F| / mean contact force");
  number(parent, "packing_fraction", s.packing_fraction, "1");
  number(parent, "column_height", s.column_height, "d");
  number(parent, "coordination", s.coordination, "contacts per flow grain");
  number(parent, "coordination_without_rattlers", s.coordination_without_rattlers, "contacts per grain");
  number(parent, "rattler_fraction", s.rattler_fraction, "1");
  number(parent, "mean_overlap", s.mean_overlap, "d");
  number(parent, "max_overlap", s.max_overlap, "d");
  number(parent, "mean_contact_force", s.mean_contact_force, "force unit of the scene");
  io::write_attribute(parent, "contacts", s.contacts);
  io::write_attribute(parent, "converged", static_cast<std::int32_t>(r.converged));
  io::write_attribute(parent, "compression_steps", static_cast<std::int64_t>(r.compression_steps));
  io::write_attribute(parent, "relaxation_steps", static_cast<std::int64_t>(r.relaxation_steps));
  io::write_attribute(parent, "newton_iterations", static_cast<std::int32_t>(r.newton_iterations));
  io::write(parent, "overlap_histogram", s.overlap_histogram.data(), s.overlap_histogram.size());
  io::write(parent, "gap_histogram", s.gap_histogram.data(), s.gap_histogram.size());
  io::write_string_attribute(parent, "histogram_bins",
                             "bin k counts separations |s|/d in [1e-(k+1), 1e-k); the last bin also holds smaller");
}

}  // namespace sedwave::forward::experiment
