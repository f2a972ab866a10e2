#include "sedwave/inversion/predictive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sedwave/io/atomic_file.hpp"
#include "sedwave/sampling/summary.hpp"

namespace sedwave::inversion {
namespace {

BandQuantiles quantiles_of(const Eigen::VectorXd& values) {
  BandQuantiles q{};
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = sampling::quantile(values, kBandQuantiles[i]);
  return q;
}

/// Draws x frequencies of attenuation and speed, every frequency in `frequencies_hz`.
struct DrawTable {
  Eigen::MatrixXd attenuation, speed;
  std::vector<bool> answered;  ///< per frequency: for every draw
};

/// Row `draw` of the table: the model at every frequency for these parameter values.
void evaluate_draw(const sediment::SedimentModel& model, const std::vector<double>& values,
                   const std::vector<double>& frequencies_hz, Eigen::Index draw, DrawTable& table) {
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    const auto column = static_cast<Eigen::Index>(i);
    try {
      const sediment::Wave w = model.evaluate(values, frequencies_hz[i], false);
      table.attenuation(draw, column) = w.attenuation;
      table.speed(draw, column) = w.speed;
    } catch (const std::domain_error&) {
      table.answered[i] = false;
    }
  }
}

DrawTable evaluate_draws(const sediment::SedimentModel& model, const FitResult& best, const Eigen::MatrixXd& samples,
                         const std::vector<double>& frequencies_hz, int max_draws) {
  const std::vector<int> free = best.fitted.free_indices();
  if (samples.cols() != static_cast<Eigen::Index>(free.size()) || samples.rows() == 0 || max_draws < 1) {
    throw std::invalid_argument("predictive_band: need draws of every free parameter, and max_draws >= 1");
  }
  const Eigen::Index draws = std::min<Eigen::Index>(samples.rows(), max_draws);
  const auto n = static_cast<Eigen::Index>(frequencies_hz.size());
  DrawTable table{Eigen::MatrixXd(draws, n), Eigen::MatrixXd(draws, n), std::vector<bool>(frequencies_hz.size(), true)};
  std::vector<double> values = best.fitted.values();
  for (Eigen::Index d = 0; d < draws; ++d) {
    // Evenly spread over the pooled draws, so every walker contributes.
    const Eigen::Index row = d * samples.rows() / draws;
    for (std::size_t j = 0; j < free.size(); ++j) values[static_cast<std::size_t>(free[j])] = samples(row, static_cast<Eigen::Index>(j));
    evaluate_draw(model, values, frequencies_hz, d, table);
  }
  return table;
}

}  // namespace

PredictiveBand predictive_band(const std::string& label, const sediment::SedimentModel& model, const FitResult& best,
                               const Eigen::MatrixXd& samples, const std::vector<double>& frequencies_hz,
                               int max_draws) {
  PredictiveBand band;
  band.model = label;
  const DrawTable curve = evaluate_draws(model, best, samples, frequencies_hz, max_draws);
  band.draws = static_cast<int>(curve.attenuation.rows());
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    if (!curve.answered[i]) continue;
    const auto c = static_cast<Eigen::Index>(i);
    band.frequency_hz.push_back(frequencies_hz[i]);
    band.attenuation.push_back(quantiles_of(curve.attenuation.col(c)));
    band.speed.push_back(quantiles_of(curve.speed.col(c)));
  }
  std::vector<double> observed_at;
  for (const PointResidual& p : best.residuals) observed_at.push_back(p.observation.frequency_hz);
  const DrawTable points = evaluate_draws(model, best, samples, observed_at, max_draws);
  for (std::size_t i = 0; i < best.residuals.size(); ++i) {
    const PointResidual& p = best.residuals[i];
    if (is_reflection(p.observation.quantity) || is_shear(p.observation.quantity)) {
      // Bands of the compressional wave only: no band of R or of the shear wave here.
      band.residual.push_back(NAN);
      continue;
    }
    const bool attenuation = p.observation.quantity == Quantity::Attenuation;
    const auto c = static_cast<Eigen::Index>(i);
    const double median =
        points.answered[i] ? sampling::quantile(attenuation ? points.attenuation.col(c) : points.speed.col(c), 0.5) : NAN;
    band.residual.push_back((p.observation.value - median) / p.sigma);
  }
  return band;
}

void write_predictive_csv(const std::filesystem::path& file, const PredictiveBand& band,
                          std::optional<double> water_sound_speed) {
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave posterior band of " << band.model << " over " << band.draws
        << " posterior draws: quantiles 2.5, 16, 50, 84, 97.5 % of the model's attenuation [dB/m] and sound speed "
           "[m/s]"
        << (water_sound_speed ? " and speed / water speed [1]" : "") << " at each frequency [Hz]\n";
    const auto header = [&](const std::string& stem) {
      for (const char* q : {"q025", "q16", "q50", "q84", "q975"}) out << ',' << stem << '_' << q;
    };
    out << "frequency_hz";
    header("alpha_db_per_m");
    header("sound_speed_m_per_s");
    if (water_sound_speed) header("sound_speed_ratio");
    out << '\n';
    out.precision(9);
    for (std::size_t i = 0; i < band.frequency_hz.size(); ++i) {
      out << band.frequency_hz[i];
      for (double a : band.attenuation[i]) out << ',' << a * kDecibelPerNeper;
      for (double c : band.speed[i]) out << ',' << c;
      if (water_sound_speed) {
        for (double c : band.speed[i]) out << ',' << c / *water_sound_speed;
      }
      out << '\n';
    }
  });
}

void write_predictive_residuals_csv(const std::filesystem::path& file, const FitResult& any_fit,
                                    const std::vector<PredictiveBand>& bands,
                                    std::optional<double> water_sound_speed) {
  for (const PredictiveBand& band : bands) {
    if (band.residual.size() != any_fit.residuals.size()) {
      throw std::invalid_argument("predictive residuals: every band must be of the same observations");
    }
  }
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave observations against each model's posterior band: quantity 0 = attenuation (display dB/m), "
           "1 = sound speed (display "
        << (water_sound_speed ? "ratio to water" : "m/s") << "); residual = (observed - band median) / sigma [1]\n"
        << "quantity,frequency_hz,display_value,display_sigma";
    for (const PredictiveBand& band : bands) out << ",residual_" << band.model;
    out << '\n';
    out.precision(9);
    for (std::size_t i = 0; i < any_fit.residuals.size(); ++i) {
      const PointResidual& p = any_fit.residuals[i];
      const bool attenuation = p.observation.quantity == Quantity::Attenuation;
      const double scale = attenuation ? kDecibelPerNeper : 1.0 / water_sound_speed.value_or(1.0);
      out << (attenuation ? 0 : 1) << ',' << p.observation.frequency_hz << ',' << p.observation.value * scale << ','
          << p.sigma * scale;
      for (const PredictiveBand& band : bands) out << ',' << band.residual[i];
      out << '\n';
    }
  });
}

}  // namespace sedwave::inversion
