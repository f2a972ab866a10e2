#pragma once
// Plots of a seabed's reflection (docs/reflection.md): bottom loss against grazing angle, one curve
// per frequency (and its band average, dashed), and the compressional and shear waves of each part
// of the seabed against frequency. Drawn by gnuplot from the CSV files `sedwave reflect` writes.
#include <filesystem>
#include <string>
#include <vector>

#include "sedwave/plot/plot.hpp"

namespace sedwave::plot {

/// Header lines (comments and the column names) of reflection.csv and media.csv.
inline constexpr int kReflectionCsvHeaderLines = 4;
inline constexpr int kMediaCsvHeaderLines = 3;
inline constexpr int kReflectionBandCsvHeaderLines = 2;

/// From DIR/reflection.csv (columns: 1 frequency [Hz], 2 grazing angle [deg], 7 bottom loss [dB],
/// 9 band-averaged loss [dB] when `band` names the band, e.g. "1/3-octave"; empty: none) and, with
/// `posterior_band`, DIR/reflection_band.csv (1 frequency, 2 angle, 3-7 the loss's 2.5, 16, 50, 84,
/// 97.5 % quantiles over posterior draws: the 68 % and 95 % bands shaded) writes
/// DIR/bottom_loss.gp, .png, .svg.
PlotOutcome draw_bottom_loss_plot(const std::filesystem::path& dir, const std::string& title,
                                  const std::vector<std::string>& frequencies, const std::string& band,
                                  bool posterior_band);

/// From DIR/bottom_loss_curves.csv (the best fit's bottom loss: 1 frequency [Hz], 2 grazing angle
/// [deg], 3 bottom loss [dB]) and DIR/observations.csv (its bottom-loss rows: quantity code 2,
/// frequency in column 2, value and sigma [dB] in 3 and 4, grazing angle in 10) writes
/// DIR/bottom_loss_fit.gp, .png, .svg: one colour per frequency, the data with their 1-sigma bars.
PlotOutcome draw_bottom_loss_fit_plot(const std::filesystem::path& dir, const std::string& title,
                                      const std::vector<double>& frequencies);

/// From DIR/media.csv (columns: 1 part index, 2 frequency [Hz], 3 c_p [m/s], 4 alpha_p [dB/m],
/// 5 c_s [m/s], 6 alpha_s [dB/m]) writes DIR/waves.gp, .png, .svg: speeds above, attenuations below,
/// one colour per part (`parts`, index 1 first), shear dashed where `has_shear`.
PlotOutcome draw_waves_plot(const std::filesystem::path& dir, const std::string& title,
                            const std::vector<std::string>& parts, const std::vector<bool>& has_shear);

}  // namespace sedwave::plot
