#include "sedwave/inversion/study.hpp"

#include "sedwave/inversion/report.hpp"

namespace sedwave::inversion {

std::size_t write_fit_files(const std::filesystem::path& dir, const FitResult& best,
                            const sediment::SedimentModel& model, const ObservationSet& data) {
  const std::vector<double> frequencies = curve_frequencies(data);
  const std::vector<CurvePoint> curves = model_curves(best, model, frequencies);
  write_curves_csv(dir / "curves.csv", curves, data.water_sound_speed);
  write_observations_table(dir / "observations.csv", data, best);
  return frequencies.size() - curves.size();
}

PosteriorStudy posterior_study(const ObservationSet& data, const sediment::SedimentModel& model,
                               const FitResult& best, const std::vector<Prior>& priors, const FitOptions& fit_options,
                               const PosteriorOptions& options) {
  PosteriorStudy study;
  study.posterior = sample_posterior(data, model, best, priors, fit_options, options);
  study.band = predictive_band(best.model, model, best, study.posterior.samples, curve_frequencies(data));
  return study;
}

void write_posterior_study(const std::filesystem::path& dir, const PosteriorStudy& study, const FitResult& best,
                           const ObservationSet& data) {
  write_posterior_samples_csv(dir / "posterior_samples.csv", study.posterior);
  write_posterior_samples_hdf5(dir / "posterior_samples.h5", study.posterior);
  write_posterior_marginals_csv(dir / "posterior_marginals.csv", study.posterior);
  write_predictive_csv(dir / "posterior_predictive.csv", study.band, data.water_sound_speed);
  write_predictive_residuals_csv(dir / "posterior_residuals.csv", best, {study.band}, data.water_sound_speed);
}

}  // namespace sedwave::inversion
