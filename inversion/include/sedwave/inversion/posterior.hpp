#pragma once
// The Bayesian answer: the posterior distribution of a model's free parameters given the data and
// the priors (priors.hpp), sampled by the affine-invariant ensemble sampler (sampling/ensemble.hpp)
// from walkers started around the best fit. The likelihood is the fit's: exp(-chi^2/2) with the
// same whitened residuals (residuals.hpp), so a posterior and a fit answer the same question.
//
// Reported per free parameter and per derived quantity (c0, tau, f*, gamma_hat, kappa/kappa_Hertz where
// they mean something): the posterior median, the 68 % and 95 % central credible intervals, and the
// sampler's split-R-hat and effective sample size; plus the acceptance, a convergence verdict with
// advice, and whether the prior rather than the data made each interval.
#include <Eigen/Dense>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/priors.hpp"
#include "sedwave/sampling/cubature.hpp"
#include "sedwave/sampling/importance.hpp"
#include "sedwave/sampling/tempering.hpp"

namespace sedwave::inversion {

struct PosteriorOptions {
  int walkers = 0;        ///< 0: max(4 x free parameters, 16), even
  /// The cap on ensemble updates per walker, burn-in included. The run stops earlier, once
  /// converged: every check_every updates the kept half is diagnosed, and the run ends when every
  /// quantity has kept steps >= 50 autocorrelation times, ESS >= 400 and walkers that agree (R-hat
  /// < 1.05); the first half of the updates run is burn-in. "NOT CONVERGED" only at the cap. The
  /// cap leaves room for posteriors along ridges bounded only by the priors, whose tau reaches
  /// ~700 updates (bench_posterior_defaults): 50 tau kept then needs ~70000 updates.
  int steps = 100000;
  int burn_in = -1;       ///< -1: the first half; another value needs check_every = 0
  unsigned seed = 20090501;
  int threads = 1;        ///< share the model evaluations; the samples do not depend on it
  int check_every = 250;  ///< 0: run exactly `steps` updates
  /// Parallel tempering (sampling/tempering.hpp): rungs of the ladder from beta = 1, as the
  /// evidence's (EvidenceOptions), with beta = 0 added. The posterior is the beta = 1 rung's, and the
  /// run stops once that rung has converged and every rung has mixed (kept steps >= 50 tau of each
  /// rung's parameters and ln L), and not before 2000 updates. -1 (auto): kAutoTemperatures rungs
  /// where a free parameter with a flat prior (uniform or log-uniform, the default) is left open by
  /// the data and the other priors together (its sd in ln in the linearised posterior at the best
  /// fit above FitOptions::determined_log_sigma: what the fit calls NOT DETERMINED, with the
  /// priors' information added), else 0; 0: one ensemble.
  /// There the posterior can reach along a ridge or plateau to the search bounds, and an ensemble
  /// started at the best fit can converge on the part of it that it has found and stop short of the
  /// rest; the hot rungs, which see the whole prior, hand the rest down (bench_posterior_defaults:
  /// docs/sampling.md). With 8 rungs instead of 16 the swaps were too weak: one bounded-ridge set of
  /// that benchmark stopped short again.
  int temperatures = -1;
  static constexpr int kAutoTemperatures = 16;
  /// Given a progress line (steps run, autocorrelation time, estimated time left) about every 2 s
  /// once the run has lasted 2 s; null: silent.
  std::function<void(const std::string&)> progress = nullptr;
};

struct PosteriorQuantity {
  std::string name;
  std::string unit;
  double median = 0.0;
  double lower_68 = 0.0, upper_68 = 0.0;  ///< central credible interval [unit]
  double lower_95 = 0.0, upper_95 = 0.0;
  double split_rhat = 0.0;
  double effective_samples = 0.0;
  /// The prior, not the data, made this interval: the prior supplies more than half of the
  /// posterior precision behind the quantity's spread (prior_share > 0.5). Judged two ways, the
  /// larger share counting: over the whole posterior against the data's information at its central
  /// draw, so that a ridge through several parameters (e.g. kappa d gamma unseen), which no single
  /// marginal shows, is flagged; and by the marginal's width against the prior's, (w_posterior /
  /// w_prior)^2 of the central 95 % intervals in the prior's own coordinate, so that a curved ridge,
  /// which the information at one draw misses, is flagged too.
  bool prior_dominated = false;
  double prior_share = 0.0;  ///< the prior's share, 0 (the data alone) .. 1 (the prior alone)
};

struct PosteriorResult {
  std::vector<PosteriorQuantity> parameters;    ///< the free ones
  std::vector<PosteriorQuantity> derived;       ///< the model's derived quantities
  std::vector<std::string> priors;              ///< one line per free parameter (Prior::describe)
  Eigen::MatrixXd samples;                      ///< pooled kept draws x free parameters, values [unit]
  std::vector<std::string> sample_names;
  std::vector<std::string> sample_units;
  Eigen::MatrixXd correlation;                  ///< of the free ln-parameters
  double acceptance = 0.0;
  bool converged = false;
  std::string advice;                           ///< what to change when not converged
  int walkers = 0, steps = 0, evaluations = 0;  ///< steps: updates run, burn-in (the first half) included
  int steps_cap = 0;                             ///< the most the run was allowed
  int temperatures = 0;                          ///< rungs of a tempered run, beta = 0 included; 0: one ensemble
  double wall_seconds = 0.0;
};

/// Samples the posterior of `best.fitted`'s free parameters (walkers started in a small ball around
/// the best fit, scaled by its covariance where determined and by the prior elsewhere). Throws
/// std::invalid_argument for priors that do not cover the best fit or a sampler option it refuses.
[[nodiscard]] PosteriorResult sample_posterior(const ObservationSet& data, const sediment::SedimentModel& model,
                                               const FitResult& best, const std::vector<Prior>& priors,
                                               const FitOptions& fit_options, const PosteriorOptions& options);

/// How the evidence is computed. Automatic: importance sampling around the best fit
/// (sampling/importance.hpp) where its own diagnostics say it applies; elsewhere adaptive cubature
/// over the priors' support (sampling/cubature.hpp) for up to EvidenceOptions::cubature_max_parameters
/// free parameters, parallel tempering beyond that or where the cubature does not converge
/// (docs/sampling.md, "The evidence from the fit"); Cubature: adaptive cubature first (parallel
/// tempering where it fails; e.g. to check the cubature on every posterior); Tempering: parallel
/// tempering always.
enum class EvidenceMethod { Automatic, Cubature, Tempering };

/// The options of parallel tempering over a ladder of inverse temperatures from 1,
/// evenly spaced in ln beta down to 1/max_temperature, and beta = 0 (the prior, sampled by
/// independent draws) (sampling/tempering.hpp); then stepping stones. Hot temperatures start from
/// prior draws, cold ones around the best fit. The run length adapts: every check_every steps the
/// evidence's standard error and the beta = 1 ensemble are checked, and the run ends once the error
/// is at most target_uncertainty and the posterior ensemble has converged, or at `steps`.
struct EvidenceOptions {
  EvidenceMethod method = EvidenceMethod::Automatic;
  /// The importance sampler's draws and target (its seed and threads are set from those below).
  sampling::ImportanceOptions importance = {};
  /// Equally weighted posterior draws resampled from importance-sampled ones (for bands and plots).
  int posterior_draws = 4000;
  /// Where importance sampling is refused, models with at most this many free parameters are
  /// integrated by adaptive cubature (cubature_integrated_evidence), others by parallel tempering.
  int cubature_max_parameters = 3;
  sampling::CubatureOptions cubature = {};  ///< its threads are set from `threads` below
  /// Draws from the cubature's first map, whose weighted draws place the second; and from the
  /// second, importance-weighted, behind its posterior draws and cross-check.
  int cubature_pilot_draws = 2000;
  int cubature_draws = 4000;
  int temperatures = 32;  ///< rungs from beta = 1 to 1/max_temperature, more where that is extended
  /// The ladder reaches at least this far; further where the prior's draws have ln L below the best
  /// fit's by more (beta_min (ln L_best - median ln L over the prior) <= 1 keeps the last stone's
  /// weights comparable), with the same number of rungs per decade.
  double max_temperature = 1e6;
  int walkers = 0;     ///< per temperature; 0: max(4 x free parameters, 16)
  int steps = 4000;    ///< the cap on updates per temperature, the first half burn-in
  unsigned seed = 20090501;
  int threads = 1;     ///< share the model evaluations; the result does not depend on it
  /// Updates at the start of the burn-in during which the ladder between beta = 1 and
  /// 1/max_temperature adapts towards equal swap rates between neighbours (Vousden, Farr & Mandel
  /// 2016, MNRAS 455, 1919, section 3.1); at most a quarter of `steps`; 0: a fixed ladder (the
  /// default until the evidence's accuracy with it is measured for every model family).
  int adapt_steps = 0;
  double target_uncertainty = 0.1;  ///< standard error of ln Z to reach
  int check_every = 250;            ///< 0: run exactly `steps`
  std::function<void(const std::string&)> progress = nullptr;  ///< as PosteriorOptions::progress
};

/// ModelEvidence::method: what gave log_evidence.
inline constexpr const char* kImportanceSamplingMethod = "importance sampling";
inline constexpr const char* kCubatureMethod = "adaptive cubature";
inline constexpr const char* kTemperingMethod = "parallel tempering";

struct ModelEvidence {
  /// kImportanceSamplingMethod, kCubatureMethod or kTemperingMethod; in a comparison also
  /// kUpperBoundMethod (comparison.hpp): log_evidence is then a bound.
  std::string method;
  /// Why importance sampling did not serve (then parallel tempering did); empty where it did.
  std::string fallback_reason;
  double pareto_k = 0.0;         ///< of the importance weights (sampling::ImportanceEstimate), where they were drawn
  double effective_draws = 0.0;  ///< Kish's effective number of the importance draws
  /// ln Z = ln of the integral of likelihood x prior over the free ln-parameters, with the
  /// likelihood exp(-chi^2/2): up to a constant that is the same for every model fitted to the same
  /// data (the Gaussian normalisation of the data's sigmas), so differences between models are exact.
  double log_evidence = 0.0;
  double uncertainty = 0.0;  ///< standard error (Monte Carlo; stepping stones have no discretisation error)
  double thermodynamic_integration = 0.0;  ///< cross-check by thermodynamic integration over the same ladder
  double stone_overlap = 0.0;  ///< smallest effective fraction of a stone's weights (sampling::Evidence)
  int temperatures = 0;        ///< rungs of the ladder, beta = 0 included
  /// Accepted fraction of swaps between neighbouring rungs, coldest pair first, over the steps after
  /// the ladder's adaptation.
  std::vector<double> swap_acceptance;
  double max_temperature = 0.0;
  int steps = 0;               ///< updates run per temperature, the first half burn-in
  /// Posterior-predictive p-value of chi^2: the chance that data replicated from the posterior fit
  /// worse than the observed data (small: the model does not describe the data).
  double predictive_p = 0.0;
  double acceptance = 0.0;   ///< of the beta = 1 ensemble
  /// The beta = 1 ensemble passed the convergence criteria and the standard error of ln Z reached
  /// the target; else the cap ended the run, and advice says how far it got.
  bool converged = false;
  std::string advice;
  /// Likelihood evaluations: importance sampling's (shared by every prior set it integrated at
  /// once) plus parallel tempering's where it ran.
  int evaluations = 0;
  /// The largest ln L among adaptive cubature's map draws (-inf where it did not run): above the
  /// best fit's -chi^2/2, the fit missed the global maximum.
  double highest_drawn_log_likelihood = -std::numeric_limits<double>::infinity();
  double wall_seconds = 0.0;
  /// Equally weighted posterior draws: resampled from the importance draws, or the beta = 1
  /// ensemble's pooled kept draws x free parameters, values [unit] (as
  /// PosteriorResult::samples): the posterior under these priors, e.g. for its predictive band.
  Eigen::MatrixXd samples;
};

/// The evidence of `model` for `data` under `priors` (all proper: every prior is normalised over
/// the search bounds), started around the best fit: by options.method.
[[nodiscard]] ModelEvidence model_evidence(const ObservationSet& data, const sediment::SedimentModel& model,
                                           const FitResult& best, const std::vector<Prior>& priors,
                                           const FitOptions& fit_options, const EvidenceOptions& options);

/// The evidence under each of `prior_sets` (priors of the same parameters, e.g. priors and
/// widened(priors)) by importance sampling from one set of likelihood evaluations, the proposal
/// built from the best fit's linearised posterior. Each entry whose fallback_reason is not empty is
/// one the importance sampler's diagnostics refused (a direction the linearisation leaves open, a
/// fit far worse than the noise, Pareto k-hat > 0.7, posterior mass far from the linearisation, a
/// posterior pressed against a bound, or an error above 0.05): model_evidence with
/// EvidenceMethod::Tempering computes that one.
[[nodiscard]] std::vector<ModelEvidence> importance_sampled_evidence(
    const ObservationSet& data, const sediment::SedimentModel& model, const FitResult& best,
    const std::vector<std::vector<Prior>>& prior_sets, const FitOptions& fit_options, const EvidenceOptions& options);

/// The evidence under each of `prior_sets` by h-adaptive cubature (sampling/cubature.hpp) over the
/// union of their supports in the free ln-parameters, every set from the same likelihood
/// evaluations. Each axis is mapped from [0, 1] through a density that puts a t distribution
/// around the best fit (scaled by the linearised posterior), a kernel density of `hints` (posterior
/// draws [unit], e.g. a refused importance-sampling run's, which saw where the linearisation was
/// wrong) and a uniform floor over the support; once more with the kernel density of that map's own
/// importance-weighted draws added. Posterior draws come from importance sampling with the final
/// map's density as the proposal; its estimate of ln Z cross-checks the cubature's.
/// An entry whose fallback_reason is not empty did not converge or failed the cross-check:
/// parallel tempering computes that one.
[[nodiscard]] std::vector<ModelEvidence> cubature_integrated_evidence(
    const ObservationSet& data, const sediment::SedimentModel& model, const FitResult& best,
    const std::vector<std::vector<Prior>>& prior_sets, const FitOptions& fit_options, const EvidenceOptions& options,
    const std::vector<Eigen::MatrixXd>& hints = {});

/// The evidence's integrand over the free ln-parameters x (in the order of best.fitted's free
/// indices, other parameters at the best fit): ln prior(x) (normalised, Prior::log_density_theta),
/// ln L(x) = -chi^2(x)/2, and independent draws from the priors. What model_evidence integrates;
/// public so that a check can integrate it another way (e.g. by quadrature). The functions refer
/// to `model`, which must outlive them.
[[nodiscard]] sampling::PriorAndLikelihood evidence_integrand(const ObservationSet& data,
                                                              const sediment::SedimentModel& model,
                                                              const FitResult& best, const std::vector<Prior>& priors,
                                                              const FitOptions& fit_options);

/// Each prior made `factor` times wider: the sd (normal) or sd of ln (log-normal) times factor; a
/// flat prior's range times factor about its centre (in ln for log-uniform); all still cut to the
/// search bounds, so a default prior (already the whole bounds) does not change.
[[nodiscard]] std::vector<Prior> widened(const std::vector<Prior>& priors, double factor);

/// The posterior as JSON (fit.json's "posterior" entry) and the pooled samples as CSV (one column
/// per free parameter, SI units in the header).
[[nodiscard]] nlohmann::json posterior_report(const PosteriorResult& posterior);
void write_posterior_samples_csv(const std::filesystem::path& path, const PosteriorResult& posterior);
/// The same for any draws x parameters matrix with its column names and units.
void write_samples_csv(const std::filesystem::path& path, const Eigen::MatrixXd& samples,
                       const std::vector<std::string>& names, const std::vector<std::string>& units);
/// The same samples as HDF5: per free parameter a dataset of shape {walkers, kept steps} with its
/// unit, and root attributes that say what the file holds (sampler, priors, convergence).
void write_posterior_samples_hdf5(const std::filesystem::path& path, const PosteriorResult& posterior);
/// Each free parameter's marginal density as a 40-bin histogram of its draws: parameter, unit, bin
/// edges [unit] and density [1/unit].
void write_posterior_marginals_csv(const std::filesystem::path& path, const PosteriorResult& posterior);

}  // namespace sedwave::inversion
