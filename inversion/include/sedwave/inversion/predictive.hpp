#pragma once
// The posterior band of a model over frequency: what the posterior says the model's attenuation and
// sound speed are, as the 2.5, 16, 50, 84 and 97.5 % quantiles over posterior draws at each
// frequency, and each observation's residual from the band's median in its own sigmas. It is the
// posterior-predictive band of the noise-free curve: replicated data scatter about it by their
// sigmas (the error bars drawn with the data). Drawn by draw_predictive_plot (plot.hpp).
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sedwave/inversion/fit.hpp"

namespace sedwave::inversion {

/// The quantiles of a band: 95 % and 68 % central intervals and the median.
inline constexpr std::array<double, 5> kBandQuantiles{0.025, 0.16, 0.5, 0.84, 0.975};
using BandQuantiles = std::array<double, 5>;

struct PredictiveBand {
  std::string model;                           ///< label in files and plots
  std::vector<double> frequency_hz;            ///< where the model answered for every draw used
  std::vector<BandQuantiles> attenuation;      ///< [Np/m], kBandQuantiles at each frequency
  std::vector<BandQuantiles> speed;            ///< [m/s]
  /// Per observation of the fit (FitResult::residuals order): (observed - band median) / sigma [1].
  std::vector<double> residual;
  int draws = 0;                               ///< posterior draws evaluated
};

/// The band of `model` from `samples` (pooled posterior draws x free parameters, values in SI, the
/// free parameters of `best.fitted` in order), the other parameters at `best`'s values. At most
/// `max_draws` draws are used, evenly spread over the pooled samples. A frequency where the model
/// does not answer for some draw (outside a table) is left out.
[[nodiscard]] PredictiveBand predictive_band(const std::string& label, const sediment::SedimentModel& model,
                                             const FitResult& best, const Eigen::MatrixXd& samples,
                                             const std::vector<double>& frequencies_hz, int max_draws = 400);

/// One band as CSV: frequency, then the five quantiles of attenuation in dB/m, of speed in m/s and,
/// with a water speed, of the speed ratio.
void write_predictive_csv(const std::filesystem::path& file, const PredictiveBand& band,
                          std::optional<double> water_sound_speed);

/// The observations (display units as observations.csv) with each band's residual in a column
/// named after its model: quantity, frequency_hz, display_value, display_sigma, residual_<model>...
void write_predictive_residuals_csv(const std::filesystem::path& file, const FitResult& any_fit,
                                    const std::vector<PredictiveBand>& bands, std::optional<double> water_sound_speed);

}  // namespace sedwave::inversion
