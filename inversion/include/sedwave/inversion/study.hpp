#pragma once
// A posterior study as one library call: from a best fit, the posterior of its free parameters
// (posterior.hpp) and the band it predicts over the data (predictive.hpp); then its files and plots.
// What `sedwave invert --method posterior` runs; a comparison of models is comparison.hpp.
//
//   const FitResult best = fit(data, model, parameters, options);
//   const PosteriorStudy study = posterior_study(data, model, best, priors, options, {});
//   write_posterior_study(out, study, best, data);
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/predictive.hpp"
#include "sedwave/inversion/priors.hpp"

namespace sedwave::inversion {

/// A fit's files in `dir`: curves.csv (the best fit's model over the data's band, curve_frequencies),
/// observations.csv (the data beside the fit) and, where the data have reflection rows,
/// bottom_loss_curves.csv (write_bottom_loss_curves). Returns how many of the curve's frequencies the
/// model did not answer (left out of curves.csv).
std::size_t write_fit_files(const std::filesystem::path& dir, const FitResult& best,
                            const sediment::SedimentModel& model, const ObservationSet& data);

/// The frequencies [Hz] of the data's reflection rows (bottom loss, |R|), ascending.
[[nodiscard]] std::vector<double> reflection_frequencies(const ObservationSet& data);

/// The best fit's bottom loss [dB] against grazing angle (0.5 deg steps) at `frequencies` [Hz], water
/// of the data's sound speed and density over the seabed the model describes, as a CSV
/// (frequency_hz, grazing_angle_deg, bottom_loss_db); write_fit_files writes it as
/// bottom_loss_curves.csv where the data have reflection rows. Throws where the model has no answer.
void write_bottom_loss_curves(const std::filesystem::path& file, const FitResult& best,
                              const sediment::SedimentModel& model, const ObservationSet& data,
                              const std::vector<double>& frequencies);

struct PosteriorStudy {
  PosteriorResult posterior;
  PredictiveBand band;  ///< the posterior's band over the data's frequencies (curve_frequencies)
};

/// Samples the posterior around `best` (sample_posterior), then its predictive band.
[[nodiscard]] PosteriorStudy posterior_study(const ObservationSet& data, const sediment::SedimentModel& model,
                                             const FitResult& best, const std::vector<Prior>& priors,
                                             const FitOptions& fit_options, const PosteriorOptions& options);

/// The study's files in `dir`: posterior_samples.csv and .h5, posterior_marginals.csv,
/// posterior_predictive.csv and posterior_residuals.csv (each written atomically).
void write_posterior_study(const std::filesystem::path& dir, const PosteriorStudy& study, const FitResult& best,
                           const ObservationSet& data);

}  // namespace sedwave::inversion
