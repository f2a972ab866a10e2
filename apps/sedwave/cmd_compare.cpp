// `sedwave compare`: several sediment models fitted to the same data and ranked by their evidence
// (the probability of the data under each model and its priors), beside chi^2, AIC and BIC, with a
// posterior-predictive check; and the ranking again with every prior widened tenfold, since
// evidence depends on priors (docs/inversion.md, "Comparing models"). The work is the library's
// compare_models (sedwave/inversion/comparison.hpp); this file reads the options and prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "model_options.hpp"
#include "option_checks.hpp"
#include "output_paths.hpp"
#include "sedwave/inversion/comparison.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/plot/plot.hpp"
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

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, by);) parts.push_back(part);
  return parts;
}

std::string name_of(const std::string& item) { return item.substr(0, item.find('=')); }

/// Every name a shared option uses must belong to at least one of the models (a typo is refused).
void require_known(const std::vector<std::string>& items, const char* option,
                   const std::vector<std::shared_ptr<const sediment::SedimentModel>>& models) {
  for (const std::string& item : items) {
    const std::string name = name_of(item);
    const bool known = std::any_of(models.begin(), models.end(), [&](const auto& m) { return m->has_parameter(name); });
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

/// A model with its free parameters, values and priors (site file, then --prior), before any work:
/// an unusable option stops the comparison before the first fit. The shared settings apply to every
/// model that has their parameter.
inversion::Candidate prepare(const std::string& spec, const CompareOptions& o) {
  inversion::ModelSetup setup = setup_of(o.shared);
  setup.model = spec;
  for (const std::string& f : o.fits) {
    if (name_of(f) != spec) continue;
    setup.free = f.substr(f.find('=') + 1);
    setup.free_origin = "--fit '" + f + "' (the parameters of " + spec + ")";
  }
  setup.priors = o.priors;
  setup.shared = true;
  return candidate_of(setup);
}

/// "IS", "AC" or "PT": what gave an evidence.
std::string method_code(const inversion::ModelEvidence& e) {
  if (e.method == inversion::kImportanceSamplingMethod) return "IS";
  if (e.method == inversion::kUpperBoundMethod) return "UB";
  return e.method == inversion::kCubatureMethod ? "AC" : "PT";
}

void print_table(const inversion::Ranking& ranking) {
  const std::vector<inversion::ComparedModel>& rows = ranking.models;
  const std::vector<int>& order = ranking.order;
  const std::vector<int>& wide = ranking.order_widened;
  const double best = ranking.best().evidence.log_evidence;
  int name_width = 20;  // wider for a long name (a layered seabed's)
  for (const inversion::ComparedModel& row : rows) name_width = std::max(name_width, static_cast<int>(row.model.size()));
  std::printf("\n%-4s %-*s %3s %9s %7s %9s %9s %17s %8s %8s %10s %5s %7s %8s\n", "rank", name_width, "model", "k",
              "chi2", "chi2/nu", "AIC", "BIC", "ln Z", "dln Z", "p(pred)", "ln Z x10", "rank", "method", "evals");
  for (std::size_t r = 0; r < order.size(); ++r) {
    const inversion::ComparedModel& row = rows[static_cast<std::size_t>(order[r])];
    const auto wide_rank = std::find(wide.begin(), wide.end(), order[r]) - wide.begin() + 1;
    const std::string method = method_code(row.evidence) + "/" + method_code(row.widened);
    // A bound is printed as one ("<= value"), never as an estimate with an error.
    char ln_z[400], bound[360];
    if (row.evidence.method == inversion::kUpperBoundMethod) {
      std::snprintf(bound, sizeof bound, "<= %.2f", row.evidence.log_evidence);
      std::snprintf(ln_z, sizeof ln_z, "%18s", bound);
    } else {
      std::snprintf(ln_z, sizeof ln_z, "%10.2f +- %4.2f", row.evidence.log_evidence, row.evidence.uncertainty);
    }
    std::printf("%-4zu %-*s %3zu %9.4g %7.3g %9.4g %9.4g %s %8.2f %8.2g %10.2f %5ld %7s %8ld%s\n",
                r + 1, name_width, row.model.c_str(), row.fit.fitted.free_indices().size(), row.fit.chi2,
                row.fit.dof > 0 ? row.fit.chi2 / row.fit.dof : NAN, row.fit.aic, row.fit.bic, ln_z,
                row.evidence.log_evidence - best,
                row.evidence.predictive_p, row.widened.log_evidence, static_cast<long>(wide_rank), method.c_str(),
                row.evaluations,
                row.evidence.converged                                   ? ""
                : row.evidence.method == inversion::kUpperBoundMethod ? "  (ln Z: an upper bound)"
                                                                        : "  (NOT CONVERGED)");
  }
  std::printf("method (ln Z / ln Z x10): IS importance sampling around the fit, AC adaptive cubature over the priors' "
              "support, PT parallel tempering; evals: the model's evaluations in all (fit, evidence, band)\n");
  const auto bounded = [](const inversion::ComparedModel& m) {
    return m.evidence.method == inversion::kUpperBoundMethod || m.widened.method == inversion::kUpperBoundMethod;
  };
  if (std::any_of(rows.begin(), rows.end(), bounded)) {
    std::printf("UB: an upper bound, ln Z <= the best fit's ln L (no estimate), stated where it lies over %.0f below "
                "the best ln Z, so that no value below it changes the ranking\n", inversion::kDecisiveGap);
  }
  for (std::size_t r = 0; r < order.size(); ++r) {
    const inversion::ComparedModel& row = rows[static_cast<std::size_t>(order[r])];
    for (const auto& [column, e] : {std::pair{"ln Z", &row.evidence}, std::pair{"ln Z x10", &row.widened}}) {
      if (!e->fallback_reason.empty()) {
        std::printf("%s, %s by %s: %s\n", row.model.c_str(), column, e->method.c_str(), e->fallback_reason.c_str());
      }
    }
  }
  if (rows.size() > 1) {
    const inversion::ComparedModel& first = rows[static_cast<std::size_t>(order[0])];
    const inversion::ComparedModel& second = rows[static_cast<std::size_t>(order[1])];
    const double gap = first.evidence.log_evidence - second.evidence.log_evidence;
    const double noise = std::hypot(first.evidence.uncertainty, second.evidence.uncertainty);
    if (gap < std::max(1.0, 2.0 * noise)) {
      std::printf("the first two differ by %.2f in ln Z (uncertainty %.2f): these data cannot tell them apart\n", gap,
                  noise);
    } else {
      std::printf("%s is preferred over %s by a factor %se^%.1f in evidence\n", first.model.c_str(),
                  second.model.c_str(), second.evidence.method == inversion::kUpperBoundMethod ? "of at least " : "",
                  gap);
    }
  }
}

std::vector<OutputPath> output_files(const std::filesystem::path& out, const std::vector<std::string>& models) {
  std::vector<OutputPath> outputs;
  for (const char* name : {"compare.json", "predictive_residuals.csv", "predictive.gp", "predictive.png",
                           "predictive.svg", "corner_best.gp", "corner_best.png", "corner_best.svg",
                           "corner_best_density.dat"}) {
    outputs.push_back({"--out", out / name});
  }
  for (std::size_t i = 0; i < models.size(); ++i) {
    outputs.push_back({"--out", out / inversion::ranking_file("predictive", i, models[i])});
    outputs.push_back({"--out", out / inversion::ranking_file("samples", i, models[i])});
  }
  return outputs;
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
      ->check(finite_in(inversion::kLowestDeclaredSpeed, inversion::kHighestDeclaredSpeed));
  cmd->add_option("--evidence", o->evidence.method,
                  "auto: importance sampling around each fit where its diagnostics allow, parallel tempering "
                  "elsewhere; tempering: parallel tempering always")
      ->transform(CLI::CheckedTransformer(std::map<std::string, inversion::EvidenceMethod>{
          {"auto", inversion::EvidenceMethod::Automatic}, {"tempering", inversion::EvidenceMethod::Tempering}}))
      ->default_str("auto");
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
    std::vector<inversion::Candidate> candidates;
    for (const std::string& spec : model_names) candidates.push_back(prepare(spec, *o));
    const inversion::ComparisonOptions options{o->evidence, threads_to_use(o->threads), [](const std::string& line) {
                                                 std::fprintf(stderr, "sedwave compare: %s\n", line.c_str());
                                               }};
    const inversion::Ranking ranking = inversion::compare_models(data, candidates, options);
    std::printf("sedwave compare: %zu models, %zu observations; ln Z up to a constant common to all models\n",
                ranking.models.size(), data.observations.size());
    for (const inversion::ComparedModel& m : ranking.models) {
      std::printf("\n%s (free: %s)\n", m.model.c_str(), m.free.c_str());
      for (const std::string& p : m.priors) std::printf("  prior %s\n", p.c_str());
    }
    print_table(ranking);
    {
      io::DeferredCommits outputs;  // a failed run leaves the previous outputs, not part of its own
      io::write_text_atomically(out / "compare.json",
                                [&](std::ostream& s) { s << inversion::ranking_report(ranking).dump(2) << "\n"; });
      std::printf("report: %s/compare.json\n", o->out.c_str());
      inversion::write_ranking_files(out, ranking, data);
      std::printf("posterior bands: %s/predictive_*.csv, samples: %s/samples_*.csv\n", out.c_str(), out.c_str());
      outputs.commit_all();
      if (o->plot) {
        for (const std::string& message : plot::draw_ranking_plots(out, ranking, data)) {
          std::printf("%s\n", message.c_str());
        }
      }
    }
    return ranking.converged() ? kExitOk : kExitIncomplete;
  }};
}

}  // namespace sedwave::app
