#pragma once
// Figures drawn by gnuplot from the files a study writes (the plotting layer at the edge: the
// numerical libraries never run a program). Each figure is driven through a script written next to
// its output, so the user can restyle and re-run it; a missing or failing gnuplot is reported, never
// thrown.
//
// The fit plot: attenuation (dB/m, log-log) and sound speed (ratio to water when known) against
// frequency, data with error bars, the fitted curve and its 1-sigma band, each above a panel of
// normalised residuals; points the model misses by more than 3 sigma are marked, the frequencies
// outside the data greyed, and the fitted values with chi^2/dof written on top. Drawn by gnuplot,
// driven through a script written next to the output so the user can restyle and re-run it.
#include <filesystem>
#include <string>
#include <vector>

#include "sedwave/inversion/comparison.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/study.hpp"

namespace sedwave::plot {

/// The message of a fit plot against frequency that has nothing to draw: the data are reflection
/// rows only (their plot is reflection_plot.hpp's draw_bottom_loss_fit_plot).
inline constexpr const char* kNoWaveRows = "no frequency plot: the data have no attenuation or speed rows";

using inversion::FitResult;

struct PlotOutcome {
  bool drawn = false;
  std::string message;  ///< where the plot is, or why it was skipped
};

/// Writes DIR/STEM.gp (the gnuplot `body` drawn once to a PNG, once to an SVG of `size`, e.g.
/// "1150,1250") and runs gnuplot on it. The figure files are drawn under temporary names and renamed
/// into place, like every output: a gnuplot killed half-way never leaves a truncated STEM.png.
/// Re-running `gnuplot STEM.gp` by hand writes STEM.png and STEM.svg directly. Never throws.
PlotOutcome run_gnuplot(const std::filesystem::path& dir, const std::string& stem, const std::string& size,
                        const std::string& body);

/// Expects DIR/curves.csv and DIR/observations.csv (report.hpp) written from `result`; writes
/// DIR/fit.gp, DIR/fit.png and DIR/fit.svg. Never throws for a missing or failing gnuplot: the
/// outcome says the plot was skipped.
PlotOutcome draw_fit_plot(const std::filesystem::path& dir, const std::string& title, bool ratio_axis,
                          const FitResult& result);

/// Where a corner plot reads its draws and what it writes: DIR/SAMPLES (write_samples_csv) and
/// DIR/STEM.gp, .png, .svg.
struct CornerFiles {
  std::string samples = "posterior_samples.csv";
  std::string stem = "posterior_corner";
  std::string title = "posterior";
  std::vector<double> best_fit;  ///< marked on every panel, one value per column (empty: none)
};

/// The posterior's corner plot (columns `names` with `units` of the samples file), as corner.py
/// draws it: physical values on log axes with a few round ticks, each parameter's marginal on the
/// diagonal, each pair's draws below with the contours of the smallest regions holding 68 % and
/// 95 % of them, and the best fit marked. Also writes DIR/STEM_density.dat (the histograms the
/// script contours). Never throws for a missing or failing gnuplot.
PlotOutcome draw_corner_plot(const std::filesystem::path& dir, const std::vector<std::string>& names,
                             const std::vector<std::string>& units, const CornerFiles& files = {});

/// One model's posterior band file (predictive.hpp, write_predictive_csv) and its label.
struct BandFile {
  std::string label;
  std::string file;  ///< name inside the plot's directory
};

/// The posterior band plot: for each quantity with data, each model's 95 % and 68 % bands and
/// median over the data with error bars, above a panel of each model's residuals from its median
/// (from `residuals_file`, write_predictive_residuals_csv). `any_fit` gives the observations' bands
/// of frequency and range. Writes DIR/STEM.gp, .png and .svg; never throws for a missing or failing
/// gnuplot.
PlotOutcome draw_predictive_plot(const std::filesystem::path& dir, const std::string& stem, const std::string& title,
                                 bool ratio_axis, const FitResult& any_fit, const std::vector<BandFile>& bands,
                                 const std::string& residuals_file);

/// The corner plot (best fit marked) and the band over the data of a posterior study, from the files
/// write_posterior_study wrote in `dir`; one message per plot (what was written, or why not).
[[nodiscard]] std::vector<std::string> draw_posterior_plots(const std::filesystem::path& dir,
                                                            const inversion::PosteriorStudy& study,
                                                            const FitResult& best,
                                                            const inversion::ObservationSet& data);

/// Every model's band over the data in one plot (predictive), and the corner plot of the model
/// ranked first (corner_best), from the files write_ranking_files wrote in `dir`; one message per plot.
[[nodiscard]] std::vector<std::string> draw_ranking_plots(const std::filesystem::path& dir,
                                                          const inversion::Ranking& ranking,
                                                          const inversion::ObservationSet& data);

}  // namespace sedwave::plot
