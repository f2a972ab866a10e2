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
#include <numbers>
#include <stdexcept>

#include "fit_problem.hpp"
#include "profile.hpp"
#include "sedwave/inversion/identifiability.hpp"

namespace sedwave::inversion {
namespace {

using detail::Jet3;
using detail::LocalFit;
using detail::Setup;
using detail::Theta;
using detail::chi2_at;
using detail::solve_local;

void report_progress(const FitOptions& options, const std::string& stage) {
  if (options.progress) options.progress(stage);
}

struct GlobalFit {
  Theta theta;
  int evaluations;
  double chi2;
};

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
  Setup subset = s;
  const std::size_t n = s.residuals.size();
  if (n <= kSearchObservations) return subset;
  const std::size_t stride = (n + kSearchObservations - 1) / kSearchObservations;
  subset.observations.clear();
  subset.residuals.clear();
  subset.sigmas.clear();
  subset.defaulted.clear();
  for (std::size_t i = 0; i < n; i += stride) {
    subset.observations.push_back(s.observations[i]);
    subset.residuals.push_back(s.residuals[i]);
    subset.sigmas.push_back(s.sigmas[i]);
    subset.defaulted.push_back(s.defaulted[i]);
  }
  return subset;
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
  } context{&s, start, 0, std::numeric_limits<double>::infinity(), start};
  auto objective = [](const std::vector<double>& xs, std::vector<double>&, void* data) {
    auto* c = static_cast<Context*>(data);
    for (size_t k = 0; k < xs.size(); ++k) c->theta[c->setup->free[k]] = xs[k];
    ++c->evaluations;
    const double chi2 = chi2_at(*c->setup, c->theta);
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
  return {context.best_theta, context.evaluations, chi2_at(full, context.best_theta)};
}

// ---- Combinations: functions of theta that the data may determine when the parameters are not.
// Each is ln q(theta) on Jets (value and gradient), so the same code gives the value, the
// linearised sigma and the likelihood profile.

forward::GrainScales<Jet3> scales(const std::array<Jet3, kParameterCount>& t, const Setup& s) {
  return {exp(t[kKappa]), exp(t[kDiameter]), Jet3(s.parameters.density)};
}

Jet3 log_gamma(const std::array<Jet3, kParameterCount>& t, const Setup& s) {
  if (s.parameters.damping == DampingForm::Gamma) return t[kDamping];
  return log(scales(t, s).gamma(forward::gamma_hat_from_restitution(exp(t[kDamping]))));
}

/// Low-frequency sound speed: the speed scale d sqrt(kappa/m) times the model's c_hat as
/// omega_hat -> 0 (1 for the chains; a 3D packing's static value for a table).
Jet3 log_c0(const std::array<Jet3, kParameterCount>& t, const Setup& s) {
  return log(scales(t, s).speed_scale()) + std::log(s.predictor.model().long_wavelength_c_hat());
}
Jet3 log_tau(const std::array<Jet3, kParameterCount>& t, const Setup& s) { return log_gamma(t, s) - t[kKappa]; }
Jet3 log_f_star(const std::array<Jet3, kParameterCount>& t, const Setup& s) {
  return -log_tau(t, s) - std::log(2.0 * std::numbers::pi);
}
Jet3 log_gamma_hat(const std::array<Jet3, kParameterCount>& t, const Setup& s) {
  const forward::GrainScales<Jet3> g = scales(t, s);
  return log_gamma(t, s) - 0.5 * log(g.kappa * g.mass());
}
/// kappa over the Hertz stiffness of quartz grains of the same d at 10 kPa (plausibility.hpp);
/// Hertz kappa is proportional to d at a given pressure.
Jet3 log_kappa_over_hertz(const std::array<Jet3, kParameterCount>& t, const Setup&) {
  return t[kKappa] - t[kDiameter] - std::log(quartz_hertz_kappa(1.0));
}

struct CombinationInfo {
  const char* name;
  const char* unit;
  const char* meaning;
  Jet3 (*log_value)(const std::array<Jet3, kParameterCount>&, const Setup&);
};

const std::array<CombinationInfo, 5> kCombinations{{
    {"c0", "m/s", "low-frequency (f -> 0) sound speed of the model", log_c0},
    {"tau", "s", "relaxation time gamma/kappa of a contact", log_tau},
    {"f_star", "Hz", "crossover frequency 1/(2 pi tau) where attenuation bends from f^2 to f^(1/2)", log_f_star},
    {"gamma_hat", "1", "dimensionless dashpot gamma/sqrt(kappa m)", log_gamma_hat},
    {"kappa_over_hertz", "1", "kappa over the Hertz stiffness of quartz grains of diameter d at 10 kPa",
     log_kappa_over_hertz},
}};

Eigen::VectorXd free_part(const Jet3& log_q, const std::vector<int>& free) {
  Eigen::VectorXd g(static_cast<Eigen::Index>(free.size()));
  for (size_t k = 0; k < free.size(); ++k) g(static_cast<Eigen::Index>(k)) = log_q.v[free[k]];
  return g;
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
  const Eigen::MatrixXd J = detail::whitened_jacobian(s, theta);
  const JacobianAnalysis analysis = analyze_jacobian(J, detail::kRankTolerance);
  result.covariance = detail::covariance(s, theta);
  result.singular_values = analysis.singular_values;
  result.rank = analysis.rank;
  const double chi2_min = chi2_at(s, theta);
  std::optional<detail::Profile> better;

  const DampingForm form = s.parameters.damping;
  for (int i : s.free) result.free_names.push_back(parameter_name(i, form));
  const auto p = static_cast<Eigen::Index>(s.free.size());
  for (Eigen::Index k = 0; k < p; ++k) {
    const double s_k = analysis.singular_values(k);
    const bool unseen = k >= analysis.rank;
    if (unseen || 1.0 / s_k > options.determined_log_sigma) {
      result.weak_directions.push_back({describe_direction(analysis.right_vectors.col(k), result.free_names),
                                        unseen ? 0.0 : s_k, unseen});
    }
  }

  for (int i = 0; i < kParameterCount; ++i) {
    const ParameterSpec& spec = s.parameters.spec[i];
    ParameterResult r;
    r.name = parameter_name(i, form);
    r.unit = parameter_unit(i, form);
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
      if (options.profile_likelihood) report_progress(options, "likelihood profile of " + r.name);
      const bool closed = !options.profile_likelihood ||
                          profile_into(s, theta, chi2_min, {i, nullptr}, d.log_sigma, options, r.profile_lower,
                                       r.profile_upper, better);
      // At a bound the bound, not the data, holds the value; and both the linearisation and the
      // profile must agree before a value is called determined.
      r.determined = d.determined && !r.at_bound && closed;
    }
    result.parameters.push_back(r);
  }

  const detail::ThetaJets t = detail::seeded_jets(theta.data());
  for (const CombinationInfo& info : kCombinations) {
    const Jet3 log_q = info.log_value(t, s);
    const Determination d = determine(free_part(log_q, s.free), analysis, result.covariance, options.determined_log_sigma);
    const double value = std::exp(log_q.a);
    CombinationResult c{info.name, info.unit, info.meaning, value, d.determined, d.log_sigma, value * d.log_sigma, {}, {}};
    if (options.profile_likelihood && std::string(info.name) == "f_star") {
      // f* = 1/(2 pi tau): its interval is tau's, inverted (tau is profiled just before).
      const CombinationResult& tau = result.combinations.back();
      const double k = 1.0 / (2.0 * std::numbers::pi);
      if (tau.profile_upper) c.profile_lower = k / *tau.profile_upper;
      if (tau.profile_lower) c.profile_upper = k / *tau.profile_lower;
      c.determined = tau.determined;
    } else if (options.profile_likelihood && d.null_component < 1.0 - 1e-9) {
      report_progress(options, std::string("likelihood profile of ") + info.name);
      const bool closed = profile_into(s, theta, chi2_min, {-1, info.log_value}, d.log_sigma, options,
                                       c.profile_lower, c.profile_upper, better);
      c.determined = d.determined && closed;
    }
    result.combinations.push_back(c);
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
  result.chi2 = 0.0;
  for (size_t r = 0; r < s.residuals.size(); ++r) {
    PointResidual& point = result.residuals.emplace_back();
    point.observation = s.observations[r];
    point.sigma = s.sigmas[r];
    point.default_sigma = s.defaulted[r];
    (void)s.residuals[r](&theta[0], &theta[1], &theta[2], &point.normalized);
    const Prediction<double> model = s.predictor(theta[0], theta[1], theta[2], point.observation.frequency_hz);
    point.model = point.observation.quantity == Quantity::Attenuation ? model.alpha : model.speed;
    result.chi2 += point.normalized * point.normalized;
  }
  result.n_observations = static_cast<int>(s.residuals.size());
  result.dof = result.n_observations - result.rank;
  result.aic = result.chi2 + 2.0 * result.rank;
  result.bic = result.chi2 + result.rank * std::log(static_cast<double>(result.n_observations));
  if (better) return better->better;
  return std::nullopt;
}

Theta with_values(FitParameters& parameters, const Theta& theta) {
  for (int i = 0; i < kParameterCount; ++i) parameters.spec[i].value = std::exp(theta[i]);
  return theta;
}

/// The interval a quantity's value is known to lie in: its 68 % profile interval (open ends reach
/// the search bounds), or the value alone when no profile was computed.
std::pair<double, double> credible_span(double value, const std::optional<double>& lower,
                                        const std::optional<double>& upper, bool profiled) {
  if (!profiled) return {value, value};
  return {lower.value_or(0.0), upper.value_or(std::numeric_limits<double>::infinity())};
}

void flag_range(const std::string& quantity, double value, std::pair<double, double> span, FitResult& result) {
  const PlausibleRange* range = plausible_range(quantity);
  if (!range) return;
  const bool below = span.second < range->lower, above = span.first > range->upper;
  if (!below && !above) return;
  char text[512];
  std::snprintf(text, sizeof text, "%s = %.4g is %s the physical range [%.3g, %.3g] (%s): likely %s", quantity.c_str(),
                value, below ? "below" : "above", range->lower, range->upper, range->basis,
                below ? range->below_cause : range->above_cause);
  result.flags.push_back({quantity, text});
}

/// Physical plausibility of every reported value (plausibility.hpp), and parameters at a bound.
void flag_implausible(const FitOptions& options, FitResult& result) {
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
               result);
  }
  for (const CombinationResult& c : result.combinations) {
    flag_range(c.name, c.value, credible_span(c.value, c.profile_lower, c.profile_upper, options.profile_likelihood),
               result);
  }
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
  flag_implausible(options, result);
  // A model whose own sigma is known to leave something out (a one-packing table) makes every
  // interval too narrow by an unknown amount.
  if (const std::string caveat = s.predictor.model().uncertainty_caveat(); !caveat.empty()) {
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

FitResult fit(const ObservationSet& data, const forward::DispersionModel& model, const FitParameters& parameters,
              const FitOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const Setup s = detail::make_setup(data, model, parameters, options);
  const Theta start = parameters.log_values();
  FitResult result;
  result.model = model.name();
  result.method = method_name(options.method);
  result.fitted = parameters;

  Theta theta = start;
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
    }
    result.global = report;
  }
  analyze_with_restarts(s, theta, options, result);
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

std::vector<CurvePoint> model_curves(const FitResult& result, const forward::DispersionModel& model,
                                     const std::vector<double>& frequencies_hz) {
  const Predictor predictor(model, result.fitted.damping, result.fitted.density);
  const std::vector<int> free = result.fitted.free_indices();
  const Theta theta = result.fitted.log_values();
  const detail::ThetaJets t = detail::seeded_jets(theta.data());
  auto sigma_of = [&](const Jet3& q) {
    const Eigen::VectorXd g = free_part(q, free) / q.a;  // d ln q
    return q.a * std::sqrt(std::max(0.0, g.dot(result.covariance * g)));
  };
  std::vector<CurvePoint> curves;
  for (double f : frequencies_hz) {
    Prediction<Jet3> p;
    try {
      p = predictor(t[0], t[1], t[2], f);
    } catch (const std::domain_error&) {
      continue;
    }
    curves.push_back({f, p.omega_hat.a, p.gamma_hat.a, p.hat.alpha_hat.a, p.hat.c_hat.a, p.alpha.a, sigma_of(p.alpha),
                      p.speed.a, sigma_of(p.speed)});
  }
  return curves;
}

}  // namespace sedwave::inversion
