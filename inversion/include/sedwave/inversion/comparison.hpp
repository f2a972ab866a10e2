#pragma once
// Sediment models ranked by their evidence, as one library call: each model fitted, then its
// evidence (the probability of the data under the model and its priors, posterior.hpp) under its
// priors and again under them widened tenfold (evidence depends on priors), then the posterior band
// it predicts over the data; beside chi^2, AIC, BIC and a posterior-predictive p-value
// (docs/inversion.md, "Comparing models").
//
//   Site site = read_site_file("site.toml");  // what is known of the seabed (site_file.hpp), or none
//   std::vector<Candidate> candidates;        // each set up by make_candidate (setup.hpp)
//   for (const char* spec : {"biot-stoll", "edfm", "lattice"}) candidates.push_back(make_candidate(spec, site));
//   const Ranking ranking = compare_models(data, candidates, {});
//   ranking.best().model  // the name of the model ranked first
//
// Both evidences come from one importance-sampling pass around the fit where its diagnostics
// allow, from adaptive cubature or parallel tempering where they do not (posterior.hpp,
// importance_sampled_evidence). A model whose ln Z cannot reach another's (its best fit's ln L lies
// kDecisiveGap below it) gets that bound instead of tempering, labelled as a bound (kUpperBoundMethod).
// The work runs as jobs on `threads` threads; each job writes only its own results and each
// sampler has its own seeded random stream, so the ranking is the same, bit for bit, for any
// thread count.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/predictive.hpp"
#include "sedwave/inversion/priors.hpp"
#include "sedwave/inversion/setup.hpp"

namespace sedwave::inversion {

struct ComparisonOptions {
  EvidenceOptions evidence;  ///< its threads are set from `threads` below
  int threads = 1;  ///< jobs side by side; threads beyond two per model share each sampler's evaluations
  /// Given "LABEL: what" as each stage starts, and each sampler's progress lines; null: silent. Called
  /// from the threads that run the jobs.
  std::function<void(const std::string&)> progress = nullptr;
};

/// How much wider the priors of the second ranking are.
inline constexpr double kPriorWidening = 10.0;

/// ModelEvidence::method of a column that states an upper bound on ln Z (the best fit's ln L) in
/// place of an estimate: only where it lies far below another model's ln Z (docs/inversion.md).
inline constexpr const char* kUpperBoundMethod = "upper bound";
/// How far (in ln Z) below the best ln Z less 3 of its sd, among those importance sampling or
/// adaptive cubature computed, the bound must lie to be stated.
inline constexpr double kDecisiveGap = 100.0;

struct ComparedModel {
  std::string label;                ///< the candidate's
  std::string model;                ///< the model's name
  std::string free;                 ///< its free parameters, comma-separated
  FitResult fit;                    ///< global search and polish, without likelihood profiles
  std::vector<std::string> priors;  ///< one line per free parameter: "NAME: " + Prior::describe
  ModelEvidence evidence;           ///< under the candidate's priors
  ModelEvidence widened;            ///< under them widened kPriorWidening times (posterior.hpp, widened)
  PredictiveBand band;              ///< over the data's frequencies, from the evidence run's posterior
  long fit_evaluations = 0;         ///< the model's evaluations at a parameter point during the fit
  /// Every evaluation the comparison made for this model: the fit's, the evidence's under both sets
  /// of priors (importance sampling's once, as both share them; parallel tempering's where it ran)
  /// and the band's posterior draws.
  long evaluations = 0;
};

struct Ranking {
  std::vector<ComparedModel> models;  ///< in the candidates' order
  std::vector<int> order;             ///< indices into models, largest evidence first
  std::vector<int> order_widened;     ///< the same under the widened priors
  [[nodiscard]] const ComparedModel& best() const { return models[static_cast<std::size_t>(order.front())]; }
  /// Every evidence run, under both sets of priors, reached its target.
  [[nodiscard]] bool converged() const;
};

/// Fits and ranks the candidates (at least one). Throws std::invalid_argument for no candidates or
/// priors that do not fit their parameters, and whatever a fit or sampler throws.
[[nodiscard]] Ranking compare_models(const ObservationSet& data, const std::vector<Candidate>& candidates,
                                     const ComparisonOptions& options = {});

/// The ranking as JSON (compare.json): one entry per model in the candidates' order, with its fit's
/// chi^2, AIC, BIC, its priors and both evidence runs.
[[nodiscard]] nlohmann::json ranking_report(const Ranking& ranking);

/// The name of a model's file of one kind: STEM_<position + 1>_<label>.csv (the position keeps two
/// labels of one model apart; any character of the label outside [A-Za-z0-9.-] is made '_').
[[nodiscard]] std::string ranking_file(const std::string& stem, std::size_t position, const std::string& label);

/// Each model's posterior band (ranking_file "predictive") and posterior draws ("samples") and
/// every model's residuals from its band median (predictive_residuals.csv), in `dir`.
void write_ranking_files(const std::filesystem::path& dir, const Ranking& ranking, const ObservationSet& data);

/// The free parameters' names and units of a model, in the order of its samples' columns.
[[nodiscard]] std::pair<std::vector<std::string>, std::vector<std::string>> sample_columns(const ComparedModel& m);

}  // namespace sedwave::inversion
