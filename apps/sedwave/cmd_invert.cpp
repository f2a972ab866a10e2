// `sedwave invert`: fit grain-contact parameters to observation files and report what the data
// determine, with a plot; with --method posterior, the library's posterior study
// (sedwave/inversion/study.hpp) from that fit.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "model_options.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/plot/plot.hpp"
#include "sedwave/plot/reflection_plot.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/study.hpp"
#include "sedwave/inversion/report.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::app {
namespace {

struct InvertOptions {
  std::vector<std::string> files;
  std::vector<std::string> digitized_files;
  std::vector<std::string> digitized_specs;
  ModelOptions model;
  std::string method = "global";
  std::string out = "sedwave-fit";
  std::optional<double> water_speed, sediment_speed;
  inversion::FitOptions fit_options;
  std::vector<std::string> priors;  ///< NAME=KIND:A,B
  inversion::PosteriorOptions posterior;
  int threads = 1;
  bool plot = true;
};

/// "QUANTITY:FREQ_UNIT:VALUE_UNIT[:REL_SIGMA]" -> DigitizedColumns.
inversion::DigitizedColumns parse_digitized_spec(const std::string& spec) {
  std::vector<std::string> parts;
  std::stringstream stream(spec);
  for (std::string part; std::getline(stream, part, ':');) parts.push_back(part);
  if (parts.size() < 3 || parts.size() > 4) {
    throw std::invalid_argument("--digitized '" + spec + "': expected QUANTITY:FREQ_UNIT:VALUE_UNIT[:REL_SIGMA]");
  }
  inversion::DigitizedColumns columns{parts[0], parts[1], parts[2], std::nullopt};
  if (parts.size() == 4) {
    try {
      columns.relative_sigma = std::stod(parts[3]);
    } catch (const std::exception&) {
      throw std::invalid_argument("--digitized '" + spec + "': REL_SIGMA '" + parts[3] + "' is not a number");
    }
  }
  return columns;
}

inversion::ObservationSet read_all(const InvertOptions& o) {
  const inversion::ReadOptions read{o.water_speed, o.sediment_speed};
  inversion::ObservationSet all;
  for (const std::string& f : o.files) all.append(inversion::read_observation_csv(f, read));
  if (!o.digitized_files.empty() && o.digitized_specs.size() != 1 && o.digitized_specs.size() != o.digitized_files.size()) {
    throw std::invalid_argument("give one --digitized spec for all --digitized-file, or one per file");
  }
  for (size_t i = 0; i < o.digitized_files.size(); ++i) {
    const std::string& spec = o.digitized_specs[o.digitized_specs.size() == 1 ? 0 : i];
    all.append(inversion::read_digitized_csv(o.digitized_files[i], parse_digitized_spec(spec), read));
  }
  if (!all.water_sound_speed) all.water_sound_speed = o.water_speed;
  if (all.observations.empty()) throw std::invalid_argument("no observation files given");
  return all;
}

/// "open" for a missing end of a profile interval (the data do not bound the quantity there: chi^2
/// stays within 1 up to the search bounds, or only another parameter's bound raises it).
std::string format_end(const std::optional<double>& end) {
  if (!end) return "open";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", *end);
  return text;
}

/// One reported quantity: a determined value with its sigma, or, when the data do not determine
/// it, its profile range and never a bare best value (along a flat direction the best-fit point is
/// wherever the solver stopped).
void print_quantity(const std::string& name, const std::string& unit, double value, double sigma, bool free,
                    bool determined, bool at_bound, const std::optional<double>& lower,
                    const std::optional<double>& upper, bool profiled) {
  std::printf("  %-16s [%-4s] ", name.c_str(), unit.c_str());
  const std::string range =
      profiled ? "(profile 68%: " + format_end(lower) + " .. " + format_end(upper) + ")" : std::string();
  if (!free) {
    std::printf("%.6g (fixed)\n", value);
  } else if (at_bound) {
    std::printf("AT ITS SEARCH BOUND %.6g: not an estimate  %s\n", value, range.c_str());
  } else if (determined) {
    std::printf("%.6g +- %.2g  %s\n", value, sigma, range.c_str());
  } else {
    std::printf("NOT DETERMINED by these data  %s  [best-fit point %.4g]\n", range.c_str(), value);
  }
}

/// A second solution within this chi^2 of the fit's (a likelihood ratio above e^-2) is about as good.
constexpr double kComparableChi2 = 4.0;

/// The global search's other local minima (fit.json "other_minima"): another solution of the data,
/// which the fit's sigmas, taken at one minimum, do not describe.
void print_other_minima(const inversion::FitResult& r) {
  for (const inversion::LocalMinimum& m : r.other_minima) {
    std::string at;
    for (const int i : r.fitted.free_indices()) {
      const auto& spec = r.fitted.spec[static_cast<std::size_t>(i)];
      if (!at.empty()) at += ", ";
      char value[32];
      std::snprintf(value, sizeof value, " %.4g", m.values[static_cast<std::size_t>(i)]);
      at += spec.name;
      at += value;
      if (!spec.unit.empty() && spec.unit != "1") at += " " + spec.unit;
    }
    const double above = m.chi2 - r.chi2;
    std::printf("another local minimum of chi2 (a barrier between it and the fit): %s; chi2 %.6g, %.3g above the "
                "fit's%s\n",
                at.c_str(), m.chi2, above,
                above < kComparableChi2 ? ": the data hardly choose between the two solutions, and the sigmas above "
                                          "describe the fit's alone"
                                        : "");
  }
}

void print_summary(const inversion::FitResult& r, const plot::PlotOutcome& plot, const std::string& out,
                   bool profiled) {
  std::printf("sedwave invert: model %s, method %s, %d observations, %.1f ms\n", r.model.c_str(), r.method.c_str(),
              r.n_observations, 1e3 * r.wall_seconds);
  std::printf("\nparameters:\n");
  for (const auto& p : r.parameters) {
    print_quantity(p.name, p.unit, p.value, p.sigma, p.free, p.determined, p.at_bound, p.profile_lower,
                   p.profile_upper, profiled && p.free);
  }
  if (!r.derived.empty()) std::printf("\ncombinations the data may determine:\n");
  for (const auto& c : r.derived) {
    print_quantity(c.name, c.unit, c.value, c.sigma, true, c.determined, false, c.profile_lower, c.profile_upper,
                   profiled);
  }
  for (const auto& w : r.weak_directions) {
    std::printf("  %s at the best fit: %s\n", w.unseen ? "unseen direction" : "poorly constrained",
                w.direction.c_str());
  }
  std::printf("\nchi2 = %.4g for %d dof (reduced %.3g), AIC %.4g, BIC %.4g, %s\n", r.chi2, r.dof,
              r.dof > 0 ? r.chi2 / r.dof : NAN, r.aic, r.bic, r.converged ? "converged" : "NOT converged");
  const double reduced = r.dof > 0 ? r.chi2 / r.dof : 0.0;
  if (reduced > 2.0) {
    std::printf("warning: reduced chi2 %.3g >> 1: the model does not describe these data within their stated "
                "errors;\n         the sigmas above are formal (scaled by sqrt(reduced chi2) they grow %.2gx)\n",
                reduced, std::sqrt(reduced));
  }
  if (r.profile_restarts > 0) {
    std::printf("note: a likelihood profile found a lower chi2 than the solvers; the fit moved there (%d time%s)\n",
                r.profile_restarts, r.profile_restarts > 1 ? "s" : "");
  }
  if (r.global && !std::isfinite(r.global->chi2_local_from_start)) {
    // The start values lie where the model does not answer (e.g. outside a table): only the global
    // search could start there, so there is no comparison to make.
    std::printf("global search (%s, %d evaluations); a local fit from the start values could not start (the model "
                "has no value there)\n",
                r.global->algorithm.c_str(), r.global->evaluations);
  } else if (r.global) {
    std::printf("global search (%s, %d evaluations) and local fit from the start values %s (chi2 %.6g vs %.6g)\n",
                r.global->algorithm.c_str(), r.global->evaluations,
                r.global->local_and_global_agree ? "agree" : "DISAGREE", r.global->chi2_polished,
                r.global->chi2_local_from_start);
  }
  print_other_minima(r);
  if (!r.flags.empty()) {
    std::printf("\nWARNING: %zu result%s outside physical ranges or at search bounds (fit.json \"flags\"):\n",
                r.flags.size(), r.flags.size() > 1 ? "s" : "");
    for (const auto& f : r.flags) std::printf("  ! %s\n", f.message.c_str());
  }
  std::printf("\nreport: %s/fit.json, curves: %s/curves.csv\n%s\n", out.c_str(), out.c_str(), plot.message.c_str());
}

/// Beside an interval that the prior rather than the data made (posterior.hpp, prior_dominated).
std::string prior_note(const inversion::PosteriorQuantity& q) {
  if (!q.prior_dominated) return "";
  return "  PRIOR-CONTROLLED (prior's share " + std::to_string(std::lround(100.0 * q.prior_share)) + " %)";
}

void print_posterior(const inversion::PosteriorResult& p, const std::string& out) {
  const std::string ladder =
      p.temperatures > 0 ? "parallel tempering, " + std::to_string(p.temperatures) + " rungs of " : "";
  std::printf("\nposterior (%s%d walkers x %d steps of at most %d, first half burn-in; acceptance %.2f; %.1f s):\n",
              ladder.c_str(), p.walkers, p.steps, p.steps_cap, p.acceptance, p.wall_seconds);
  std::printf("  priors:\n");
  for (const std::string& line : p.priors) std::printf("    %s\n", line.c_str());
  std::printf("  %-16s %-6s %11s  %-23s  %-23s %6s %7s\n", "quantity", "unit", "median", "68% credible",
              "95% credible", "R-hat", "ESS");
  const auto row = [](const inversion::PosteriorQuantity& q) {
    std::printf("  %-16s %-6s %11.4g  %10.4g .. %-10.4g  %10.4g .. %-10.4g %6.3f %7.0f%s\n", q.name.c_str(),
                q.unit.c_str(), q.median, q.lower_68, q.upper_68, q.lower_95, q.upper_95, q.split_rhat,
                q.effective_samples, prior_note(q).c_str());
  };
  for (const auto& q : p.parameters) row(q);
  for (const auto& q : p.derived) row(q);
  if (p.converged) {
    std::printf("  converged (kept steps >= 50 autocorrelation times, effective sample sizes >= 400, walkers agree%s)\n",
                p.temperatures > 0 ? "; every rung mixed" : "");
  } else {
    std::printf("  NOT CONVERGED: %s\n", p.advice.c_str());
  }
  std::printf("  samples: %s/posterior_samples.csv and .h5, band over the data: %s/posterior_predictive.csv, "
              "marginal densities: %s/posterior_marginals.csv\n",
              out.c_str(), out.c_str(),
              out.c_str());
}

/// From this many observations on, a fit takes seconds to minutes: it reports its stages on stderr.
constexpr std::size_t kProgressObservations = 10000;

/// Every file the run reads: observation and digitised files, and a table model's file.
std::vector<std::filesystem::path> input_files(const InvertOptions& o) {
  std::vector<std::filesystem::path> inputs(o.files.begin(), o.files.end());
  inputs.insert(inputs.end(), o.digitized_files.begin(), o.digitized_files.end());
  if (const auto table = sediment::sediment_model_file(o.model.model)) inputs.emplace_back(*table);
  if (!o.model.site.empty()) inputs.emplace_back(o.model.site);
  return inputs;
}

std::vector<OutputPath> output_files(const std::filesystem::path& out) {
  std::vector<OutputPath> outputs;
  for (const char* name : {"fit.json", "curves.csv", "observations.csv", "fit.gp", "fit.png", "fit.svg",
                           "posterior_samples.csv", "posterior_samples.h5", "posterior_marginals.csv",
                           "posterior_corner.gp", "posterior_corner.png", "posterior_corner.svg",
                           "posterior_corner_density.dat",
                           "posterior_predictive.csv", "posterior_residuals.csv", "posterior_predictive.gp",
                           "posterior_predictive.png", "posterior_predictive.svg", "bottom_loss_curves.csv",
                           "bottom_loss_fit.gp", "bottom_loss_fit.png", "bottom_loss_fit.svg"}) {
    const bool hdf5 = std::filesystem::path(name).extension() == ".h5";
    outputs.push_back({"--out", out / name, hdf5 ? io::OutputFormat::seekable : io::OutputFormat::text});
  }
  return outputs;
}

}  // namespace

Command add_invert_command(CLI::App& app) {
  auto o = std::make_shared<InvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "invert", "Fit a sediment model's parameters (by default the grain contact's kappa, d and gamma or e_n) to "
                "attenuation/sound-speed observations (SI units; see docs/cli.md, sedwave models)");
  cmd->add_option("files", o->files, "observation CSV files (docs/file-formats.md)");
  cmd->add_option("--digitized-file", o->digitized_files, "WebPlotDigitizer x,y export (repeatable)");
  cmd->add_option("--digitized", o->digitized_specs,
                  "QUANTITY:FREQ_UNIT:VALUE_UNIT[:REL_SIGMA] for --digitized-file (one for all, or one each)");
  add_model_options(*cmd, o->model, ModelUse::Fit);
  cmd->add_option("--method", o->method,
                  "ceres (local) | nlopt (global search) | global (search + polish) | posterior (global, then the "
                  "Bayesian posterior with --prior; docs/inversion.md)")
      ->capture_default_str()->check(CLI::IsMember({"ceres", "nlopt", "global", "posterior"}));
  cmd->add_option("--prior", o->priors,
                  "NAME=KIND:A,B, KIND uniform | log-uniform | normal | log-normal (A,B: bounds, mean and sd, or median "
                  "and sd of ln) [SI]; default log-uniform over the search bounds (repeatable; --method posterior)");
  auto* walkers = cmd->add_option("--walkers", o->posterior.walkers,
                                  "posterior: ensemble walkers (0: max(4 x free, 16))")
      ->capture_default_str()->check(CLI::Range(0, 100000));
  auto* steps = cmd->add_option("--steps", o->posterior.steps,
                                "posterior: the most ensemble updates; the run stops once converged, the first half "
                                "discarded as burn-in")
      ->capture_default_str()->check(CLI::Range(10, 10000000));
  auto* temperatures =
      cmd->add_option("--temperatures", o->posterior.temperatures,
                      "posterior: rungs of a parallel-tempering ladder (0: one ensemble; -1: " +
                          std::to_string(inversion::PosteriorOptions::kAutoTemperatures) +
                          " where a parameter with a flat prior is left open by the data and the other priors, else one ensemble)")
          ->capture_default_str()->check(CLI::Range(-1, 1000));
  add_threads_option(*cmd, o->threads,
                     "posterior: threads that share each half-ensemble's evaluations (they meet at every "
                     "half-step, which on a busy machine costs more than it saves)");
  cmd->add_option("--out", o->out, "output directory")->capture_default_str();
  cmd->add_option("--water-speed", o->water_speed, "water sound speed [m/s] for sound-speed ratios")
      ->check(finite_in(inversion::kLowestDeclaredSpeed, inversion::kHighestDeclaredSpeed));
  cmd->add_option("--sediment-speed", o->sediment_speed, "sediment sound speed [m/s] to convert dB/wavelength")
      ->check(finite_in(inversion::kLowestDeclaredSpeed, inversion::kHighestDeclaredSpeed));
  cmd->add_option("--default-sigma", o->fit_options.default_relative_sigma,
                  "relative 1-sigma for observations given without one")->capture_default_str()
      ->check(finite_in(1e-12, 10.0));
  cmd->add_option("--global-algorithm", o->fit_options.global_algorithm, "direct-l | crs2 | mlsl")->capture_default_str()
      ->check(CLI::IsMember({"direct-l", "crs2", "mlsl"}));
  cmd->add_option("--max-evaluations", o->fit_options.max_global_evaluations, "global search budget")
      ->capture_default_str()->check(CLI::Range(10, 10000000));
  cmd->add_option("--determined-log-sigma", o->fit_options.determined_log_sigma,
                  "largest 1-sigma of ln(value) that still counts as determined")->capture_default_str()
      ->check(finite_in(1e-6, 10.0));
  cmd->add_flag("!--no-plot", o->plot, "skip the gnuplot figure");
  cmd->add_flag("!--no-profile", o->fit_options.profile_likelihood,
                "skip the likelihood profiles (most of a fit's time on large files); determination then rests on "
                "the linearised sigmas alone");

  return {cmd, [o, walkers, steps, temperatures]() {
            for (const CLI::Option* sampler : {walkers, steps, temperatures}) {
              if (sampler->count() > 0 && o->method != "posterior") {
                throw UsageError(sampler->get_name() + " is for --method posterior; --method " + o->method +
                                 " does not sample");
              }
            }
            const std::filesystem::path out(o->out);
            check_outputs(output_files(out), input_files(*o), "invert");
            const inversion::ObservationSet data = read_all(*o);
            const bool posterior = o->method == "posterior";
            if (!o->priors.empty() && !posterior) throw UsageError("--prior is for --method posterior");
            inversion::ModelSetup setup = setup_of(o->model);
            setup.priors = o->priors;
            const inversion::Candidate candidate = candidate_of(setup);
            const auto& model = candidate.model;
            const std::vector<std::string>& site_notes = candidate.notes;
            for (const std::string& note : site_notes) std::printf("site: %s\n", note.c_str());
            inversion::FitOptions options = o->fit_options;
            options.method = inversion::parse_fit_method(posterior ? "global" : o->method);
            const io::OutputLock lock(out, "--out");  // after every check: a refused run waits for nothing
            io::DeferredCommits outputs;  // a failed run leaves the previous outputs, not half of its own
            if (data.observations.size() >= kProgressObservations) {
              const auto started = std::chrono::steady_clock::now();
              options.progress = [started](const std::string& stage) {
                const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
                std::fprintf(stderr, "sedwave invert: %7.1f s: %s\n", s, stage.c_str());
              };
            }
            const inversion::FitResult result = inversion::fit(data, *model, candidate.parameters, options);

            nlohmann::json report = inversion::fit_report(result, data);
            std::optional<inversion::PosteriorStudy> sampled;
            if (posterior) {
              inversion::PosteriorOptions posterior_options = o->posterior;
              posterior_options.threads = threads_to_use(o->threads);
              posterior_options.progress = [](const std::string& line) {
                std::fprintf(stderr, "sedwave invert: posterior: %s\n", line.c_str());
              };
              sampled = inversion::posterior_study(data, *model, result, candidate.priors, options, posterior_options);
              report["posterior"] = inversion::posterior_report(sampled->posterior);
              inversion::write_posterior_study(out, *sampled, result, data);
            }
            if (!site_notes.empty()) report["site_inputs"] = site_notes;
            // A table model may have answered some evaluations with the 1D theory or its long-wavelength
            // limit outside its range: the report must say so, or a theory fit would pass for a table fit.
            if (const forward::DispersionModel* engine = model->dimensionless_engine()) {
              for (const forward::ModelDiagnostic& d : engine->diagnostics()) {
                report[d.key] = d.count;
                if (!d.note.empty()) std::printf("note: %s\n", d.note.c_str());
              }
            }
            io::write_text_atomically(out / "fit.json", [&](std::ostream& s) { s << report.dump(2) << "\n"; });
            if (const std::size_t left_out = inversion::write_fit_files(out, result, *model, data); left_out > 0) {
              std::printf("note: the model curves leave out %zu of %zu frequencies, where %s does not answer\n",
                          left_out, inversion::curve_frequencies(data).size(), result.model.c_str());
            }
            outputs.commit_all();  // the plots read them
            plot::PlotOutcome plot{false, "plot skipped (--no-plot)"};
            if (o->plot) {
              const bool chain = o->model.model == "lattice" || o->model.model == "continuum";
              plot = plot::draw_fit_plot(out, "sedwave fit: " + result.model + (chain ? " chain model" : ""),
                                              data.water_sound_speed.has_value(), result);
              if (const std::vector<double> at = inversion::reflection_frequencies(data); !at.empty()) {
                const plot::PlotOutcome loss =
                    plot::draw_bottom_loss_fit_plot(out, "sedwave fit: " + result.model + ", bottom loss", at);
                plot.message += "\n" + loss.message;
              }
            }
            print_summary(result, plot, o->out, options.profile_likelihood);
            if (sampled) {
              print_posterior(sampled->posterior, o->out);
              if (o->plot) {
                for (const std::string& message : plot::draw_posterior_plots(out, *sampled, result, data)) {
                  std::printf("  %s\n", message.c_str());
                }
              }
            }
            const bool sampled_ok = !sampled || sampled->posterior.converged;
            return result.converged && sampled_ok && result.flags.empty() ? kExitOk : kExitIncomplete;
          }};
}

}  // namespace sedwave::app
