#include "sedwave/inversion/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/residuals.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

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
  if (!design.waves && design.grazing_angles.empty()) {
    throw std::invalid_argument("synthetic band: neither waves nor grazing angles: no observations to write");
  }
  for (const double angle : design.grazing_angles) {
    if (!(angle > 0.0 && angle <= std::numbers::pi / 2)) {
      throw std::invalid_argument("synthetic band: a grazing angle must be in (0, 90] degrees");
    }
  }
  if (!design.grazing_angles.empty() && !(design.bottom_loss_sigma_db > 0.0 && std::isfinite(design.bottom_loss_sigma_db))) {
    throw std::invalid_argument("synthetic band: the bottom loss's sigma must be positive [dB]");
  }
  std::mt19937_64 rng(design.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::vector<double> values = truth.values();
  ObservationSet set;
  if (!design.grazing_angles.empty()) {
    set.water_sound_speed = design.water_speed;
    char density[40];
    std::snprintf(density, sizeof density, "%.17g", design.water_density);
    set.metadata["water_density_kg_per_m3"] = density;
  }
  const sediment::SeabedModel seabed = sediment::seabed_of(model, values, design.water_speed, design.water_density);
  for (int i = 0; i < design.points; ++i) {
    const double f = design.lowest_hz * std::pow(design.highest_hz / design.lowest_hz, i / (design.points - 1.0));
    if (!design.grazing_angles.empty()) {
      const sediment::LayeredHalfspace media = sediment::layered_halfspace_at(seabed, f);
      for (const double angle : design.grazing_angles) {
        const double loss = sediment::bottom_loss_db(sediment::reflection_coefficient(media, angle, f));
        Observation o{Quantity::BottomLoss, f, loss + design.bottom_loss_sigma_db * normal(rng),
                      design.bottom_loss_sigma_db, "dB", "synthetic", i + 1};
        o.grazing_angle = angle;
        set.observations.push_back(o);
      }
    }
    if (!design.waves) continue;
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
    const bool angles = std::ranges::any_of(set.observations, [](const Observation& o) { return is_reflection(o.quantity); });
    char row[160];
    if (set.water_sound_speed) {
      std::snprintf(row, sizeof row, "# water_sound_speed_m_per_s: %.17g\n", *set.water_sound_speed);
      out << row;
    }
    if (const auto rho = set.metadata.find("water_density_kg_per_m3"); rho != set.metadata.end()) {
      out << "# water_density_kg_per_m3: " << rho->second << '\n';
    }
    out << "quantity,frequency,frequency_unit,value,value_unit,sigma" << (angles ? ",grazing_angle_deg" : "") << '\n';
    for (const Observation& o : set.observations) {
      std::snprintf(row, sizeof row, "%s,%.17g,Hz,%.17g,%s,", quantity_name(o.quantity), o.frequency_hz, o.value,
                    quantity_unit(o.quantity));
      out << row;
      if (o.sigma) {
        std::snprintf(row, sizeof row, "%.17g", *o.sigma);
        out << row;
      }
      if (angles) out << ',';
      if (is_reflection(o.quantity)) {
        std::snprintf(row, sizeof row, "%.17g", o.grazing_angle * 180.0 / std::numbers::pi);
        out << row;
      }
      out << '\n';
    }
  });
}

}  // namespace sedwave::inversion
