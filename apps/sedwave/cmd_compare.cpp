// `sedwave compare`: several sediment models fitted to the same data and ranked by their evidence
// (the probability of the data under each model and its priors), beside chi^2, AIC and BIC, with a
// posterior-predictive check; and the ranking again with every prior widened tenfold, since
// evidence depends on priors (docs/inversion.md, "Comparing models").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "job_queue.hpp"
#include "model_options.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/plot.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/predictive.hpp"
#include "sedwave/inversion/report.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::app {
namespace {

struct CompareOptions {
  std::vector<std::string> files;
  std::string models;
  std::vector<std::string> fits;    ///< MODEL=a,b,c
  std::vector<std::string> priors;  ///< NAME=KIND:A,B, for every model that has NAME free
  ModelOptions shared;              ///< --set and site inputs, for every model that has the parameter
  std::optional<double> water_speed;
  inversion::EvidenceOptions evidence;
  int threads = 0;  ///< 0: every usable core
  bool plot = true;
  std::string out = "sedwave-compare";
};

struct Row {
  std::string model;
  std::string free;
  inversion::FitResult fit;
  std::vector<std::string> priors;
  inversion::ModelEvidence evidence, widened;
  inversion::PredictiveBand band;
};

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, by);) parts.push_back(part);
  return parts;
}

std::string name_of(const std::string& item) { return item.substr(0, item.find('=')); }

bool has_parameter(const sediment::SedimentModel& model, const std::string& name) {
  const auto& ps = model.parameters();
  return std::any_of(ps.begin(), ps.end(), [&](const sediment::Parameter& p) { return p.name == name; });
}

/// Every name a shared option uses must belong to at least one of the models (a typo is refused).
void require_known(const std::vector<std::string>& items, const char* option,
                   const std::vector<std::shared_ptr<const sediment::SedimentModel>>& models) {
  for (const std::string& item : items) {
    const std::string name = name_of(item);
    const bool known = std::any_of(models.begin(), models.end(), [&](const auto& m) { return has_parameter(*m, name); });
    if (!known) throw UsageError(std::string(option) + " '" + item + "': none of the models has a parameter '" + name + "'");
  }
}

/// --models names each model once: an empty list or item, or one spec twice, is refused.
void check_model_list(const std::string& option, const std::vector<std::string>& names) {
  if (names.empty()) throw UsageError("--models '" + option + "': name at least one model (sedwave models)");
  if (option.front() == ',' || option.back() == ',' || option.find(",,") != std::string::npos) {
    throw UsageError("--models '" + option + "': an empty model name");
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (names[i] == names[j]) {
        throw UsageError("--models '" + option + "' names '" + names[i] + "' twice: its rows would be identical");
      }
    }
  }
}

/// Each --fit MODEL=a,b names one of --models, a non-empty list, and no model twice.
void check_fits(const std::vector<std::string>& fits, const std::vector<std::string>& model_names) {
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const std::string& f = fits[i];
    if (f.find('=') == std::string::npos) throw UsageError("--fit '" + f + "': expected MODEL=a,b,c");
    if (std::find(model_names.begin(), model_names.end(), name_of(f)) == model_names.end()) {
      throw UsageError("--fit '" + f + "': '" + name_of(f) + "' is not one of --models");
    }
    if (f.back() == '=') {
      throw UsageError("--fit '" + f + "': an empty list names no parameter (leave --fit out for the model's "
                       "typical set)");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (name_of(fits[j]) == name_of(f)) {
        throw UsageError("--fit '" + fits[j] + "' and --fit '" + f + "' both choose the free parameters of " +
                         name_of(f) + ": give one");
      }
    }
  }
}

/// One model's comparison, filled in by jobs (job_queue.hpp): its fit, then its evidence under the
/// priors and under the priors widened x10, then its posterior band. Each job writes only its own
/// fields, and each sampler has its own seeded random stream: the results do not depend on how many
/// threads run the jobs or in which order they finish.
struct ModelRun {
  std::string spec;
  std::shared_ptr<const sediment::SedimentModel> model;
  inversion::FitParameters parameters;
  std::vector<inversion::SitePrior> site_priors;
  std::vector<inversion::Prior> priors;
  Row row;
};

const inversion::FitOptions kFitOptions{.method = inversion::FitMethod::Global, .profile_likelihood = false};

/// The model, its free parameters and its site priors, before any work: an unusable option stops
/// the comparison before the first fit.
ModelRun prepare(const std::string& spec, const CompareOptions& o) {
  ModelOptions mo = o.shared;
  mo.model = spec;
  for (const std::string& f : o.fits) {
    if (name_of(f) == spec) mo.fit = f.substr(f.find('=') + 1);
  }
  const auto probe = make_model(mo);  // for the names it has
  mo.set_values.erase(std::remove_if(mo.set_values.begin(), mo.set_values.end(),
                                     [&](const std::string& item) { return !has_parameter(*probe, name_of(item)); }),
                      mo.set_values.end());
  ModelRun run;
  run.spec = spec;
  run.model = make_model(mo);
  std::vector<std::string> notes;
  run.parameters = make_parameters(mo, *run.model, ModelUse::Fit, &notes, &run.site_priors);
  return run;
}

/// The fit, then the priors around it (every prior covers the search bounds of the fitted set).
void fit_model(ModelRun& run, const CompareOptions& o, const inversion::ObservationSet& data) {
  std::fprintf(stderr, "sedwave compare: %s: fit ...\n", run.spec.c_str());
  Row& row = run.row;
  row.model = run.model->name();
  row.fit = inversion::fit(data, *run.model, run.parameters, kFitOptions);
  std::vector<std::string> prior_items;
  for (const std::string& item : o.priors) {
    const int i = has_parameter(*run.model, name_of(item)) ? run.parameters.index_of(name_of(item)) : -1;
    if (i >= 0 && run.parameters.spec[i].free) prior_items.push_back(item);
  }
  run.priors = inversion::default_priors(row.fit.fitted);
  inversion::apply_site_priors(row.fit.fitted, run.site_priors, run.priors);
  inversion::apply_priors(row.fit.fitted, prior_items, "command line", run.priors);
  for (int i : row.fit.fitted.free_indices()) {
    const auto& parameter = row.fit.fitted.spec[i];
    row.free += (row.free.empty() ? "" : ",") + parameter.name;
    row.priors.push_back(parameter.name + ": " + run.priors[static_cast<std::size_t>(i)].describe(parameter.unit));
  }
}

/// One evidence run of a fitted model under `priors`; it announces itself and reports its progress
/// on stderr under `label` (two runs of a model go side by side).
inversion::ModelEvidence evidence_of(const ModelRun& run, const inversion::ObservationSet& data,
                                     const std::vector<inversion::Prior>& priors, inversion::EvidenceOptions options,
                                     const char* label) {
  std::fprintf(stderr, "sedwave compare: %s: %s ...\n", run.spec.c_str(), label);
  const std::string spec = run.spec;
  options.progress = [spec, label](const std::string& line) {
    std::fprintf(stderr, "sedwave compare: %s: %s: %s\n", spec.c_str(), label, line.c_str());
  };
  return inversion::model_evidence(data, *run.model, run.row.fit, priors, kFitOptions, options);
}

/// Queues every model's jobs; `threads` run them, and threads beyond the two evidence runs per
/// model share each sampler's evaluations.
void run_all(std::vector<ModelRun>& runs, const CompareOptions& o, const inversion::ObservationSet& data,
             int threads) {
  inversion::EvidenceOptions evidence = o.evidence;
  evidence.threads = std::max(1, threads / (2 * static_cast<int>(runs.size())));
  JobQueue queue;
  for (ModelRun& run : runs) {
    queue.add([&run, &o, &data, evidence](JobQueue& next) {
      fit_model(run, o, data);
      next.add([&run, &data, evidence](JobQueue&) {
        run.row.widened =
            evidence_of(run, data, inversion::widened(run.priors, 10.0), evidence, "evidence, priors widened x10");
      });
      next.add([&run, &data, evidence](JobQueue& after) {
        run.row.evidence = evidence_of(run, data, run.priors, evidence, "evidence");
        after.add([&run, &data](JobQueue&) {
          run.row.band = inversion::predictive_band(run.row.model, *run.model, run.row.fit, run.row.evidence.samples,
                                                    inversion::curve_frequencies(data));
        });
      });
    });
  }
  queue.run(threads);
}

std::vector<int> ranking(const std::vector<Row>& rows, bool widened) {
  std::vector<int> order(rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto& ea = widened ? rows[a].widened : rows[a].evidence;
    const auto& eb = widened ? rows[b].widened : rows[b].evidence;
    return ea.log_evidence > eb.log_evidence;
  });
  return order;
}

void print_table(const std::vector<Row>& rows) {
  const std::vector<int> order = ranking(rows, false), wide = ranking(rows, true);
  const double best = rows[order[0]].evidence.log_evidence;
  std::printf("\n%-4s %-20s %3s %9s %7s %9s %9s %17s %8s %8s %10s %5s\n", "rank", "model", "k", "chi2", "chi2/nu",
              "AIC", "BIC", "ln Z", "dln Z", "p(pred)", "ln Z x10", "rank");
  for (std::size_t r = 0; r < order.size(); ++r) {
    const Row& row = rows[order[r]];
    const auto wide_rank = std::find(wide.begin(), wide.end(), order[r]) - wide.begin() + 1;
    std::printf("%-4zu %-20s %3zu %9.4g %7.3g %9.4g %9.4g %10.2f +- %4.2f %8.2f %8.2g %10.2f %5ld%s\n", r + 1,
                row.model.c_str(), row.fit.fitted.free_indices().size(), row.fit.chi2,
                row.fit.dof > 0 ? row.fit.chi2 / row.fit.dof : NAN, row.fit.aic, row.fit.bic,
                row.evidence.log_evidence, row.evidence.uncertainty, row.evidence.log_evidence - best,
                row.evidence.predictive_p, row.widened.log_evidence, static_cast<long>(wide_rank),
                row.evidence.converged ? "" : "  (NOT CONVERGED)");
  }
  if (rows.size() > 1) {
    const double gap = rows[order[0]].evidence.log_evidence - rows[order[1]].evidence.log_evidence;
    const double noise = std::hypot(rows[order[0]].evidence.uncertainty, rows[order[1]].evidence.uncertainty);
    if (gap < std::max(1.0, 2.0 * noise)) {
      std::printf("the first two differ by %.2f in ln Z (uncertainty %.2f): these data cannot tell them apart\n", gap,
                  noise);
    } else {
      std::printf("%s is preferred over %s by a factor e^%.1f in evidence\n", rows[order[0]].model.c_str(),
                  rows[order[1]].model.c_str(), gap);
    }
  }
}

nlohmann::json report(const std::vector<Row>& rows) {
  nlohmann::json j = nlohmann::json::array();
  for (const Row& row : rows) {
    const auto ev = [](const inversion::ModelEvidence& e) {
      return nlohmann::json{{"log_evidence", e.log_evidence}, {"uncertainty", e.uncertainty},
                            {"predictive_p", e.predictive_p}, {"converged", e.converged},
                            {"advice", e.advice}, {"evaluations", e.evaluations}, {"wall_seconds", e.wall_seconds},
                            {"steps", e.steps}, {"temperatures", e.temperatures},
                            {"max_temperature", e.max_temperature},
                            {"thermodynamic_integration", e.thermodynamic_integration},
                            {"stone_overlap", e.stone_overlap}};
    };
    j.push_back({{"model", row.model}, {"free", row.free}, {"chi2", row.fit.chi2}, {"dof", row.fit.dof},
                 {"aic", row.fit.aic}, {"bic", row.fit.bic}, {"priors", row.priors}, {"evidence", ev(row.evidence)},
                 {"evidence_priors_widened_x10", ev(row.widened)}});
  }
  return j;
}

/// Each model's file of one kind: STEM_<position>_<spec>.csv (the position keeps two specs of one
/// model apart; any character of the spec outside [A-Za-z0-9.-] is made '_').
std::string model_file(const std::string& stem, std::size_t position, const std::string& spec) {
  std::string name = stem + "_" + std::to_string(position + 1) + "_";
  for (char c : spec) name += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
  return name + ".csv";
}

std::vector<OutputPath> output_files(const std::filesystem::path& out, const std::vector<std::string>& models) {
  std::vector<OutputPath> outputs;
  for (const char* name : {"compare.json", "predictive_residuals.csv", "predictive.gp", "predictive.png",
                           "predictive.svg", "corner_best.gp", "corner_best.png", "corner_best.svg",
                           "corner_best_density.dat"}) {
    outputs.push_back({"--out", out / name});
  }
  for (std::size_t i = 0; i < models.size(); ++i) {
    outputs.push_back({"--out", out / model_file("predictive", i, models[i])});
    outputs.push_back({"--out", out / model_file("samples", i, models[i])});
  }
  return outputs;
}

/// Every model's posterior band over the data, as files; returns them for the plot.
std::vector<inversion::BandFile> write_bands(const std::filesystem::path& out, const std::vector<std::string>& specs,
                                             const std::vector<Row>& rows, const inversion::ObservationSet& data) {
  std::vector<inversion::PredictiveBand> bands;
  std::vector<inversion::BandFile> files;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    files.push_back({rows[i].model, model_file("predictive", i, specs[i])});
    inversion::write_predictive_csv(out / files.back().file, rows[i].band, data.water_sound_speed);
    bands.push_back(rows[i].band);
  }
  inversion::write_predictive_residuals_csv(out / "predictive_residuals.csv", rows.front().fit, bands,
                                            data.water_sound_speed);
  std::printf("posterior bands: %s/predictive_*.csv, samples: %s/samples_*.csv\n", out.c_str(), out.c_str());
  return files;
}

/// The bands of every model in one plot (read from the files write_bands wrote).
void plot_bands(const std::filesystem::path& out, const std::vector<inversion::BandFile>& files,
                const std::vector<Row>& rows, const inversion::ObservationSet& data) {
  std::printf("%s\n", inversion::draw_predictive_plot(out, "predictive", "sedwave compare: posterior bands",
                                                      data.water_sound_speed.has_value(), rows.front().fit, files,
                                                      "predictive_residuals.csv")
                          .message.c_str());
}

/// The free parameters' names and units of a row, in the order of its samples' columns.
std::pair<std::vector<std::string>, std::vector<std::string>> sample_columns(const Row& row) {
  std::vector<std::string> names, units;
  for (int i : row.fit.fitted.free_indices()) {
    names.push_back(row.fit.fitted.spec[i].name);
    units.push_back(row.fit.fitted.spec[i].unit);
  }
  return {names, units};
}

/// Each model's posterior draws (the evidence run's beta = 1 ensemble).
void write_samples(const std::filesystem::path& out, const std::vector<std::string>& specs,
                   const std::vector<Row>& rows) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto [names, units] = sample_columns(rows[i]);
    inversion::write_samples_csv(out / model_file("samples", i, specs[i]), rows[i].evidence.samples, names, units);
  }
}

/// The corner plot of the model ranked first (read from its samples file).
void plot_best_corner(const std::filesystem::path& out, const std::vector<std::string>& specs,
                      const std::vector<Row>& rows) {
  const auto best = static_cast<std::size_t>(ranking(rows, false).front());
  const auto [names, units] = sample_columns(rows[best]);
  std::vector<double> best_fit;
  for (int i : rows[best].fit.fitted.free_indices()) best_fit.push_back(rows[best].fit.fitted.spec[i].value);
  const inversion::CornerFiles files{model_file("samples", best, specs[best]), "corner_best",
                                     "posterior of " + rows[best].model + " (ranked first)", best_fit};
  std::printf("%s\n", inversion::draw_corner_plot(out, names, units, files).message.c_str());
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Fit several sediment models to the same observations and rank them by evidence (with chi2, AIC, BIC, "
                 "a posterior-predictive check, and the ranking under priors widened x10); docs/inversion.md");
  cmd->add_option("files", o->files, "observation CSV files (docs/file-formats.md)")->required();
  cmd->add_option("--models", o->models, "comma-separated models (sedwave models)")->required();
  cmd->add_option("--fit", o->fits, "MODEL=a,b,c: a model's free parameters (default: its typical set; repeatable)");
  cmd->add_option("--prior", o->priors, "NAME=KIND:A,B, for every model with NAME free (as invert; repeatable)");
  cmd->add_option("--set", o->shared.set_values, "NAME=VALUE for every model that has NAME (repeatable)");
  cmd->add_option("--site", o->shared.site, "site file (TOML; docs/inversion.md, \"Site files\"): priors for every model")
      ->check(CLI::ExistingFile);
  cmd->add_option("--water-speed", o->water_speed, "water sound speed [m/s] for sound-speed ratios")
      ->check(finite_in(100.0, 10000.0));
  cmd->add_option("--temperatures", o->evidence.temperatures, "tempering ladder length")->capture_default_str()
      ->check(CLI::Range(4, 64));
  cmd->add_option("--steps", o->evidence.steps,
                  "the most ensemble updates per temperature; the run stops once ln Z's standard error is below "
                  "0.1 and the posterior ensemble has converged, the first half burn-in")
      ->capture_default_str()->check(CLI::Range(100, 10000000));
  cmd->add_option("--seed", o->evidence.seed, "seed of the samplers")->capture_default_str();
  add_threads_option(*cmd, o->threads,
                     "threads that run the models' fits and evidence computations side by side");
  cmd->add_option("--out", o->out, "output directory (compare.json, each model's posterior band, the band plot)")
      ->capture_default_str();
  cmd->add_flag("!--no-plot", o->plot, "skip the gnuplot figure");
  return {cmd, [o]() {
    const std::filesystem::path out(o->out);
    std::vector<std::filesystem::path> inputs(o->files.begin(), o->files.end());
    if (!o->shared.site.empty()) inputs.emplace_back(o->shared.site);
    const std::vector<std::string> model_names = split(o->models, ',');
    check_model_list(o->models, model_names);
    check_outputs(output_files(out, model_names), inputs, "compare");
    const inversion::ReadOptions read{o->water_speed, std::nullopt};
    inversion::ObservationSet data;
    for (const std::string& f : o->files) data.append(inversion::read_observation_csv(f, read));
    std::vector<std::shared_ptr<const sediment::SedimentModel>> models;
    for (const std::string& spec : model_names) models.push_back(sediment::make_sediment_model(spec));
    require_known(o->priors, "--prior", models);
    require_known(o->shared.set_values, "--set", models);
    check_fits(o->fits, model_names);
    const io::OutputLock lock(out, "--out");  // after every check: a refused run waits for nothing
    std::vector<ModelRun> runs;
    for (const std::string& spec : model_names) runs.push_back(prepare(spec, *o));
    run_all(runs, *o, data, threads_to_use(o->threads));
    std::vector<Row> rows;
    for (ModelRun& run : runs) rows.push_back(std::move(run.row));
    std::printf("sedwave compare: %zu models, %zu observations; ln Z up to a constant common to all models\n",
                rows.size(), data.observations.size());
    for (const Row& row : rows) {
      std::printf("\n%s (free: %s)\n", row.model.c_str(), row.free.c_str());
      for (const std::string& p : row.priors) std::printf("  prior %s\n", p.c_str());
    }
    print_table(rows);
    {
      io::DeferredCommits outputs;  // a failed run leaves the previous outputs, not part of its own
      io::write_text_atomically(out / "compare.json", [&](std::ostream& s) { s << report(rows).dump(2) << "\n"; });
      std::printf("report: %s/compare.json\n", o->out.c_str());
      const std::vector<inversion::BandFile> band_files = write_bands(out, model_names, rows, data);
      write_samples(out, model_names, rows);
      outputs.commit_all();
      if (o->plot) {
        plot_bands(out, band_files, rows, data);
        plot_best_corner(out, model_names, rows);
      }
    }
    const bool all_converged = std::all_of(rows.begin(), rows.end(), [](const Row& r) {
      return r.evidence.converged && r.widened.converged;
    });
    return all_converged ? kExitOk : kExitIncomplete;
  }};
}

}  // namespace sedwave::app
