#pragma once
// Synthetic observations: what a forward model predicts for known parameters over a planned band,
// with noise. This is experiment design: fit the synthetic set back and the report says
// which parameters a measurement of that band and precision would determine (docs/inversion.md).
//
//   const ObservationSet lab = synthetic_observations(model, truth, {1e5, 1e6, 12, 0.1, 0.01, 1});
//   const FitResult r = fit(lab, model, start);   // r.parameters[kDiameter].determined ?
//
// Units: SI (frequencies in Hz, attenuation in Np/m, sound speed in m/s); noise levels relative.
#include <filesystem>
#include <vector>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/parameters.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::inversion {

/// A planned measurement: log-spaced frequencies and the relative precision of each quantity.
struct SyntheticDesign {
  double lowest_hz = 10.0;      ///< first frequency [Hz]
  double highest_hz = 1.0e6;    ///< last frequency [Hz] (inclusive)
  int points = 25;              ///< frequencies, log-spaced; one attenuation and one speed at each
  double alpha_noise = 0.05;    ///< 1-sigma of ln(attenuation) (log-normal noise); sigma stated = this x value
  double speed_noise = 0.05;    ///< the same for the sound speed
  unsigned seed = 1;            ///< of the noise (std::mt19937_64): the same seed gives the same set
  /// Attenuation and sound speed rows at each frequency (false: reflection rows only).
  bool waves = true;
  /// Grazing angles [rad]: bottom-loss rows at each frequency and angle, from the plane-wave
  /// reflection coefficient of water over the seabed the model describes (a half-space of it, or a
  /// layered model's stack), with Gaussian noise of 1-sigma bottom_loss_sigma_db (also the sigma).
  std::vector<double> grazing_angles{};
  double bottom_loss_sigma_db = 0.5;  ///< [dB]
  double water_speed = 1500.0;        ///< [m/s], of the water above (reflection rows only)
  double water_density = 1025.0;      ///< [kg/m^3]
};

/// Attenuation and sound speed predicted by `model` at the values of `truth` (free or not) with the
/// noise the inversion's likelihood assumes: the attenuation multiplied by exp(alpha_noise N(0, 1)),
/// sigma = alpha_noise * the value drawn; the speed multiplied by (1 + speed_noise N(0, 1)),
/// sigma = speed_noise * the noise-free value; bottom-loss rows as SyntheticDesign says. Throws
/// std::invalid_argument for a design that is not a band of >= 2 positive frequencies, and whatever
/// the model throws where it has no value (a table: std::domain_error).
[[nodiscard]] ObservationSet synthetic_observations(const sediment::SedimentModel& model, const FitParameters& truth,
                                                    const SyntheticDesign& design);
/// The same with a dimensionless model as a dry grain-contact frame.
[[nodiscard]] ObservationSet synthetic_observations(const forward::DispersionModel& model, const FitParameters& truth,
                                                    const SyntheticDesign& design);

/// Writes observations as a sedwave observation CSV (docs/file-formats.md) in SI units (Hz, Np/m,
/// m/s; bottom loss in dB, |R| as it is, with their grazing angles in degrees and the set's water
/// sound speed and density), at full precision, with `header` lines written as "# " comments before
/// the column names.
/// Throws std::runtime_error if the file cannot be written.
void write_observation_csv(const std::filesystem::path& path, const ObservationSet& set,
                           const std::vector<std::string>& header);

}  // namespace sedwave::inversion
