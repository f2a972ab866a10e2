#include "sedwave/inversion/synthetic.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/residuals.hpp"
#include "sedwave/io/atomic_file.hpp"

namespace sedwave::inversion {

ObservationSet synthetic_observations(const sediment::SedimentModel& model, const FitParameters& truth,
                                      const SyntheticDesign& design) {
  truth.require_parameters_of(model);
  if (!(design.lowest_hz > 0.0 && design.highest_hz > design.lowest_hz && design.points >= 2)) {
    throw std::invalid_argument("synthetic band: need 0 < lowest < highest frequency and at least 2 points");
  }
  if (!(design.alpha_noise > 0.0 && design.speed_noise > 0.0)) {
    throw std::invalid_argument("synthetic band: the relative noise levels must be positive (they are the sigmas)");
  }
  std::mt19937_64 rng(design.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::vector<double> values = truth.values();
  ObservationSet set;
  for (int i = 0; i < design.points; ++i) {
    const double f = design.lowest_hz * std::pow(design.highest_hz / design.lowest_hz, i / (design.points - 1.0));
    const sediment::Wave p = model.evaluate(values, f, false);
    // Attenuation is compared in ln space with sigma/value as its sigma (residuals.hpp), so its noise
    // is drawn there: log-normal, with the stated sigma the same fraction of the value drawn. Then the
    // synthetic data follow exactly the likelihood the fit assumes, and intervals can be calibrated
    // on them (multiplying by 1 + eps N instead biases ln alpha by -eps^2/2).
    const double alpha = p.attenuation * std::exp(design.alpha_noise * normal(rng));
    set.observations.push_back({Quantity::Attenuation, f, alpha, design.alpha_noise * alpha, "Np/m", "synthetic", i + 1});
    set.observations.push_back({Quantity::SoundSpeed, f, p.speed * (1.0 + design.speed_noise * normal(rng)),
                                design.speed_noise * p.speed, "m/s", "synthetic", i + 1});
  }
  return set;
}

ObservationSet synthetic_observations(const forward::DispersionModel& model, const FitParameters& truth,
                                      const SyntheticDesign& design) {
  return synthetic_observations(*grain_contact_model(model, truth.damping_form()), truth, design);
}

void write_observation_csv(const std::filesystem::path& path, const ObservationSet& set,
                           const std::vector<std::string>& header) {
  io::write_text_atomically(path, [&](std::ostream& out) {
    out << "# sedwave observation CSV (format: docs/file-formats.md); SI units\n";
    for (const std::string& line : header) out << "# " << line << '\n';
    out << "quantity,frequency,frequency_unit,value,value_unit,sigma\n";
    char row[160];
    for (const Observation& o : set.observations) {
      const bool attenuation = o.quantity == Quantity::Attenuation;
      std::snprintf(row, sizeof row, "%s,%.17g,Hz,%.17g,%s,", attenuation ? "attenuation" : "sound_speed",
                    o.frequency_hz, o.value, attenuation ? "Np/m" : "m/s");
      out << row;
      if (o.sigma) {
        std::snprintf(row, sizeof row, "%.17g", *o.sigma);
        out << row;
      }
      out << '\n';
    }
  });
}

}  // namespace sedwave::inversion
