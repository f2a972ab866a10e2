// `sedwave synthesize`: the observations a forward model predicts for known parameters over a
// planned band, with noise, as an observation CSV. Fitting the file back with `sedwave invert`
// shows what a measurement of that band and precision would determine (docs/inversion.md).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "option_checks.hpp"
#include "model_options.hpp"
#include "output_paths.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/inversion/plausibility.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::app {
namespace {

/// Flags synthetic sound speeds outside what any sediment can have (inversion/plausibility.hpp,
/// sound_speed): parameters far from any sediment (a kappa 10^6 times too stiff) make speeds no
/// data would show.
/// Returns whether any was flagged.
bool flag_implausible_speeds(const inversion::ObservationSet& set) {
  const inversion::PlausibleRange& range = *inversion::plausible_range("sound_speed");
  std::size_t outside = 0, speeds = 0;
  const inversion::Observation* worst = nullptr;
  for (const inversion::Observation& ob : set.observations) {
    if (ob.quantity != inversion::Quantity::SoundSpeed) continue;
    ++speeds;
    if (ob.value >= range.lower && ob.value <= range.upper) continue;
    ++outside;
    const auto distance = [&](double c) { return c < range.lower ? range.lower / c : c / range.upper; };
    if (!worst || !(distance(ob.value) <= distance(worst->value))) worst = &ob;
  }
  if (outside == 0) return false;
  std::printf("! %zu of %zu sound speeds lie outside [%g, %g] m/s (%s); the farthest: %.4g m/s at %.4g Hz: "
              "likely %s\n",
              outside, speeds, range.lower, range.upper, range.basis, worst->value, worst->frequency_hz,
              worst->value < range.lower ? range.below_cause : range.above_cause);
  return true;
}

}  // namespace

Command add_synthesize_command(CLI::App& app) {
  struct Options {
    ModelOptions model;
    inversion::SyntheticDesign design;
    std::vector<double> grazing_angles_deg;
    bool reflection_only = false;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "synthesize", "Write the attenuation and sound speed a sediment model predicts for given parameters (by default "
                    "the grain contact's kappa, d and gamma or e_n) at log-spaced frequencies, and the bottom loss at "
                    "grazing angles if asked, with noise, as an observation CSV (SI units)");
  add_model_options(*cmd, o->model, ModelUse::Truth);
  cmd->add_option("--from", o->design.lowest_hz, "lowest frequency [Hz]")->required()->check(finite_positive());
  cmd->add_option("--to", o->design.highest_hz, "highest frequency [Hz]")->required()->check(finite_positive());
  cmd->add_option("--points", o->design.points, "log-spaced frequencies (each gives one attenuation and one speed)")
      ->capture_default_str()->check(CLI::Range(2, 100000));
  cmd->add_option("--alpha-noise", o->design.alpha_noise, "relative 1-sigma noise of the attenuation, also its sigma")
      ->capture_default_str()->check(finite_positive());
  cmd->add_option("--speed-noise", o->design.speed_noise, "relative 1-sigma noise of the sound speed, also its sigma")
      ->capture_default_str()->check(finite_positive());
  cmd->add_option("--seed", o->design.seed, "seed of the noise")->capture_default_str();
  cmd->add_option("--grazing-angles", o->grazing_angles_deg,
                  "grazing angles [deg], comma-separated: bottom-loss rows at each frequency and angle, water over "
                  "the seabed the model describes (docs/reflection.md)")
      ->delimiter(',')->check(CLI::Range(0.0, 90.0));
  cmd->add_option("--bottom-loss-sigma", o->design.bottom_loss_sigma_db, "1-sigma Gaussian noise of the bottom loss [dB], also its sigma")
      ->capture_default_str()->check(finite_in(1e-6, 100.0));
  cmd->add_option("--water-speed", o->design.water_speed, "sound speed of the water above [m/s] (bottom-loss rows)")
      ->capture_default_str()->check(water_speed_range());
  cmd->add_option("--water-density", o->design.water_density, "density of the water above [kg/m^3] (bottom-loss rows)")
      ->capture_default_str()->check(water_density_range());
  cmd->add_flag("--reflection-only", o->reflection_only, "bottom-loss rows only (no attenuation and sound speed)");
  cmd->add_option("--out", o->out, "observation CSV to write")->required();
  return {cmd, [o]() {
    const inversion::Candidate candidate = candidate_of(setup_of(o->model), ModelUse::Truth);
    const auto& model = candidate.model;
    const inversion::FitParameters& truth = candidate.parameters;
    for (const std::string& note : candidate.notes) std::printf("site: %s\n", note.c_str());
    // A grain contact has no typical values to fall back on: its truth must be given.
    const std::vector<std::string> missing = inversion::values_not_given(candidate);
    const auto lacks = [&](const char* name) { return std::ranges::find(missing, name) != missing.end(); };
    if (lacks("kappa") || lacks("d")) {
      throw std::invalid_argument("give the grain contact: --kappa (or --depth, --effective-pressure) and --d (or --phi)");
    }
    if (lacks("gamma") || lacks("e_n")) throw std::invalid_argument("give the damping: --gamma or --en");
    if (!missing.empty()) {  // a layer's thickness, or a model's own parameter without a typical value
      throw std::invalid_argument("give " + comma_separated(missing) + " (--set NAME=VALUE): no typical value stands in for it");
    }
    if (!(o->design.highest_hz > o->design.lowest_hz)) {
      throw std::invalid_argument("--from must be below --to");
    }
    for (const double degrees : o->grazing_angles_deg) {
      if (!(degrees > 0.0)) throw UsageError("--grazing-angles: a grazing angle must be in (0, 90] degrees");
      o->design.grazing_angles.push_back(degrees * std::numbers::pi / 180.0);
    }
    if (o->reflection_only && o->design.grazing_angles.empty()) {
      throw UsageError("--reflection-only needs --grazing-angles (the bottom-loss rows to write)");
    }
    o->design.waves = !o->reflection_only;
    std::vector<std::filesystem::path> inputs;
    if (const auto table = sediment::sediment_model_file(o->model.model)) inputs.emplace_back(*table);
    check_outputs({{"--out", o->out}}, inputs, "synthesize");
    const inversion::ObservationSet set = inversion::synthetic_observations(*model, truth, o->design);
    std::ostringstream truth_line;
    truth_line.precision(9);
    truth_line << "synthetic_truth:";
    for (std::size_t i = 0; i < truth.spec.size(); ++i) {
      truth_line << (i ? ", " : " ") << truth.spec[i].name << " " << truth.spec[i].value
                 << (truth.spec[i].unit == "1" ? "" : " " + truth.spec[i].unit);
    }
    char noise_line[240];
    if (o->reflection_only) {
      std::snprintf(noise_line, sizeof noise_line, "synthetic_noise: Gaussian, bottom loss %g dB (also the sigma), seed %u",
                    o->design.bottom_loss_sigma_db, o->design.seed);
    } else {
      std::snprintf(noise_line, sizeof noise_line,
                    "synthetic_noise: relative Gaussian, attenuation %g, sound speed %g (also the sigmas)%s, seed %u",
                    o->design.alpha_noise, o->design.speed_noise,
                    o->design.grazing_angles.empty() ? "" : "; Gaussian, bottom loss (dB) as its sigma", o->design.seed);
    }
    inversion::write_observation_csv(o->out, set,
                                     {"data_kind: SYNTHETIC, not measurements (sedwave synthesize)",
                                      "synthetic_model: " + model->name(), truth_line.str(), noise_line});
    std::printf("%s: %zu observations from %s, %g-%g Hz\n", o->out.c_str(), set.observations.size(),
                model->name().c_str(), o->design.lowest_hz, o->design.highest_hz);
    return flag_implausible_speeds(set) ? kExitIncomplete : kExitOk;
  }};
}

}  // namespace sedwave::app
