#pragma once
// Writing a fit's results: DIR/fit.json (machine-readable report), DIR/curves.csv (model curves).
// Units are stated in every file: JSON fields carry a "unit", CSV columns carry it in their name.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "sedwave/inversion/fit.hpp"

namespace sedwave::inversion {

/// The fit report as JSON (schema documented in docs/cli.md).
[[nodiscard]] nlohmann::json fit_report(const FitResult& result, const ObservationSet& data);

/// Log-spaced frequencies [Hz] from a decade below the lowest observation to a decade above the
/// highest: the data's range "and beyond".
[[nodiscard]] std::vector<double> curve_frequencies(const ObservationSet& data, int count = 241);

/// Writes curves as CSV; the sound-speed ratio column appears only when the water speed is known,
/// the dimensionless ones (omega_hat, gamma_hat, alpha_hat, c_hat) only for a model with a dry
/// grain-contact frame (CurvePoint: NaN for every other).
void write_curves_csv(const std::filesystem::path& file, const std::vector<CurvePoint>& curves,
                      std::optional<double> water_sound_speed);

/// Writes the observations as fitted, as CSV for plotting: SI and display units, the model at each
/// point and the normalised residual (observed - model)/sigma.
void write_observations_table(const std::filesystem::path& file, const ObservationSet& data,
                              const FitResult& result);

}  // namespace sedwave::inversion
