#include "sedwave/inversion/study.hpp"

#include <complex>
#include <memory>
#include <numbers>
#include <set>

#include "sedwave/inversion/report.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::inversion {
namespace {

/// Angles of the bottom-loss curves: 0.5 deg apart up to 90 deg.
constexpr int kBottomLossCurveAngles = 180;

}  // namespace

std::vector<double> reflection_frequencies(const ObservationSet& data) {
  std::set<double> frequencies;
  for (const Observation& o : data.observations) {
    if (is_reflection(o.quantity)) frequencies.insert(o.frequency_hz);
  }
  return {frequencies.begin(), frequencies.end()};
}

std::size_t write_fit_files(const std::filesystem::path& dir, const FitResult& best,
                            const sediment::SedimentModel& model, const ObservationSet& data) {
  const std::vector<double> frequencies = curve_frequencies(data);
  const std::vector<CurvePoint> curves = model_curves(best, model, frequencies);
  write_curves_csv(dir / "curves.csv", curves, data.water_sound_speed);
  write_observations_table(dir / "observations.csv", data, best);
  if (const std::vector<double> at = reflection_frequencies(data); !at.empty()) {
    write_bottom_loss_curves(dir / "bottom_loss_curves.csv", best, model, data, at);
  }
  return frequencies.size() - curves.size();
}

void write_bottom_loss_curves(const std::filesystem::path& file, const FitResult& best,
                              const sediment::SedimentModel& model, const ObservationSet& data,
                              const std::vector<double>& frequencies) {
  std::vector<double> values;
  for (const ParameterResult& p : best.parameters) values.push_back(p.value);
  const sediment::SeabedModel seabed =
      sediment::seabed_of(model, values, data.water_sound_speed.value_or(1500.0), water_density_of(data));
  std::vector<double> angles;
  for (int k = 1; k <= kBottomLossCurveAngles; ++k) angles.push_back(k * (std::numbers::pi / 2) / kBottomLossCurveAngles);
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave: the best fit's plane-wave bottom loss -20 log10|R| [dB] against grazing angle [deg] at each "
           "frequency of the data's reflection rows [Hz]; water "
        << seabed.water_speed << " m/s, " << seabed.water_density << " kg/m^3 over " << model.name() << "\n"
        << "frequency_hz,grazing_angle_deg,bottom_loss_db\n";
    out.precision(10);
    for (const double f : frequencies) {
      const std::vector<std::complex<double>> r =
          sediment::reflection_coefficients(sediment::layered_halfspace_at(seabed, f), angles, f);
      for (std::size_t k = 0; k < angles.size(); ++k) {
        out << f << ',' << angles[k] * 180.0 / std::numbers::pi << ',' << sediment::bottom_loss_db(r[k]) << '\n';
      }
    }
  });
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
