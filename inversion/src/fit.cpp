#include "sedwave/inversion/fit.hpp"

#include <ceres/ceres.h>
#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <numbers>
#include <stdexcept>

#include "fit_problem.hpp"
#include "profile.hpp"
#include "sedwave/inversion/identifiability.hpp"

namespace sedwave::inversion {
namespace {

using detail::Differentiated;
using detail::LocalFit;
using detail::Setup;
using detail::Theta;
using detail::chi2_at;
using detail::solve_local;

void report_progress(const FitOptions& options, const std::string& stage) {
  if (options.progress) options.progress(stage);
}

/// Says before each likelihood profile how long it will take, from the profiles before it: where
/// every row has its own frequency nothing groups (fit_problem.hpp, Setup::RowGroup), the model runs
/// once per row at every evaluation, and a profile of 10^5 such rows takes tens of seconds.
class ProfileClock {
 public:
  explicit ProfileClock(const FitOptions& options) : options_(options) {}
  void start(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    if (running_) {
      total_ += std::chrono::duration<double>(now - started_).count();
      ++done_;
    }
    std::string stage = "likelihood profile of " + name;
    if (done_ > 0 && total_ / done_ >= kWorthSaying) {
      char estimate[64];
      std::snprintf(estimate, sizeof estimate, " (about %.0f s, as each profile so far)", total_ / done_);
      stage += estimate;
    }
    report_progress(options_, stage);
    started_ = now;
    running_ = true;
  }

 private:
  static constexpr double kWorthSaying = 1.0;  ///< seconds: shorter profiles are not worth a remark
  const FitOptions& options_;
  std::chrono::steady_clock::time_point started_;
  bool running_ = false;
  int done_ = 0;
  double total_ = 0.0;
};

struct GlobalFit {
  Theta theta;
  int evaluations;
  double chi2;
  /// The lowest search points of separate regions other than the best's (search_candidates).
  std::vector<Theta> candidates;
};

/// The search's points (free ln-parameters scaled to [0, 1] over the bounds) with no lower point
/// within this distance (per coordinate) stand for a region of their own.
constexpr double kCandidateRadius = 0.05;
/// At most this many such regions besides the best's are polished.
constexpr std::size_t kMaxCandidates = 4;

/// Of the search's points (theta, chi^2), the lowest of each region that no lower point lies within
/// kCandidateRadius of, the best's region left out; at most kMaxCandidates, lowest first.
std::vector<Theta> search_candidates(std::vector<std::pair<Theta, double>> points, const Setup& s,
                                     const std::vector<double>& lower, const std::vector<double>& upper) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  const auto near = [&](const Theta& a, const Theta& b) {
    for (std::size_t k = 0; k < s.free.size(); ++k) {
      const auto i = static_cast<std::size_t>(s.free[k]);
      if (std::abs(a[i] - b[i]) > kCandidateRadius * (upper[k] - lower[k])) return false;
    }
    return true;
  };
  std::vector<Theta> out;
  for (std::size_t i = 1; i < points.size() && out.size() < kMaxCandidates; ++i) {
    if (!std::isfinite(points[i].second)) break;
    bool lowest = true;
    for (std::size_t j = 0; j < i && lowest; ++j) lowest = !near(points[i].first, points[j].first);
    if (lowest) out.push_back(points[i].first);
  }
  return out;
}

nlopt::algorithm nlopt_algorithm(const std::string& name) {
  if (name == "direct-l") return nlopt::GN_DIRECT_L;
  if (name == "crs2") return nlopt::GN_CRS2_LM;
  if (name == "mlsl") return nlopt::G_MLSL_LDS;
  throw std::invalid_argument("unknown global algorithm '" + name + "' (accepted: direct-l, crs2, mlsl)");
}

/// The global search needs the shape of chi^2, not its last digit: above kSearchObservations it
/// runs on an evenly strided subset (every k-th observation in file order, both quantities kept),
/// and the polish that follows uses every observation. Makes a 10^6-row file's search cost what a
/// 2000-row file's does.
constexpr std::size_t kSearchObservations = 2000;

Setup search_subset(const Setup& s) {
  const std::size_t n = s.observations.size();
  if (n <= kSearchObservations) return s;
  return detail::every_kth_row(s, (n + kSearchObservations - 1) / kSearchObservations);
}

GlobalFit solve_global(const Setup& full, const Theta& start, const FitOptions& options) {
  const Setup s = search_subset(full);
  const auto n = static_cast<unsigned>(s.free.size());
  nlopt::srand(options.random_seed);
  nlopt::opt opt(nlopt_algorithm(options.global_algorithm), n);
  if (options.global_algorithm == "mlsl") {
    nlopt::opt local(nlopt::LN_BOBYQA, n);
    local.set_xtol_rel(1e-8);
    opt.set_local_optimizer(local);
  }
  std::vector<double> lower, upper, x;
  for (int i : s.free) {
    lower.push_back(std::log(s.parameters.spec[i].lower));
    upper.push_back(std::log(s.parameters.spec[i].upper));
    x.push_back(start[i]);
  }
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_maxeval(options.max_global_evaluations);

  struct Context {
    const Setup* setup;
    Theta theta;
    int evaluations = 0;
    double best = std::numeric_limits<double>::infinity();
    Theta best_theta;
    std::vector<std::pair<Theta, double>> points;
  } context{&s, start, 0, std::numeric_limits<double>::infinity(), start, {}};
  auto objective = [](const std::vector<double>& xs, std::vector<double>&, void* data) {
    auto* c = static_cast<Context*>(data);
    for (size_t k = 0; k < xs.size(); ++k) c->theta[c->setup->free[k]] = xs[k];
    ++c->evaluations;
    const double chi2 = chi2_at(*c->setup, c->theta);
    c->points.emplace_back(c->theta, std::isfinite(chi2) ? chi2 : std::numeric_limits<double>::infinity());
    if (chi2 < c->best) {
      c->best = chi2;
      c->best_theta = c->theta;
    }
    return std::isfinite(chi2) ? chi2 : std::numeric_limits<double>::max();
  };
  opt.set_min_objective(objective, &context);
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {
    // NLopt signals roundoff-limited or forced stops by throwing; the best point seen still stands.
  }
  return {context.best_theta, context.evaluations, chi2_at(full, context.best_theta),
          search_candidates(std::move(context.points), s, lower, upper)};
}

/// chi^2 rises by more than this above both ends somewhere on the straight line between two minima
/// (in the ln-parameters): separate modes, not two points of one flat valley or ridge.
constexpr double kBarrierChi2 = 2.0;

bool barrier_between(const Setup& s, const Theta& a, double chi2_a, const Theta& b, double chi2_b) {
  const double top = std::max(chi2_a, chi2_b) + kBarrierChi2;
  for (const double t : {0.25, 0.5, 0.75}) {
    Theta x = a;
    for (int i : s.free) x[static_cast<std::size_t>(i)] += t * (b[static_cast<std::size_t>(i)] - a[static_cast<std::size_t>(i)]);
    if (!(chi2_at(s, x) <= top)) return true;
  }
  return false;
}

/// The local minima among `found` (polished fits) that a barrier separates from the fit (`result`)
/// and from each other, within kOtherMinimaChi2 of its chi^2, lowest first.
std::vector<LocalMinimum> other_minima(const Setup& s, const FitResult& result, std::vector<LocalFit> found) {
  std::sort(found.begin(), found.end(), [](const LocalFit& a, const LocalFit& b) { return a.chi2 < b.chi2; });
  const Theta best = result.fitted.log_values();
  std::vector<std::pair<Theta, double>> kept{{best, result.chi2}};
  std::vector<LocalMinimum> out;
  for (const LocalFit& f : found) {
    if (!(f.chi2 <= result.chi2 + kOtherMinimaChi2)) continue;
    const bool separate = std::all_of(kept.begin(), kept.end(), [&](const auto& k) {
      return barrier_between(s, k.first, k.second, f.theta, f.chi2);
    });
    if (!separate) continue;
    kept.emplace_back(f.theta, f.chi2);
    LocalMinimum m{{}, f.chi2};
    for (const double t : f.theta) m.values.push_back(std::exp(t));
    out.push_back(std::move(m));
  }
  return out;
}

// ---- The analysis at the solution.

/// A quantity is "at its bound" within 1 % (0.01 in ln units) of it: closer than that the bound,
/// not the data, decides where a flat direction stops.
constexpr double kAtBoundLog = 1e-2;

/// Profile interval of one quantity into (lower, upper) [unit]; whether it closes within the
/// "determined" spread. Records a better minimum if the profile found one.
bool profile_into(const Setup& s, const Theta& theta, double chi2_min, const detail::ProfiledQuantity& q,
                  double log_sigma, const FitOptions& options, std::optional<double>& lower,
                  std::optional<double>& upper, std::optional<detail::Profile>& better) {
  const detail::Profile p = detail::profile(s, theta, chi2_min, q, log_sigma, options.max_iterations);
  if (p.lower) lower = std::exp(*p.lower);
  if (p.upper) upper = std::exp(*p.upper);
  if (p.better && (!better || p.better_chi2 < better->better_chi2)) better = p;
  return p.lower && p.upper && p.bounded_at_2_sigma && 0.5 * (*p.upper - *p.lower) < options.determined_log_sigma;
}

/// The identifiability, intervals and goodness of fit at theta. Returns a point of lower chi^2 if
/// a likelihood profile found one (the solvers stopped in a local minimum).
std::optional<Theta> analyze(const Setup& s, const Theta& theta, const FitOptions& options, FitResult& result) {
  const std::vector<detail::DerivedFunction> derived_functions = detail::derived_functions_for(s);
  const Eigen::MatrixXd J = detail::whitened_jacobian(s, theta);
  const JacobianAnalysis analysis = analyze_jacobian(J, detail::kRankTolerance);
  result.covariance = detail::covariance(s, theta);
  result.singular_values = analysis.singular_values;
  result.rank = analysis.rank;
  const double chi2_min = chi2_at(s, theta);
  std::optional<detail::Profile> better;

  ProfileClock clock(options);
  for (int i : s.free) result.free_names.push_back(s.parameters.spec[i].name);
  const auto p = static_cast<Eigen::Index>(s.free.size());
  for (Eigen::Index k = 0; k < p; ++k) {
    const double s_k = analysis.singular_values(k);
    const bool unseen = k >= analysis.rank;
    if (unseen || 1.0 / s_k > options.determined_log_sigma) {
      result.weak_directions.push_back({describe_direction(analysis.right_vectors.col(k), result.free_names),
                                        unseen ? 0.0 : s_k, unseen});
    }
  }

  for (int i = 0; i < s.parameters.size(); ++i) {
    const ParameterSpec& spec = s.parameters.spec[i];
    ParameterResult r;
    r.name = spec.name;
    r.unit = spec.unit;
    r.value = std::exp(theta[i]);
    r.free = spec.free;
    r.determined = true;  // fixed parameters are known exactly
    if (spec.free) {
      const auto k = std::find(s.free.begin(), s.free.end(), i) - s.free.begin();
      Eigen::VectorXd e = Eigen::VectorXd::Zero(p);
      e(k) = 1.0;
      const Determination d = determine(e, analysis, result.covariance, options.determined_log_sigma);
      r.at_bound = theta[i] <= detail::log_lower(s, i) + kAtBoundLog || theta[i] >= detail::log_upper(s, i) - kAtBoundLog;
      r.log_sigma = d.log_sigma;
      r.sigma = r.value * d.log_sigma;
      if (options.profile_likelihood) clock.start(r.name);
      const bool closed = !options.profile_likelihood ||
                          profile_into(s, theta, chi2_min, {i, nullptr}, d.log_sigma, options, r.profile_lower,
                                       r.profile_upper, better);
      // At a bound the bound, not the data, holds the value; and both the linearisation and the
      // profile must agree before a value is called determined.
      r.determined = d.determined && !r.at_bound && closed;
    }
    result.parameters.push_back(r);
  }

  for (const detail::DerivedFunction& info : derived_functions) {
    const Differentiated log_q = info.log_value(s, theta);
    const Eigen::VectorXd free_gradient = detail::free_part(log_q.v, s.free);
    const Determination d = determine(free_gradient, analysis, result.covariance, options.determined_log_sigma);
    const double value = std::exp(log_q.a);
    DerivedResult c{info.name, info.unit, info.meaning, value, d.determined, d.log_sigma, value * d.log_sigma, {}, {}};
    if (free_gradient.isZero(0.0)) {
      // Made of fixed parameters only: known exactly, and checked for plausibility like a fitted value.
      c.determined = true;
      c.log_sigma = c.sigma = 0.0;
      c.profile_lower = c.profile_upper = value;
    } else if (options.profile_likelihood && info.name == "f_star" && !result.derived.empty() &&
               result.derived.back().name == "tau") {
      // The grain contact's f* = 1/(2 pi tau): its interval is tau's, inverted (tau is profiled just
      // before, sediment::GrainContactDerived).
      const DerivedResult& tau = result.derived.back();
      const double k = 1.0 / (2.0 * std::numbers::pi);
      if (tau.profile_upper) c.profile_lower = k / *tau.profile_upper;
      if (tau.profile_lower) c.profile_upper = k / *tau.profile_lower;
      c.determined = tau.determined;
    } else if (options.profile_likelihood && d.null_component < 1.0 - 1e-9) {
      clock.start(info.name);
      const bool closed = profile_into(s, theta, chi2_min, {-1, &info}, d.log_sigma, options, c.profile_lower,
                                       c.profile_upper, better);
      c.determined = d.determined && closed;
    }
    result.derived.push_back(c);
  }

  // Correlations of the free ln-parameters; undetermined ones have none worth quoting.
  result.correlation = Eigen::MatrixXd::Constant(p, p, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index a = 0; a < p; ++a) {
    for (Eigen::Index b = 0; b < p; ++b) {
      const bool ok = result.parameters[s.free[a]].determined && result.parameters[s.free[b]].determined;
      if (ok) result.correlation(a, b) = result.covariance(a, b) / std::sqrt(result.covariance(a, a) * result.covariance(b, b));
    }
  }

  // Goodness of fit and per-point residuals.
  std::vector<double> normalized(s.observations.size());
  std::string why = "a residual is not defined at the solution (a non-positive model attenuation)";
  if (!detail::row_residuals_at(s, theta, normalized.data(), &why)) throw std::runtime_error(why);
  const std::vector<double> model = detail::predictions_at(s, theta);
  result.chi2 = 0.0;
  for (size_t r = 0; r < s.observations.size(); ++r) {
    result.residuals.push_back({s.observations[r], s.sigmas[r], s.defaulted[r], model[r], normalized[r]});
    result.chi2 += normalized[r] * normalized[r];
  }
  result.n_observations = static_cast<int>(s.observations.size());
  result.dof = result.n_observations - result.rank;
  result.aic = result.chi2 + 2.0 * result.rank;
  result.bic = result.chi2 + result.rank * std::log(static_cast<double>(result.n_observations));
  if (better) return better->better;
  return std::nullopt;
}

Theta with_values(FitParameters& parameters, const Theta& theta) {
  for (int i = 0; i < parameters.size(); ++i) {
    ParameterSpec& spec = parameters.spec[i];
    // exp(ln(bound)) may round to just outside the bound; a solution on a bound stays on it, so
    // that the fitted parameters are valid where a posterior or a profile starts from them.
    spec.value = std::clamp(std::exp(theta[i]), spec.lower, spec.upper);
  }
  return theta;
}

/// The interval a quantity's value is known to lie in: its 68 % profile interval (open ends reach
/// the search bounds), or the value alone when no profile was computed.
std::pair<double, double> credible_span(double value, const std::optional<double>& lower,
                                        const std::optional<double>& upper, bool profiled) {
  if (!profiled) return {value, value};
  return {lower.value_or(0.0), upper.value_or(std::numeric_limits<double>::infinity())};
}

void flag_range(const std::string& quantity, double value, std::pair<double, double> span,
                const PlausibleRange* range, FitResult& result) {
  if (!range) return;
  const bool below = span.second < range->lower, above = span.first > range->upper;
  if (!below && !above) return;
  char text[512];
  std::snprintf(text, sizeof text, "%s = %.4g is %s the physical range [%.3g, %.3g] (%s): likely %s", quantity.c_str(),
                value, below ? "below" : "above", range->lower, range->upper, range->basis,
                below ? range->below_cause : range->above_cause);
  result.flags.push_back({quantity, text});
}

/// A sand (d >= 62.5 um) looser than any sand: the joint check of grain size and porosity.
void flag_loose_sand(FitResult& result) {
  const auto find = [&](const char* name) {
    return std::find_if(result.parameters.begin(), result.parameters.end(),
                        [&](const ParameterResult& p) { return p.name == name; });
  };
  const auto d = find("d"), porosity = find("porosity");
  if (d == result.parameters.end() || porosity == result.parameters.end()) return;
  if (d->value < kSandDiameter || porosity->value <= kLoosestSandPorosity) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "porosity = %.3g with sand-sized grains (d = %.3g m): sands have porosities 0.37-0.47 (Hamilton 1980), "
                "none above %.2g; the model lowers the mixture's modulus through porosity to fit the data, so its "
                "mixture (water speed, grain moduli) or its loss mechanism does not describe them",
                porosity->value, d->value, kLoosestSandPorosity);
  result.flags.push_back({"porosity", text});
}

/// The plausible range a model gives one of its derived quantities, or nothing.
std::optional<PlausibleRange> derived_range(const sediment::SedimentModel& model, const std::string& name) {
  for (const sediment::DerivedQuantity& q : model.derived_quantities()) {
    if (q.name != name || !(q.plausible_upper > q.plausible_lower)) continue;
    return PlausibleRange{q.plausible_lower, q.plausible_upper, q.plausible_basis.c_str(), q.below_cause.c_str(),
                          q.above_cause.c_str()};
  }
  return std::nullopt;
}

/// Physical plausibility of every reported value (parameters: plausibility.hpp; derived quantities:
/// the model's own ranges), and parameters at a bound.
void flag_implausible(const sediment::SedimentModel& model, const FitOptions& options, FitResult& result) {
  for (const ParameterResult& p : result.parameters) {
    if (!p.free) continue;
    if (p.at_bound) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "%s stopped at its search bound (%.4g %s): the bound, not the data, holds it; widen the bound, "
                    "fix the parameter, or check the data's units",
                    p.name.c_str(), p.value, p.unit.c_str());
      result.flags.push_back({p.name, text});
    }
    flag_range(p.name, p.value, credible_span(p.value, p.profile_lower, p.profile_upper, options.profile_likelihood),
               plausible_range(p.name), result);
  }
  for (const DerivedResult& c : result.derived) {
    const std::optional<PlausibleRange> range = derived_range(model, c.name);
    flag_range(c.name, c.value, credible_span(c.value, c.profile_lower, c.profile_upper, options.profile_likelihood),
               range ? &*range : nullptr, result);
  }
  flag_loose_sand(result);
}

/// Analyses the fit at theta; if a profile finds a lower chi^2, polishes from there and analyses
/// again (at most three times), so no reported interval is drawn around a point that is not the minimum.
void analyze_with_restarts(const Setup& s, Theta theta, const FitOptions& options, FitResult& result) {
  for (int attempt = 0;; ++attempt) {
    FitResult analysed = result;
    with_values(analysed.fitted, theta);
    const std::optional<Theta> better = analyze(s, theta, options, analysed);
    if (!better || attempt == 3) {
      analysed.profile_restarts = attempt;
      result = std::move(analysed);
      break;
    }
    theta = solve_local(s, *better, options.max_iterations).theta;
  }
  flag_implausible(*s.model, options, result);
  // A model whose own sigma is known to leave something out (a one-packing table) makes every
  // interval too narrow by an unknown amount.
  if (const std::string caveat = s.model->uncertainty_caveat(); !caveat.empty()) {
    result.flags.push_back({"model", caveat});
  }
}

const char* method_name(FitMethod method) {
  switch (method) {
    case FitMethod::Ceres: return "ceres";
    case FitMethod::NLopt: return "nlopt";
    default: return "global";
  }
}

}  // namespace

FitMethod parse_fit_method(const std::string& name) {
  if (name == "ceres") return FitMethod::Ceres;
  if (name == "nlopt") return FitMethod::NLopt;
  if (name == "global") return FitMethod::Global;
  throw std::invalid_argument("unknown fit method '" + name + "' (accepted: ceres, nlopt, global)");
}

FitResult fit(const ObservationSet& data, const sediment::SedimentModel& model, const FitParameters& parameters,
              const FitOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const Setup s = detail::make_setup(data, model, parameters, options);
  const Theta start = parameters.log_values();
  FitResult result;
  result.model = model.name();
  result.method = method_name(options.method);
  result.fitted = parameters;

  Theta theta = start;
  std::vector<LocalFit> found;
  if (options.method == FitMethod::Ceres) {
    const LocalFit local = solve_local(s, start, options.max_iterations);
    theta = local.theta;
    result.converged = local.converged;
    result.solver_message = local.message;
  } else {
    report_progress(options, "global search (" + options.global_algorithm + ", at most " +
                                 std::to_string(options.max_global_evaluations) + " evaluations)");
    const GlobalFit global = solve_global(s, start, options);
    GlobalSearchReport report{options.global_algorithm, global.evaluations, global.chi2, global.chi2, 0.0, false};
    theta = global.theta;
    result.converged = std::isfinite(global.chi2);
    result.solver_message = "NLopt " + options.global_algorithm + " search";
    if (options.method == FitMethod::Global) {
      const LocalFit polished = solve_local(s, global.theta, options.max_iterations);
      const LocalFit from_start = solve_local(s, start, options.max_iterations);
      report.chi2_polished = polished.chi2;
      report.chi2_local_from_start = from_start.chi2;
      // Two minima differing by Delta chi^2 < 0.01 are the same minimum within a tenth of the
      // parameters' 1-sigma (Delta chi^2 = 1); an interpolated table model stops its local fits a
      // few thousandths apart without being a different solution.
      report.local_and_global_agree =
          std::abs(polished.chi2 - from_start.chi2) <= std::max(1e-2, 1e-6 * polished.chi2);
      const LocalFit& best = from_start.chi2 < polished.chi2 ? from_start : polished;
      theta = best.theta;
      result.converged = best.converged;
      result.solver_message = best.message;
      // The other polished fits, and the search's best points in other regions polished: where
      // they end apart from the fit, the posterior has several modes.
      found.push_back(from_start.chi2 < polished.chi2 ? polished : from_start);
      for (const Theta& candidate : global.candidates) found.push_back(solve_local(s, candidate, options.max_iterations));
    }
    result.global = report;
  }
  analyze_with_restarts(s, theta, options, result);
  if (!found.empty()) result.other_minima = other_minima(s, result, std::move(found));
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

FitResult fit(const ObservationSet& data, const forward::DispersionModel& model, const FitParameters& parameters,
              const FitOptions& options) {
  return fit(data, *grain_contact_model(model, parameters.damping_form()), parameters, options);
}

std::shared_ptr<const sediment::GrainContactModel> grain_contact_model(const forward::DispersionModel& model,
                                                                       DampingForm form) {
  // Non-owning: the caller keeps `model` alive for as long as the result is used.
  const std::shared_ptr<const forward::DispersionModel> borrowed(&model, [](const forward::DispersionModel*) {});
  return std::make_shared<const sediment::GrainContactModel>(borrowed, form);
}

std::vector<CurvePoint> model_curves(const FitResult& result, const sediment::SedimentModel& model,
                                     const std::vector<double>& frequencies_hz) {
  const std::vector<int> free = result.fitted.free_indices();
  const std::vector<double> values = result.fitted.values();
  auto sigma_of = [&](double q, const std::vector<double>& d_value) {
    Eigen::VectorXd g(static_cast<Eigen::Index>(free.size()));  // d ln q / d theta_free
    for (std::size_t k = 0; k < free.size(); ++k) g(static_cast<Eigen::Index>(k)) = d_value[free[k]] * values[free[k]] / q;
    return q * std::sqrt(std::max(0.0, g.dot(result.covariance * g)));
  };
  std::vector<CurvePoint> curves;
  for (double f : frequencies_hz) {
    sediment::Wave w;
    try {
      w = model.evaluate(values, f, true);
    } catch (const std::domain_error&) {
      continue;
    }
    CurvePoint c{f, kNotApplicable, kNotApplicable, kNotApplicable, kNotApplicable, w.attenuation,
                 sigma_of(w.attenuation, w.d_attenuation), w.speed, sigma_of(w.speed, w.d_speed)};
    if (const std::optional<sediment::DimensionlessWave> h = model.dimensionless_wave(values, f)) {
      c.omega_hat = h->omega_hat;
      c.gamma_hat = h->gamma_hat;
      c.alpha_hat = h->alpha_hat;
      c.c_hat = h->c_hat;
    }
    curves.push_back(c);
  }
  return curves;
}

std::vector<CurvePoint> model_curves(const FitResult& result, const forward::DispersionModel& model,
                                     const std::vector<double>& frequencies_hz) {
  return model_curves(result, *grain_contact_model(model, result.fitted.damping_form()), frequencies_hz);
}

}  // namespace sedwave::inversion
