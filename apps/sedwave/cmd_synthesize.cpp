// `sedwave synthesize`: the observations a forward model predicts for known parameters over a
// planned band, with noise, as an observation CSV. Fitting the file back with `sedwave invert`
// shows what a measurement of that band and precision would determine (docs/inversion.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/models.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::app {

Command add_synthesize_command(CLI::App& app) {
  struct Options {
    std::string model = "lattice";
    double kappa = 0.0, diameter = 0.0, density = 2650.0;
    std::optional<double> gamma, restitution;
    inversion::SyntheticDesign design;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "synthesize", "Write the attenuation and sound speed a model predicts for given kappa, d and gamma (or e_n) "
                    "at log-spaced frequencies, with relative Gaussian noise, as an observation CSV (SI units)");
  cmd->add_option("--model", o->model,
                  "continuum | lattice | table:FILE.h5[?extrapolate=theory|long-wavelength]")->capture_default_str();
  cmd->add_option("--kappa", o->kappa, "contact stiffness [N/m]")->required()->check(finite_positive());
  cmd->add_option("--d", o->diameter, "grain diameter [m]")->required()->check(finite_positive());
  auto* gamma = cmd->add_option("--gamma", o->gamma, "normal dashpot [kg/s]")->check(finite_positive());
  auto* en = cmd->add_option("--en", o->restitution, "restitution coefficient e_n in (0, 1)")
                 ->check(finite_in(1e-6, 0.999999));
  gamma->excludes(en);
  cmd->add_option("--density", o->density, "grain density rho_s [kg/m^3]")->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--from", o->design.lowest_hz, "lowest frequency [Hz]")->required()->check(finite_positive());
  cmd->add_option("--to", o->design.highest_hz, "highest frequency [Hz]")->required()->check(finite_positive());
  cmd->add_option("--points", o->design.points, "log-spaced frequencies (each gives one attenuation and one speed)")
      ->capture_default_str()->check(CLI::Range(2, 100000));
  cmd->add_option("--alpha-noise", o->design.alpha_noise, "relative 1-sigma noise of the attenuation, also its sigma")
      ->capture_default_str()->check(finite_positive());
  cmd->add_option("--speed-noise", o->design.speed_noise, "relative 1-sigma noise of the sound speed, also its sigma")
      ->capture_default_str()->check(finite_positive());
  cmd->add_option("--seed", o->design.seed, "seed of the noise")->capture_default_str();
  cmd->add_option("--out", o->out, "observation CSV to write")->required();
  return {cmd, [o]() {
    if (!o->gamma && !o->restitution) throw std::invalid_argument("give the damping: --gamma or --en");
    inversion::FitParameters truth;
    truth.density = o->density;
    if (o->restitution) truth.set_damping_form(inversion::DampingForm::Restitution);
    truth.spec[inversion::kKappa].value = o->kappa;
    truth.spec[inversion::kDiameter].value = o->diameter;
    truth.spec[inversion::kDamping].value = o->restitution ? *o->restitution : *o->gamma;
    if (!(o->design.highest_hz > o->design.lowest_hz)) {
      throw std::invalid_argument("--from must be below --to");
    }
    std::vector<std::filesystem::path> inputs;
    if (const auto table = forward::dispersion_model_file(o->model)) inputs.emplace_back(*table);
    check_outputs({{"--out", o->out}}, inputs, "synthesize");
    const auto model = forward::make_dispersion_model(o->model);
    const inversion::ObservationSet set = inversion::synthetic_observations(*model, truth, o->design);
    char truth_line[256], noise_line[160];
    std::snprintf(truth_line, sizeof truth_line, "synthetic_truth: kappa %.9g N/m, d %.9g m, %s %.9g%s, rho_s %.9g kg/m^3",
                  o->kappa, o->diameter, o->restitution ? "e_n" : "gamma",
                  truth.spec[inversion::kDamping].value, o->restitution ? "" : " kg/s", o->density);
    std::snprintf(noise_line, sizeof noise_line,
                  "synthetic_noise: relative Gaussian, attenuation %g, sound speed %g (also the sigmas), seed %u",
                  o->design.alpha_noise, o->design.speed_noise, o->design.seed);
    inversion::write_observation_csv(o->out, set,
                                     {"data_kind: SYNTHETIC, not measurements (sedwave synthesize)",
                                      "synthetic_model: " + model->name(), truth_line, noise_line});
    std::printf("%s: %zu observations from %s, %g-%g Hz\n", o->out.c_str(), set.observations.size(),
                model->name().c_str(), o->design.lowest_hz, o->design.highest_hz);
    return 0;
  }};
}

}  // namespace sedwave::app
