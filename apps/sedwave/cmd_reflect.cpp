// `sedwave reflect`: the plane-wave reflection coefficient of a seabed given as sediment models
// (a half-space under optional layers), its bottom loss against grazing angle, the waves of each part,
// and the files propagation codes read (a BELLHOP .brc table, an Acoustics Toolbox environment)
// (docs/reflection.md).
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "model_options.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/inversion/plausibility.hpp"
#include "sedwave/inversion/predictive.hpp"
#include "sedwave/plot/reflection_plot.hpp"
#include "sedwave/inversion/samples_file.hpp"
#include "sedwave/inversion/setup.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/sampling/summary.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/propagation_files.hpp"
#include "sedwave/sediment/reflection.hpp"
#include "sedwave/sediment/layered_seabed.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::app {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kDbPerNeper = 8.6858896380650365;

struct ReflectOptions {
  ModelOptions model;
  std::vector<std::string> layers;  ///< each layer's model, top first
  std::vector<double> frequencies;
  double angle_step = 0.5;
  double water_speed = 1500.0;
  double water_density = 1025.0;
  bool fluid = false;
  double band = 0.0;
  int band_samples = 31;
  std::string out;
  std::string brc;
  std::string env;
  std::string env_unit = "W";
  double water_depth = 0.0;
  std::string from_fit;   ///< fit.json of sedwave invert: the half-space's parameter values
  std::string posterior;  ///< posterior_samples.csv of a posterior over the seabed's parameters
  int posterior_draws = 200;
};

std::string number(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

/// The `--set lN.NAME=VALUE` items of layer N (1-based), NAME=VALUE; the others stay in `rest`.
std::map<int, std::vector<std::string>> split_layer_settings(std::vector<std::string>& rest, int layers) {
  std::map<int, std::vector<std::string>> by_layer;
  std::vector<std::string> kept;
  for (const std::string& item : rest) {
    const std::size_t dot = item.find('.');
    const std::size_t digits = item.find_first_not_of("0123456789", 1);
    if (item.size() < 3 || item[0] != 'l' || dot == std::string::npos || digits != dot || dot == 1) {
      kept.push_back(item);
      continue;
    }
    const int layer = std::stoi(item.substr(1, dot - 1));
    if (layer < 1 || layer > layers) {
      throw UsageError("--set " + item + ": layer l" + std::to_string(layer) + " does not exist (" +
                       std::to_string(layers) + " --layer given)");
    }
    by_layer[layer].push_back(item.substr(dot + 1));
  }
  rest = kept;
  return by_layer;
}

/// Layer N's part: its model, its --set values and its thickness (l<N>.thickness, required).
sediment::SeabedPart layer_part(const std::string& model_name, int layer, const std::vector<std::string>& settings) {
  ModelOptions o;
  o.model = model_name;
  double thickness = -1.0;
  const std::string label = "l" + std::to_string(layer);
  for (const std::string& item : settings) {
    if (item.starts_with("thickness=")) {
      const std::string value = item.substr(10);
      std::size_t used = 0;
      try {
        thickness = std::stod(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != value.size() || !std::isfinite(thickness) || thickness < 0.0) {
        throw UsageError("--set " + label + ".thickness=" + value + ": a thickness in m, finite and not negative");
      }
    } else {
      o.set_values.push_back(item);
    }
  }
  if (thickness < 0.0) throw UsageError("layer " + label + " (--layer " + model_name + "): give --set " + label + ".thickness=METRES");
  const inversion::Candidate part = candidate_of(setup_of(o), ModelUse::Truth);
  return {part.model, part.parameters.values(), thickness};
}

void write_reflection_csv(const std::filesystem::path& file, const std::vector<double>& frequencies,
                          const std::vector<double>& angles_deg,
                          const std::vector<std::vector<std::complex<double>>>& r,
                          const std::vector<std::vector<double>>& band_power, double band) {
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave reflect: plane-wave reflection coefficient R of the seabed; time e^{-i omega t};\n"
        << "# grazing angle from the horizontal; phase_deg = arg R (BELLHOP's .brc phase is -arg R);\n"
        << "# bottom_loss_db = -20 log10|R|" << (band > 0.0 ? "; band_power = |R|^2 averaged over the band" : "")
        << "\n"
        << "frequency_hz,grazing_deg,r_real,r_imag,abs_r,phase_deg,bottom_loss_db"
        << (band > 0.0 ? ",band_power,band_loss_db" : "") << "\n";
    for (std::size_t i = 0; i < frequencies.size(); ++i) {
      for (std::size_t j = 0; j < angles_deg.size(); ++j) {
        const std::complex<double> x = r[i][j];
        out << number(frequencies[i]) << ',' << number(angles_deg[j]) << ',' << number(x.real()) << ','
            << number(x.imag()) << ',' << number(std::abs(x)) << ',' << number(std::arg(x) / kDegree) << ','
            << number(sediment::bottom_loss_db(x) + 0.0);  // + 0.0: |R| = 1 prints 0, not -0
        if (band > 0.0) out << ',' << number(band_power[i][j]) << ',' << number(-10.0 * std::log10(band_power[i][j]));
        out << "\n";
      }
    }
  });
}

/// The parts' names, top first, then the half-space.
std::vector<std::string> part_names(const sediment::SeabedModel& seabed) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < seabed.layers.size(); ++i) {
    names.push_back("l" + std::to_string(i + 1) + " " + seabed.layers[i].model->name() + " (" +
                    number(seabed.layers[i].thickness) + " m)");
  }
  names.push_back("half-space " + seabed.halfspace.model->name());
  return names;
}

std::vector<const sediment::SeabedPart*> parts_of(const sediment::SeabedModel& seabed) {
  std::vector<const sediment::SeabedPart*> parts;
  for (const sediment::SeabedPart& l : seabed.layers) parts.push_back(&l);
  parts.push_back(&seabed.halfspace);
  return parts;
}

/// media.csv: each part's waves over two decades either side of the frequencies asked for.
void write_media_csv(const std::filesystem::path& file, const sediment::SeabedModel& seabed, double low, double high) {
  const std::vector<const sediment::SeabedPart*> parts = parts_of(seabed);
  const std::vector<std::string> names = part_names(seabed);
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave reflect: the waves of each part of the seabed (part 1 = top layer, last = half-space);\n"
        << "# c_s and alpha_s are 0 where the part is treated as a fluid\n"
        << "part,frequency_hz,c_p_m_per_s,alpha_p_db_per_m,c_s_m_per_s,alpha_s_db_per_m,density_kg_per_m3\n";
    const int points = 61;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      for (int i = 0; i < points; ++i) {
        const double f = low * std::pow(high / low, static_cast<double>(i) / (points - 1));
        const sediment::AcousticMedium m = sediment::medium_of(*parts[k], f, seabed.fluid_only, names[k]);
        out << k + 1 << ',' << number(f) << ',' << number(m.compressional_speed) << ','
            << number(m.compressional_attenuation * kDbPerNeper) << ',' << number(m.shear_speed) << ','
            << number(m.shear_attenuation * kDbPerNeper) << ',' << number(m.density) << "\n";
      }
    }
  });
}

/// The half-space's values from a fit report (fit.json of sedwave invert): every parameter's fitted
/// or fixed value. Throws naming the file for another model, a missing parameter or a parameter
/// also given by --set.
void apply_fit_report(const std::string& file, sediment::SeabedPart& halfspace, const std::vector<std::string>& sets) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(file + ": cannot open the fit report");
  nlohmann::json report;
  try {
    report = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw std::invalid_argument(file + ": not a fit report (JSON): " + e.what());
  }
  const std::string model = report.value("model", std::string());
  if (model != halfspace.model->name()) {
    throw UsageError("--from-fit " + file + ": a fit of model '" + model + "', the half-space is '" +
                     halfspace.model->name() + "' (--model)");
  }
  const std::vector<sediment::Parameter>& ps = halfspace.model->parameters();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    for (const std::string& item : sets) {
      if (item.starts_with(ps[i].name + "=")) {
        throw UsageError("--set " + item + ": " + ps[i].name + " is also given by --from-fit " + file);
      }
    }
    const auto& entry = report["parameters"][ps[i].name];
    if (!entry.is_object() || !entry["value"].is_number()) {
      throw std::invalid_argument(file + ": no value of parameter '" + ps[i].name + "'");
    }
    halfspace.values[i] = entry["value"].get<double>();
  }
  halfspace.model->check_values(halfspace.values);
}

/// Where a posterior's column goes: the half-space's parameter NAME, layer N's lN.NAME or its
/// thickness lN.thickness.
struct SampleTarget {
  sediment::SeabedPart* part = nullptr;
  int index = -1;  ///< parameter index; -1: the thickness
};

SampleTarget sample_target(sediment::SeabedModel& seabed, const std::string& name, const std::string& file) {
  try {
    const std::size_t dot = name.find('.');
    if (name.size() > 2 && name[0] == 'l' && dot != std::string::npos && dot > 1 &&
        name.find_first_not_of("0123456789", 1) == dot) {
      const std::size_t layer = std::stoul(name.substr(1, dot - 1));
      if (layer < 1 || layer > seabed.layers.size()) throw std::invalid_argument("no layer l" + std::to_string(layer));
      sediment::SeabedPart& part = seabed.layers[layer - 1];
      const std::string parameter = name.substr(dot + 1);
      return {&part, parameter == "thickness" ? -1 : part.model->index_of(parameter)};
    }
    return {&seabed.halfspace, seabed.halfspace.model->index_of(name)};
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file + ": column '" + name + "' names no parameter of this seabed: " + e.what());
  }
}

/// The 2.5, 16, 50, 84 and 97.5 % quantiles of the bottom loss over posterior draws of the seabed's
/// parameters (the other parameters at their values), as reflection_band.csv.
void write_posterior_band(const ReflectOptions& o, const sediment::SeabedModel& seabed,
                          const std::vector<double>& angles, const std::vector<double>& angles_deg,
                          const std::filesystem::path& file) {
  const inversion::SamplesTable samples = inversion::read_samples_csv(o.posterior);
  sediment::SeabedModel drawn = seabed;
  std::vector<SampleTarget> targets;
  for (const std::string& name : samples.names) targets.push_back(sample_target(drawn, name, o.posterior));
  const std::vector<Eigen::Index> rows = inversion::evenly_spread_rows(samples.draws.rows(), o.posterior_draws);
  const std::size_t n_f = o.frequencies.size(), n_a = angles.size();
  std::vector<Eigen::VectorXd> loss(n_f * n_a, Eigen::VectorXd(static_cast<Eigen::Index>(rows.size())));
  for (std::size_t d = 0; d < rows.size(); ++d) {
    for (std::size_t j = 0; j < targets.size(); ++j) {
      const double value = samples.draws(rows[d], static_cast<Eigen::Index>(j));
      if (targets[j].index < 0) {
        targets[j].part->thickness = value;
      } else {
        targets[j].part->values[static_cast<std::size_t>(targets[j].index)] = value;
      }
    }
    for (std::size_t i = 0; i < n_f; ++i) {
      const std::vector<std::complex<double>> r =
          sediment::reflection_coefficients(sediment::layered_halfspace_at(drawn, o.frequencies[i]), angles,
                                            o.frequencies[i]);
      for (std::size_t a = 0; a < n_a; ++a) loss[i * n_a + a](static_cast<Eigen::Index>(d)) = sediment::bottom_loss_db(r[a]);
    }
  }
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# sedwave reflect: bottom loss -20 log10|R| [dB] over " << rows.size() << " posterior draws of "
        << o.posterior << "; quantiles 2.5, 16, 50, 84, 97.5 %\n"
        << "frequency_hz,grazing_deg,loss_db_q025,loss_db_q16,loss_db_q50,loss_db_q84,loss_db_q975\n";
    for (std::size_t i = 0; i < n_f; ++i) {
      for (std::size_t a = 0; a < n_a; ++a) {
        out << number(o.frequencies[i]) << ',' << number(angles_deg[a]);
        for (const double q : inversion::kBandQuantiles) out << ',' << number(sampling::quantile(loss[i * n_a + a], q) + 0.0);
        out << "\n";
      }
    }
  });
  std::printf("posterior: bottom loss quantiles over %zu draws of %s in %s\n", rows.size(), o.posterior.c_str(),
              file.string().c_str());
}

/// Flags a part's waves no sediment can have: a compressional speed outside the plausible range of
/// sediments, or a shear speed at or above sqrt(3)/2 c_p (a negative bulk modulus). Returns whether
/// it flagged.
bool flag_implausible_medium(const sediment::AcousticMedium& m, const std::string& part, double frequency_hz) {
  const inversion::PlausibleRange& range = *inversion::plausible_range("sound_speed");
  bool flagged = false;
  if (m.compressional_speed < range.lower || m.compressional_speed > range.upper) {
    std::printf("! %s at %g Hz: c_p = %.5g m/s outside [%g, %g] m/s (%s): likely %s\n", part.c_str(), frequency_hz,
                m.compressional_speed, range.lower, range.upper, range.basis,
                m.compressional_speed < range.lower ? range.below_cause : range.above_cause);
    flagged = true;
  }
  if (m.shear_speed >= std::sqrt(0.75) * m.compressional_speed) {
    std::printf("! %s at %g Hz: c_s / c_p = %.4g >= sqrt(3)/2, a negative bulk modulus: likely a shear parameter "
                "far too large\n",
                part.c_str(), frequency_hz, m.shear_speed / m.compressional_speed);
    flagged = true;
  }
  return flagged;
}

int run_reflect(const ReflectOptions& o) {
  std::vector<std::string> halfspace_sets = o.model.set_values;
  // A layered model (layered:...) names its layers' parameters lN.NAME itself.
  const bool layered_model = o.model.model.starts_with(sediment::kLayeredPrefix);
  if (layered_model && !o.layers.empty()) {
    throw UsageError("--layer: model '" + o.model.model + "' is layered itself (its layers' parameters are lN.NAME, "
                     "their thicknesses lN.thickness); use one or the other");
  }
  const auto layer_sets =
      layered_model ? std::map<int, std::vector<std::string>>{}
                    : split_layer_settings(halfspace_sets, static_cast<int>(o.layers.size()));
  ModelOptions halfspace_options = o.model;
  halfspace_options.set_values = halfspace_sets;
  sediment::SeabedModel seabed;
  seabed.water_speed = o.water_speed;
  seabed.water_density = o.water_density;
  seabed.fluid_only = o.fluid;
  for (std::size_t i = 0; i < o.layers.size(); ++i) {
    const auto found = layer_sets.find(static_cast<int>(i + 1));
    seabed.layers.push_back(layer_part(o.layers[i], static_cast<int>(i + 1),
                                       found == layer_sets.end() ? std::vector<std::string>{} : found->second));
  }
  const inversion::Candidate halfspace = candidate_of(setup_of(halfspace_options), ModelUse::Truth);
  const std::vector<std::string>& site_notes = halfspace.notes;
  seabed.halfspace = {halfspace.model, halfspace.parameters.values(), 0.0};
  if (!o.from_fit.empty()) {
    apply_fit_report(o.from_fit, seabed.halfspace, halfspace_sets);
  } else if (const std::vector<std::string> missing = inversion::values_not_given(halfspace); !missing.empty()) {
    // A layer's thickness or a grain contact's stiffness: no typical value stands in for it.
    throw UsageError("model '" + halfspace.model->name() + "': give " + comma_separated(missing) +
                     " (--set NAME=VALUE, or --from-fit)");
  }
  if (layered_model) {
    const sediment::SeabedModel stack = sediment::seabed_of(seabed.halfspace.model, seabed.halfspace.values,
                                                            seabed.water_speed, seabed.water_density);
    seabed.layers = stack.layers;
    seabed.halfspace = stack.halfspace;
  }
  for (const std::string& note : site_notes) std::printf("site: %s\n", note.c_str());
  if (!o.brc.empty() && o.frequencies.size() != 1) throw UsageError("--brc is for one --frequency (a table per frequency)");
  if (!o.env.empty() && !(o.water_depth > 0.0)) throw UsageError("--env needs --water-depth (the half-space's depth [m])");
  if (!o.env.empty() && !o.layers.empty()) {
    throw UsageError("--env writes a half-space line: leave out --layer (or write the layers' table with --brc)");
  }
  const sediment::AttenuationUnit unit = sediment::attenuation_unit_from_letter(o.env_unit.size() == 1 ? o.env_unit[0] : '?');

  const std::filesystem::path out(o.out);
  std::vector<OutputPath> outputs;
  for (const char* name : {"reflection.csv", "reflection_band.csv", "media.csv", "bottom_loss.gp", "bottom_loss.png",
                           "bottom_loss.svg", "waves.gp", "waves.png", "waves.svg"}) {
    outputs.push_back({"--out", out / name});
  }
  if (!o.brc.empty()) outputs.push_back({"--brc", o.brc});
  if (!o.env.empty()) outputs.push_back({"--env", o.env});
  std::vector<std::filesystem::path> inputs;
  if (const auto table = sediment::sediment_model_file(o.model.model)) inputs.emplace_back(*table);
  if (!o.model.site.empty()) inputs.emplace_back(o.model.site);
  if (!o.posterior.empty()) inputs.emplace_back(o.posterior);
  if (!o.from_fit.empty()) inputs.emplace_back(o.from_fit);
  check_outputs(outputs, inputs, "reflect");

  std::vector<double> angles_deg, angles;
  const int steps = static_cast<int>(std::floor(90.0 / o.angle_step + 1e-9));
  for (int i = 0; i <= steps; ++i) angles_deg.push_back(i * o.angle_step);
  if (angles_deg.back() < 90.0) angles_deg.push_back(90.0);
  for (const double a : angles_deg) angles.push_back(a * kDegree);

  const std::vector<std::string> names = part_names(seabed);
  std::vector<std::vector<std::complex<double>>> r;
  std::vector<std::vector<double>> band_power;
  bool flagged = false;
  std::printf("# %-36s %12s %10s %12s %10s %12s %10s\n", "part", "frequency_Hz", "c_p_m/s", "alpha_p_dB/m", "c_s_m/s",
              "alpha_s_dB/m", "rho_kg/m3");
  for (const double f : o.frequencies) {
    const sediment::LayeredHalfspace media = sediment::layered_halfspace_at(seabed, f);
    std::vector<sediment::AcousticMedium> listed;
    for (const sediment::MediumLayer& l : media.layers) listed.push_back(l.medium);
    listed.push_back(media.halfspace);
    for (std::size_t k = 0; k < listed.size(); ++k) {
      const sediment::AcousticMedium& m = listed[k];
      std::printf("  %-36s %12.6g %10.2f %12.4g %10.2f %12.4g %10.1f\n", names[k].c_str(), f, m.compressional_speed,
                  m.compressional_attenuation * kDbPerNeper, m.shear_speed, m.shear_attenuation * kDbPerNeper,
                  m.density);
    }
    for (std::size_t k = 0; k < listed.size(); ++k) flagged = flag_implausible_medium(listed[k], names[k], f) || flagged;
    r.push_back(sediment::reflection_coefficients(media, angles, f));
    if (o.band > 0.0) {
      band_power.push_back(sediment::band_averaged_power(
          [&](double fb) { return sediment::layered_halfspace_at(seabed, fb); }, angles, f, o.band, o.band_samples));
    }
    for (std::size_t j = 0; j < angles.size(); ++j) {
      if (std::abs(r.back()[j]) > 1.0 + 1e-9) {
        std::printf("! |R| = %.6g > 1 at %g deg, %g Hz: a seabed of passive media cannot reflect more than it "
                    "receives; likely a model outside its range\n",
                    std::abs(r.back()[j]), angles_deg[j], f);
        flagged = true;
      }
    }
  }
  std::filesystem::create_directories(out);
  write_reflection_csv(out / "reflection.csv", o.frequencies, angles_deg, r, band_power, o.band);
  double low = o.frequencies.front(), high = o.frequencies.front();
  for (const double f : o.frequencies) {
    low = std::min(low, f);
    high = std::max(high, f);
  }
  write_media_csv(out / "media.csv", seabed, low / 100.0, high * 100.0);
  if (!o.posterior.empty()) write_posterior_band(o, seabed, angles, angles_deg, out / "reflection_band.csv");
  std::printf("# grazing_deg bottom_loss_dB at each frequency (reflection.csv holds every %g deg)\n", o.angle_step);
  for (const double a : {5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0}) {
    std::size_t j = 0;
    while (j + 1 < angles_deg.size() && angles_deg[j] < a - 1e-9) ++j;
    if (std::abs(angles_deg[j] - a) > 1e-9) continue;
    std::printf("  %5g", a);
    for (std::size_t i = 0; i < o.frequencies.size(); ++i) std::printf(" %8.3f", sediment::bottom_loss_db(r[i][j]));
    std::printf("\n");
  }

  std::vector<std::string> frequency_labels;
  for (const double f : o.frequencies) frequency_labels.push_back(number(f));
  const std::string band_label = o.band > 0.0 ? number(o.band) + "-octave band average" : "";
  std::string title = "seabed: ";
  for (std::size_t k = 0; k < names.size(); ++k) title += (k ? " over " : "") + names[k];
  std::printf("%s\n", plot::draw_bottom_loss_plot(out, title, frequency_labels, band_label, !o.posterior.empty()).message.c_str());
  std::vector<bool> has_shear;
  for (const sediment::SeabedPart* part : parts_of(seabed)) has_shear.push_back(!o.fluid && part->model->has_shear());
  std::printf("%s\n", plot::draw_waves_plot(out, title, names, has_shear).message.c_str());

  if (!o.brc.empty()) {
    const std::vector<sediment::ReflectionTableRow> rows = sediment::toolbox_reflection_table(angles_deg, r.front());
    io::write_text_atomically(o.brc, [&](std::ostream& s) { sediment::write_reflection_table(s, rows); });
    std::printf("%s: BELLHOP bottom reflection table, %zu grazing angles at %g Hz (phase -arg R, degrees)\n",
                o.brc.c_str(), rows.size(), o.frequencies.front());
  }
  if (!o.env.empty()) {
    io::write_text_atomically(o.env, [&](std::ostream& s) {
      for (std::size_t i = 0; i < o.frequencies.size(); ++i) {
        const double f = o.frequencies[i];
        const sediment::LayeredHalfspace media = sediment::layered_halfspace_at(seabed, f);
        const std::string title_line = "sedwave " + seabed.halfspace.model->name() + " half-space at " + number(f) + " Hz";
        sediment::write_toolbox_environment(
            s, sediment::toolbox_environment(title_line, f, o.water_depth, media.halfspace, unit), o.water_speed,
            o.water_density);
      }
    });
    std::printf("%s: Acoustics Toolbox environment (blocks 1-6), %zu frequenc%s, attenuation unit '%s'\n",
                o.env.c_str(), o.frequencies.size(), o.frequencies.size() == 1 ? "y" : "ies", o.env_unit.c_str());
  }
  std::printf("%s: reflection.csv, media.csv\n", out.string().c_str());
  if (flagged) std::printf("WARNING: results flagged above (lines starting with '!'); exit status 3\n");
  return flagged ? kExitIncomplete : kExitOk;
}

}  // namespace

Command add_reflect_command(CLI::App& app) {
  auto o = std::make_shared<ReflectOptions>();
  o->model.model = "grain-shearing";
  CLI::App* cmd = app.add_subcommand(
      "reflect", "Plane-wave reflection coefficient of a seabed (a model's half-space under optional layers) against "
                 "grazing angle: bottom loss, phase, band averages, each part's waves; BELLHOP .brc and Acoustics "
                 "Toolbox .env files (docs/reflection.md)");
  add_model_options(*cmd, o->model, ModelUse::Truth);
  cmd->add_option("--layer", o->layers,
                  "a layer's model, top first (repeat the option); its parameters by --set lN.NAME=VALUE and its "
                  "thickness by --set lN.thickness=METRES");
  cmd->add_option("--frequency", o->frequencies, "frequencies [Hz] (comma-separated or repeated)")
      ->required()->delimiter(',')->check(finite_positive());
  cmd->add_option("--angle-step", o->angle_step, "grazing-angle step [deg] from 0 to 90")
      ->capture_default_str()->check(finite_in(1e-3, 90.0));
  cmd->add_option("--water-speed", o->water_speed, "sound speed of the water above [m/s]")
      ->capture_default_str()->check(water_speed_range());
  cmd->add_option("--water-density", o->water_density, "density of the water above [kg/m^3]")
      ->capture_default_str()->check(water_density_range());
  cmd->add_flag("--fluid", o->fluid, "leave shear waves out: every part a fluid");
  cmd->add_option("--band", o->band, "also |R|^2 averaged over a band this many octaves wide around each frequency "
                                     "(e.g. 0.3333 for third octaves); 0: none")
      ->capture_default_str()->check(finite_in(0.0, 4.0));
  cmd->add_option("--band-samples", o->band_samples, "frequencies averaged across each band")
      ->capture_default_str()->check(CLI::Range(2, 10001));
  cmd->add_option("--out", o->out, "output directory (reflection.csv, media.csv, bottom_loss.png, waves.png)")
      ->required();
  cmd->add_option("--brc", o->brc, "also write a BELLHOP bottom reflection coefficient file (one --frequency)");
  cmd->add_option("--env", o->env, "also write an Acoustics Toolbox environment file's first six blocks (one per "
                                   "--frequency): isovelocity water over the half-space");
  cmd->add_option("--env-unit", o->env_unit, "attenuation unit of --env: N (Np/m), M (dB/m), F (dB/(m kHz)), "
                                             "W (dB/wavelength), Q (quality factor)")
      ->capture_default_str()->check(CLI::IsMember({"N", "M", "F", "W", "Q"}));
  cmd->add_option("--water-depth", o->water_depth, "water depth for --env [m]")->check(finite_positive());
  cmd->add_option("--from-fit", o->from_fit,
                  "fit.json of sedwave invert: the half-space's parameter values (fitted and fixed); its model must "
                  "be --model");
  cmd->add_option("--posterior", o->posterior,
                  "posterior_samples.csv of sedwave invert --method posterior (columns: the half-space's parameters, "
                  "lN.NAME, lN.thickness): also the bottom loss's 2.5-97.5 % quantiles (reflection_band.csv, drawn as "
                  "a band); the other parameters as the options give them");
  cmd->add_option("--posterior-draws", o->posterior_draws, "posterior draws evaluated, evenly spread")
      ->capture_default_str()->check(CLI::Range(2, 100000));
  return {cmd, [o]() { return run_reflect(*o); }};
}

}  // namespace sedwave::app
