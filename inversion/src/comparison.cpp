#include "sedwave/inversion/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cctype>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "fit_problem.hpp"
#include "job_queue.hpp"
#include "sedwave/inversion/report.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::inversion {
namespace {

/// A comparison's fits: global search and polish; no likelihood profiles, since the evidence
/// samples the whole posterior anyway.
const FitOptions kFitOptions{.method = FitMethod::Global, .profile_likelihood = false};

void report(const ComparisonOptions& options, const std::string& line) {
  if (options.progress) options.progress(line);
}

/// The fit, and what the report says of the free parameters and their priors.
void fit_candidate(const Candidate& candidate, ComparedModel& compared, const ObservationSet& data,
                   const ComparisonOptions& options) {
  report(options, candidate.label + ": fit ...");
  compared.label = candidate.label;
  compared.model = candidate.model->name();
  const long before = detail::evaluations_on_this_thread();
  compared.fit = fit(data, *candidate.model, candidate.parameters, kFitOptions);
  compared.fit_evaluations = detail::evaluations_on_this_thread() - before;
  for (int i : compared.fit.fitted.free_indices()) {
    const ParameterSpec& parameter = compared.fit.fitted.spec[static_cast<std::size_t>(i)];
    compared.free += (compared.free.empty() ? "" : ",") + parameter.name;
    compared.priors.push_back(parameter.name + ": " + candidate.priors[static_cast<std::size_t>(i)].describe(parameter.unit));
  }
}

/// One evidence run of a fitted model under `priors`; it announces itself and reports its progress
/// under `stage` (two runs of a model go side by side).
ModelEvidence evidence_of(const Candidate& candidate, const ComparedModel& compared, const ObservationSet& data,
                          const std::vector<Prior>& priors, EvidenceOptions evidence, const ComparisonOptions& options,
                          const std::string& stage) {
  const std::string label = candidate.label + ": " + stage;
  report(options, label + " ...");
  if (options.progress) {
    evidence.progress = [&options, label](const std::string& line) { options.progress(label + ": " + line); };
  }
  return model_evidence(data, *candidate.model, compared.fit, priors, kFitOptions, evidence);
}

/// Whether a column still needs parallel tempering: it was not computed by importance sampling or
/// adaptive cubature, or their diagnostics refused it (a column they served keeps importance
/// sampling's reason for the cubature).
bool needs_tempering(const ModelEvidence& e, const EvidenceOptions& options) {
  return options.method == EvidenceMethod::Tempering ||
         (!e.fallback_reason.empty() && e.method != kCubatureMethod);  // Cubature: where it failed
}

/// Tempering's result for a column that importance sampling refused, saying why.
ModelEvidence fall_back(const ModelEvidence& refused, ModelEvidence tempered) {
  tempered.fallback_reason = refused.fallback_reason;
  return tempered;
}

/// Every evaluation made for a model: the fit's, importance sampling's and adaptive cubature's
/// once (both columns share them: `shared`), tempering's per column, the band's draws.
long model_evaluations(const ComparedModel& m, long shared) {
  long total = m.fit_evaluations + shared + m.band.draws;
  for (const ModelEvidence* e : {&m.evidence, &m.widened}) {
    if (e->method == kTemperingMethod) total += e->evaluations;
  }
  return total;
}

/// The columns that importance sampling refused, by adaptive cubature in one pass where the model
/// has few enough free parameters (each column still refused keeps both reasons); the cubature's
/// evaluations are added to `shared`.
void integrate_refused(const Candidate& candidate, ComparedModel& compared, const ObservationSet& data,
                       const std::vector<Prior>& wide, const EvidenceOptions& evidence, const ComparisonOptions& options) {
  std::vector<ModelEvidence*> refused;
  std::vector<std::vector<Prior>> sets;
  std::vector<Eigen::MatrixXd> hints;
  for (auto [column, priors] : {std::pair{&compared.evidence, &candidate.priors}, std::pair{&compared.widened, &wide}}) {
    if (column->fallback_reason.empty()) continue;
    refused.push_back(column);
    sets.push_back(*priors);
    hints.push_back(column->samples);
  }
  if (refused.empty() || std::ssize(compared.fit.fitted.free_indices()) > evidence.cubature_max_parameters) return;
  report(options, candidate.label + ": evidence by adaptive cubature ...");
  const std::vector<ModelEvidence> integrated =
      cubature_integrated_evidence(data, *candidate.model, compared.fit, sets, kFitOptions, evidence, hints);
  compared.evaluations += integrated.front().evaluations;
  for (std::size_t c = 0; c < refused.size(); ++c) {
    const std::string reason = refused[c]->fallback_reason;
    if (integrated[c].fallback_reason.empty()) {
      *refused[c] = integrated[c];
      refused[c]->fallback_reason = reason;
    } else {
      refused[c]->fallback_reason = reason + "; " + integrated[c].fallback_reason;
      refused[c]->highest_drawn_log_likelihood = integrated[c].highest_drawn_log_likelihood;
    }
  }
}

/// The posterior band of a model from its first column's draws.
JobQueue::Job band_of(const Candidate& candidate, ComparedModel& compared, const ObservationSet& data) {
  return [&candidate, &compared, &data](JobQueue&) {
    compared.band = predictive_band(compared.model, *candidate.model, compared.fit, compared.evidence.samples,
                                    curve_frequencies(data));
  };
}

std::string formatted_bound(double bound, double reference) {
  char text[512];
  std::snprintf(text, sizeof text,
                "ln Z <= %.2f (the best fit's ln L: the prior integrates to 1), at least %.0f below the best "
                "model's ln Z %.2f less 3 sd: no value below the bound changes the ranking, so tempering was not "
                "run; the band and the samples are the best fit alone",
                bound, reference - bound, reference);
  return text;
}

/// The largest ln Z - 3 sd among the columns the fast paths served (-inf where none).
double best_fast(const std::vector<ComparedModel>& models, bool widened) {
  double best = -std::numeric_limits<double>::infinity();
  for (const ComparedModel& m : models) {
    const ModelEvidence& e = widened ? m.widened : m.evidence;
    if (e.converged && e.method != kTemperingMethod) best = std::max(best, e.log_evidence - 3.0 * e.uncertainty);
  }
  return best;
}

/// Where ln Z needs no tempering because another model's is far above it: ln Z <= ln L_max (the
/// prior integrates to 1 and L <= L_max everywhere, L_max the global search's best fit), and where
/// that bound lies kDecisiveGap below the best ln Z that importance sampling or the cubature
/// computed for the same column (less 3 of its standard errors), no value of this ln Z could change
/// the ranking. The column then states the bound, labelled as such, not an estimate.
/// The bound in place of tempering where it decides the ranking; false where tempering must run:
/// no reference far enough above, no cubature's draws (more than its free parameters), or one of
/// them above the best fit (then the fit is not the global maximum, and no bound). The band is the
/// best fit's curve alone (one draw): there is no posterior to draw from.
bool upper_bounded(ModelEvidence& e, const ComparedModel& m, double reference) {
  const double bound = -0.5 * m.fit.chi2;
  if (!(bound < reference - kDecisiveGap) || !std::isfinite(e.highest_drawn_log_likelihood)) return false;
  if (!(e.highest_drawn_log_likelihood <= bound + 1e-9 * std::abs(bound))) return false;
  const std::vector<int> free = m.fit.fitted.free_indices();
  e.samples.resize(1, std::ssize(free));
  for (std::size_t j = 0; j < free.size(); ++j) {
    e.samples(0, static_cast<Eigen::Index>(j)) = m.fit.fitted.spec[static_cast<std::size_t>(free[j])].value;
  }
  e.method = kUpperBoundMethod;
  e.log_evidence = bound;
  e.uncertainty = 0.0;
  e.converged = false;
  e.advice = formatted_bound(bound, reference);
  return true;
}

std::vector<int> order_by_evidence(const std::vector<ComparedModel>& models, bool widened) {
  std::vector<int> order(models.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  // Largest first; a NaN (a failed run) last, and ties in the candidates' order.
  const auto key = [&](int i) {
    const ComparedModel& m = models[static_cast<std::size_t>(i)];
    const double z = (widened ? m.widened : m.evidence).log_evidence;
    return std::isnan(z) ? -std::numeric_limits<double>::infinity() : z;
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) > key(b); });
  return order;
}


std::string widened_stage() {
  char text[64];
  std::snprintf(text, sizeof text, "evidence, priors widened x%g", kPriorWidening);
  return text;
}

}  // namespace

std::pair<std::vector<std::string>, std::vector<std::string>> sample_columns(const ComparedModel& m) {
  std::vector<std::string> names, units;
  for (int i : m.fit.fitted.free_indices()) {
    names.push_back(m.fit.fitted.spec[static_cast<std::size_t>(i)].name);
    units.push_back(m.fit.fitted.spec[static_cast<std::size_t>(i)].unit);
  }
  return {names, units};
}

bool Ranking::converged() const {
  // A bound decides its model's rank (compare_models states it only where it lies far below another
  // model's converged ln Z).
  const auto decided = [](const ModelEvidence& e) { return e.converged || e.method == kUpperBoundMethod; };
  return std::all_of(models.begin(), models.end(),
                     [&](const ComparedModel& m) { return decided(m.evidence) && decided(m.widened); });
}

Ranking compare_models(const ObservationSet& data, const std::vector<Candidate>& candidates,
                       const ComparisonOptions& options) {
  if (candidates.empty()) throw std::invalid_argument("compare_models: no models to compare");
  for (const Candidate& c : candidates) {
    c.parameters.require_parameters_of(*c.model);
    if (c.priors.size() != c.parameters.spec.size()) {
      throw std::invalid_argument("compare_models: " + c.label + ": one prior per parameter expected");
    }
  }
  Ranking ranking;
  ranking.models.resize(candidates.size());
  EvidenceOptions evidence = options.evidence;
  evidence.threads = std::max(1, options.threads / (2 * static_cast<int>(candidates.size())));
  // Per model: its fit, then both evidences by importance sampling where it applies, by adaptive
  // cubature (both in one pass) where it does not and the model has few free parameters; once every
  // model is there, parallel tempering for each column neither serves (the two side by side) unless
  // the bound ln Z <= ln L_max decides its rank; then the band from the first.
  JobQueue queue;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& candidate = candidates[i];
    ComparedModel& compared = ranking.models[i];
    queue.add([&candidate, &compared, &data, &options, evidence](JobQueue& next) {
      fit_candidate(candidate, compared, data, options);
      next.add([&candidate, &compared, &data, &options, evidence](JobQueue& after) {
        const std::vector<Prior> wide = widened(candidate.priors, kPriorWidening);
        if (evidence.method == EvidenceMethod::Automatic) {
          report(options, candidate.label + ": evidence by importance sampling ...");
          const std::vector<ModelEvidence> fast =
              importance_sampled_evidence(data, *candidate.model, compared.fit, {candidate.priors, wide}, kFitOptions,
                                          evidence);
          compared.evidence = fast[0];
          compared.widened = fast[1];
          compared.evaluations = std::max(fast[0].evaluations, fast[1].evaluations);
          integrate_refused(candidate, compared, data, wide, evidence, options);
        } else if (evidence.method == EvidenceMethod::Cubature) {
          compared.evidence.fallback_reason = compared.widened.fallback_reason = "adaptive cubature asked for";
          integrate_refused(candidate, compared, data, wide, evidence, options);
        }
        if (!needs_tempering(compared.evidence, evidence)) after.add(band_of(candidate, compared, data));
      });
    });
  }
  queue.run(options.threads);
  // Then tempering for the columns neither fast path served, unless a bound decides their rank.
  // This waits for every model's fast paths, so that what decides is the same for any thread count.
  EvidenceOptions tempering = evidence;
  tempering.method = EvidenceMethod::Tempering;
  const double reference[2] = {best_fast(ranking.models, false), best_fast(ranking.models, true)};
  JobQueue fallbacks;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& candidate = candidates[i];
    ComparedModel& compared = ranking.models[i];
    if (needs_tempering(compared.widened, evidence) && !upper_bounded(compared.widened, compared, reference[1])) {
      fallbacks.add([&candidate, &compared, &data, &options, tempering](JobQueue&) {
        const std::vector<Prior> wide = widened(candidate.priors, kPriorWidening);
        compared.widened = fall_back(compared.widened, evidence_of(candidate, compared, data, wide, tempering,
                                                                   options, widened_stage()));
      });
    }
    if (!needs_tempering(compared.evidence, evidence)) continue;
    if (upper_bounded(compared.evidence, compared, reference[0])) {
      fallbacks.add(band_of(candidate, compared, data));
      continue;
    }
    fallbacks.add([&candidate, &compared, &data, &options, tempering](JobQueue& then) {
      compared.evidence = fall_back(compared.evidence, evidence_of(candidate, compared, data, candidate.priors,
                                                                   tempering, options, "evidence"));
      then.add(band_of(candidate, compared, data));
    });
  }
  fallbacks.run(options.threads);
  for (ComparedModel& m : ranking.models) m.evaluations = model_evaluations(m, m.evaluations);
  ranking.order = order_by_evidence(ranking.models, false);
  ranking.order_widened = order_by_evidence(ranking.models, true);
  return ranking;
}

nlohmann::json ranking_report(const Ranking& ranking) {
  const auto ev = [](const ModelEvidence& e) {
    return nlohmann::json{{"method", e.method}, {"fallback_reason", e.fallback_reason},
                          {"pareto_k", e.pareto_k}, {"effective_draws", e.effective_draws},
                          {"log_evidence", e.log_evidence}, {"uncertainty", e.uncertainty},
                          {"predictive_p", e.predictive_p}, {"converged", e.converged},
                          {"advice", e.advice}, {"evaluations", e.evaluations}, {"wall_seconds", e.wall_seconds},
                          {"steps", e.steps}, {"temperatures", e.temperatures},
                          {"max_temperature", e.max_temperature},
                          {"thermodynamic_integration", e.thermodynamic_integration},
                          {"stone_overlap", e.stone_overlap}, {"swap_acceptance", e.swap_acceptance}};
  };
  nlohmann::json j = nlohmann::json::array();
  for (const ComparedModel& m : ranking.models) {
    j.push_back({{"model", m.model}, {"free", m.free}, {"chi2", m.fit.chi2}, {"dof", m.fit.dof},
                 {"aic", m.fit.aic}, {"bic", m.fit.bic}, {"priors", m.priors},
                 {"evaluations", m.evaluations}, {"fit_evaluations", m.fit_evaluations},
                 {"band_draws", m.band.draws}, {"evidence", ev(m.evidence)},
                 {"evidence_priors_widened_x10", ev(m.widened)}});
  }
  return j;
}

std::string ranking_file(const std::string& stem, std::size_t position, const std::string& label) {
  std::string name = stem + "_" + std::to_string(position + 1) + "_";
  for (char c : label) name += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
  return name + ".csv";
}

void write_ranking_files(const std::filesystem::path& dir, const Ranking& ranking, const ObservationSet& data) {
  std::vector<PredictiveBand> bands;
  for (std::size_t i = 0; i < ranking.models.size(); ++i) {
    const ComparedModel& m = ranking.models[i];
    write_predictive_csv(dir / ranking_file("predictive", i, m.label), m.band, data.water_sound_speed);
    bands.push_back(m.band);
  }
  write_predictive_residuals_csv(dir / "predictive_residuals.csv", ranking.models.front().fit, bands,
                                 data.water_sound_speed);
  for (std::size_t i = 0; i < ranking.models.size(); ++i) {
    const auto [names, units] = sample_columns(ranking.models[i]);
    write_samples_csv(dir / ranking_file("samples", i, ranking.models[i].label), ranking.models[i].evidence.samples,
                      names, units);
  }
}

}  // namespace sedwave::inversion
