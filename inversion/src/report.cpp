#include "sedwave/inversion/report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fstream>
#include <iomanip>
#include <limits>
#include <stdexcept>

#include "sedwave/io/atomic_file.hpp"
#include "sedwave/version.hpp"

namespace sedwave::inversion {
namespace {

/// JSON has no NaN: undetermined numbers become null.
nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

/// A missing end of a profile interval (open: it reaches the search bound) becomes null.
nlohmann::json optional_or_null(const std::optional<double>& x) { return x ? nlohmann::json(*x) : nlohmann::json(); }

/// The code of a quantity in the observations table.
int quantity_code(Quantity q) {
  if (q == Quantity::BottomLoss) return 2;
  if (q == Quantity::ShearSpeed) return 3;
  if (q == Quantity::ShearAttenuation) return 4;
  if (q == Quantity::ReflectionMagnitude) return 5;
  return q == Quantity::Attenuation ? 0 : 1;
}

}  // namespace

nlohmann::json fit_report(const FitResult& r, const ObservationSet& data) {
  nlohmann::json j;
  j["sedwave_version"] = kVersion;
  j["model"] = r.model;
  j["method"] = r.method;
  if (data.water_sound_speed) j["water_sound_speed"] = {{"value", *data.water_sound_speed}, {"unit", "m/s"}};
  for (const ParameterResult& p : r.parameters) {
    j["parameters"][p.name] = {{"value", p.value},
                               {"unit", p.unit},
                               {"free", p.free},
                               {"identifiable", p.determined},
                               {"sigma", p.free && p.determined ? number_or_null(p.sigma) : nlohmann::json()},
                               {"log_sigma", p.free && p.determined ? number_or_null(p.log_sigma) : nlohmann::json()},
                               {"at_bound", p.at_bound},
                               {"profile_interval_68", {optional_or_null(p.profile_lower), optional_or_null(p.profile_upper)}}};
  }
  for (const DerivedResult& c : r.derived) {
    j["combinations"][c.name] = {{"value", c.value},       {"unit", c.unit},
                                 {"meaning", c.meaning},   {"determined", c.determined},
                                 {"sigma", c.determined ? number_or_null(c.sigma) : nlohmann::json()},
                                 {"log_sigma", c.determined ? number_or_null(c.log_sigma) : nlohmann::json()},
                                 {"profile_interval_68", {optional_or_null(c.profile_lower), optional_or_null(c.profile_upper)}}};
  }
  nlohmann::json correlation = nlohmann::json::array();
  for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index b = 0; b < r.correlation.cols(); ++b) row.push_back(number_or_null(r.correlation(a, b)));
    correlation.push_back(row);
  }
  j["correlation"] = {{"parameters", r.free_names}, {"of", "natural logarithms of the free parameters"},
                      {"matrix", correlation}};
  std::vector<double> singular(r.singular_values.data(), r.singular_values.data() + r.singular_values.size());
  j["identifiability"] = {{"jacobian_singular_values", singular},
                          {"rank", r.rank},
                          {"free_parameters", r.free_names.size()},
                          {"weak_directions", nlohmann::json::array()}};
  for (const WeakDirection& w : r.weak_directions) {
    j["identifiability"]["weak_directions"].push_back(
        {{"direction", w.direction},
         {"singular_value", w.singular_value},
         {"meaning", w.unseen ? "the data cannot see changes along this product of parameters"
                              : "the data constrain this product only poorly"}});
  }
  j["chi2"] = r.chi2;
  j["n_observations"] = r.n_observations;
  j["dof"] = r.dof;
  j["reduced_chi2"] = r.dof > 0 ? number_or_null(r.chi2 / r.dof) : nlohmann::json();
  j["aic"] = r.aic;
  j["bic"] = r.bic;
  j["converged"] = r.converged;
  j["profile_restarts"] = r.profile_restarts;
  j["flags"] = nlohmann::json::array();
  for (const PlausibilityFlag& f : r.flags) j["flags"].push_back({{"quantity", f.quantity}, {"message", f.message}});
  j["solver_message"] = r.solver_message;
  if (r.global) {
    j["global_search"] = {{"algorithm", r.global->algorithm},
                          {"evaluations", r.global->evaluations},
                          {"chi2_search", r.global->chi2_search},
                          {"chi2_polished", r.global->chi2_polished},
                          {"chi2_local_from_start", r.global->chi2_local_from_start},
                          {"local_and_global_agree", r.global->local_and_global_agree}};
  }
  // Other local minima of chi^2 that a barrier separates from the fit: other solutions the data allow.
  j["other_minima"] = nlohmann::json::array();
  for (const LocalMinimum& m : r.other_minima) {
    nlohmann::json at = nlohmann::json::object();
    for (const int i : r.fitted.free_indices())
      at[r.fitted.spec[static_cast<std::size_t>(i)].name] = m.values[static_cast<std::size_t>(i)];
    j["other_minima"].push_back({{"chi2", m.chi2}, {"free_parameters", at}, {"units", "as in \"parameters\""}});
  }
  int defaulted = 0;
  for (const PointResidual& p : r.residuals) {
    defaulted += p.default_sigma ? 1 : 0;
    j["residuals"].push_back({{"quantity", quantity_name(p.observation.quantity)},
                              {"frequency_hz", p.observation.frequency_hz},
                              {"observed", p.observation.value},
                              {"model", p.model},
                              {"sigma", p.sigma},
                              {"unit", quantity_unit(p.observation.quantity)},
                              {"sigma_defaulted", p.default_sigma},
                              {"normalized_residual", p.normalized},
                              {"source", p.observation.file + ":" + std::to_string(p.observation.line)}});
    if (is_reflection(p.observation.quantity)) {
      j["residuals"].back()["grazing_angle_deg"] = p.observation.grazing_angle * 180.0 / std::numbers::pi;
    }
  }
  j["observations_with_default_sigma"] = defaulted;
  j["wall_seconds"] = r.wall_seconds;
  return j;
}

std::vector<double> curve_frequencies(const ObservationSet& data, int count) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const Observation& o : data.observations) {
    lo = std::min(lo, o.frequency_hz);
    hi = std::max(hi, o.frequency_hz);
  }
  const double a = std::log10(lo) - 1.0, b = std::log10(hi) + 1.0;
  std::vector<double> f;
  for (int i = 0; i < count; ++i) f.push_back(std::pow(10.0, a + (b - a) * i / (count - 1)));
  return f;
}

void write_curves_csv(const std::filesystem::path& file, const std::vector<CurvePoint>& curves,
                      std::optional<double> water_sound_speed) {
  io::write_text_atomically(file, [&](std::ostream& out) {
  // The dimensionless columns only for a model with a dry grain-contact frame: for any other they
  // would be NaN throughout.
  const bool dimensionless =
      std::any_of(curves.begin(), curves.end(), [](const CurvePoint& c) { return !std::isnan(c.omega_hat); });
  out << "# sedwave model curves; sigma columns are 1-sigma bands from the fit covariance\n";
  out << "frequency_hz," << (dimensionless ? "omega_hat,gamma_hat,alpha_hat,c_hat," : "")
      << "alpha_np_per_m,alpha_np_per_m_sigma,alpha_db_per_m,alpha_db_per_m_sigma,sound_speed_m_per_s,"
         "sound_speed_m_per_s_sigma";
  if (water_sound_speed) out << ",sound_speed_ratio,sound_speed_ratio_sigma";
  out << "\n";
  for (const CurvePoint& c : curves) {
    out << c.frequency_hz << ',';
    if (dimensionless) out << c.omega_hat << ',' << c.gamma_hat << ',' << c.alpha_hat << ',' << c.c_hat << ',';
    out << c.alpha << ',' << c.alpha_sigma << ',' << c.alpha * kDecibelPerNeper << ','
        << c.alpha_sigma * kDecibelPerNeper << ',' << c.speed << ',' << c.speed_sigma;
    if (water_sound_speed) out << ',' << c.speed / *water_sound_speed << ',' << c.speed_sigma / *water_sound_speed;
    out << "\n";
  }
  });
}

void write_observations_table(const std::filesystem::path& file, const ObservationSet& data, const FitResult& result) {
  io::write_text_atomically(file, [&](std::ostream& out) {
  out << "# sedwave observations as fitted; quantity 0 = attenuation [Np/m], 1 = sound speed [m/s], "
         "2 = bottom loss [dB] (its display columns in dB too), 3 = shear speed [m/s] (display m/s), "
         "4 = shear attenuation [Np/m] (display dB/m), 5 = |R| [1] (display |R|);\n"
      << "# display columns: attenuation in dB/m, sound speed as ratio to water if known, else m/s;\n"
      << "# normalized_residual = (observed - model)/sigma as fitted (attenuation in log space) [1]; "
         "grazing_angle_deg: of a reflection row (empty for others)\n"
      << "quantity,frequency_hz,value,sigma,display_value,display_sigma,model_value,display_model_value,"
         "normalized_residual,grazing_angle_deg\n";
  const double speed_unit = data.water_sound_speed.value_or(1.0);
  for (const PointResidual& p : result.residuals) {
    const Observation& o = p.observation;
    const double scale = is_attenuation(o.quantity)                                                ? kDecibelPerNeper
                         : is_reflection(o.quantity) || o.quantity == Quantity::ShearSpeed ? 1.0
                                                                                                    : 1.0 / speed_unit;
    // The fit's residual is model minus observed; a plot reads better as observed minus model.
    out << quantity_code(o.quantity) << ',' << o.frequency_hz << ',' << o.value << ',' << p.sigma << ',' << o.value * scale
        << ',' << p.sigma * scale << ',' << p.model << ',' << p.model * scale << ',' << -p.normalized << ',';
    if (is_reflection(o.quantity)) out << o.grazing_angle * 180.0 / std::numbers::pi;
    out << "\n";
  }
  });
}

}  // namespace sedwave::inversion
