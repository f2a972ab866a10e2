#include "sedwave/inversion/fit.hpp"

#include <ceres/ceres.h>
#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "sedwave/inversion/identifiability.hpp"
#include "sedwave/inversion/residuals.hpp"

namespace sedwave::inversion {
namespace {

using Theta = std::array<double, kParameterCount>;
using Jet3 = ceres::Jet<double, kParameterCount>;

/// Everything a fit needs besides the solver: observations with resolved sigmas and the predictor.
struct Setup {
  std::vector<Observation> observations;
  std::vector<ObservationResidual> residuals;
  std::vector<double> sigmas;
  std::vector<bool> defaulted;
  Predictor predictor;
  FitParameters parameters;
  std::vector<int> free;
};

Setup make_setup(const ObservationSet& data, const forward::DispersionModel& model, const FitParameters& parameters,
                 const FitOptions& options) {
  if (data.observations.empty()) throw std::invalid_argument("no observations to fit");
  parameters.validate();
  Setup s{data.observations, {}, {}, {}, Predictor(model, parameters.damping, parameters.density), parameters, parameters.free_indices()};
  for (const Observation& o : data.observations) {
    const bool missing = !o.sigma.has_value();
    const double sigma = missing ? options.default_relative_sigma * o.value : *o.sigma;
    s.residuals.emplace_back(s.predictor, o, sigma);
    s.sigmas.push_back(sigma);
    s.defaulted.push_back(missing);
  }
  return s;
}

double chi2_at(const Setup& s, const Theta& theta) {
  double chi2 = 0.0;
  for (const ObservationResidual& r : s.residuals) {
    double value = 0.0;
    try {
      if (!r(&theta[0], &theta[1], &theta[2], &value)) return std::numeric_limits<double>::infinity();
    } catch (const std::domain_error&) {
      return std::numeric_limits<double>::infinity();
    }
    chi2 += value * value;
  }
  return chi2;
}

/// Ceres cost wrapper: a model outside its domain makes the step fail instead of throwing.
struct GuardedResidual {
  ObservationResidual residual;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, T* out) const {
    try {
      return residual(a, b, c, out);
    } catch (const std::domain_error&) {
      return false;
    }
  }
};

/// The Ceres problem over theta; fixed parameters are constant blocks, bounds are in ln space.
/// `held` (if >= 0) is a free parameter held at its current value, as a likelihood profile needs.
void build_problem(const Setup& s, Theta& theta, ceres::Problem& problem, int held = -1) {
  for (const ObservationResidual& r : s.residuals) {
    auto* cost = new ceres::AutoDiffCostFunction<GuardedResidual, 1, 1, 1, 1>(new GuardedResidual{r});
    problem.AddResidualBlock(cost, nullptr, &theta[0], &theta[1], &theta[2]);
  }
  for (int i = 0; i < kParameterCount; ++i) {
    const ParameterSpec& spec = s.parameters.spec[i];
    if (!spec.free || i == held) {
      problem.SetParameterBlockConstant(&theta[i]);
      continue;
    }
    problem.SetParameterLowerBound(&theta[i], 0, std::log(spec.lower));
    problem.SetParameterUpperBound(&theta[i], 0, std::log(spec.upper));
  }
}

struct LocalFit {
  Theta theta;
  bool converged;
  std::string message;
  double chi2;
};

LocalFit solve_local(const Setup& s, Theta theta, int max_iterations, int held = -1) {
  ceres::Problem problem;
  build_problem(s, theta, problem, held);
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  // chi^2 from our own evaluation: when the model cannot be evaluated at the start (outside a
  // table, say) Ceres fails with final_cost 0, which must not read as a perfect fit.
  const double chi2 = chi2_at(s, theta);
  return {theta, summary.termination_type == ceres::CONVERGENCE && std::isfinite(chi2), summary.message, chi2};
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

GlobalFit solve_global(const Setup& s, const Theta& start, const FitOptions& options) {
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
  return {context.best_theta, context.evaluations, context.best};
}

/// Whitened Jacobian d residual / d theta_free, by forward-mode automatic differentiation.
Eigen::MatrixXd whitened_jacobian(const Setup& s, const Theta& theta) {
  std::array<Jet3, kParameterCount> t;
  for (int i = 0; i < kParameterCount; ++i) t[i] = Jet3(theta[i], i);
  Eigen::MatrixXd J(static_cast<Eigen::Index>(s.residuals.size()), static_cast<Eigen::Index>(s.free.size()));
  for (size_t r = 0; r < s.residuals.size(); ++r) {
    Jet3 value;
    if (!s.residuals[r](&t[0], &t[1], &t[2], &value)) throw std::runtime_error("residual failed at the solution");
    for (size_t k = 0; k < s.free.size(); ++k) J(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = value.v[s.free[k]];
  }
  return J;
}

/// Relative size below which a singular value of the whitened Jacobian counts as zero. The
/// covariance drops the matching eigenvalues of J^T J (their squares), so both views agree on
/// which directions are unseen.
constexpr double kRankTolerance = 1e-8;

/// Covariance of the free ln-parameters from ceres::Covariance; a pseudo-inverse when J^T J is
/// singular.
Eigen::MatrixXd ceres_covariance(const Setup& s, Theta theta) {
  ceres::Problem problem;
  build_problem(s, theta, problem);
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.null_space_rank = -1;
  options.min_reciprocal_condition_number = kRankTolerance * kRankTolerance;
  options.num_threads = 1;
  ceres::Covariance covariance(options);
  std::vector<const double*> blocks;
  for (int i : s.free) blocks.push_back(&theta[i]);
  const auto n = static_cast<Eigen::Index>(blocks.size());
  Eigen::MatrixXd result = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (!covariance.Compute(blocks, &problem)) return result;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dense(n, n);
  covariance.GetCovarianceMatrix(blocks, dense.data());
  return dense;
}

/// c0, tau, f*, gamma_hat as functions of theta (templated for gradients).
template <typename T>
std::array<T, 4> combinations(const std::array<T, 3>& theta, DampingForm form, double density) {
  using std::exp;
  const forward::GrainScales<T> s{exp(theta[0]), exp(theta[1]), T(density)};
  const T gamma = form == DampingForm::Gamma ? exp(theta[2]) : s.gamma(forward::gamma_hat_from_restitution(exp(theta[2])));
  const T tau = gamma / s.kappa;
  return {s.speed_scale(), tau, 1.0 / (2.0 * std::numbers::pi * tau), s.gamma_hat(gamma)};
}

Eigen::VectorXd free_part(const Jet3& q, const std::vector<int>& free) {
  Eigen::VectorXd g(static_cast<Eigen::Index>(free.size()));
  for (size_t k = 0; k < free.size(); ++k) g(static_cast<Eigen::Index>(k)) = q.v[free[k]] / q.a;  // d ln q
  return g;
}

/// Profile-likelihood interval of one free ln-parameter: where chi^2, minimised over the other
/// parameters, rises by 1 above its minimum on each side. A side that reaches the bound first is
/// open. Unlike the linearised sigma this stays honest when the model is strongly nonlinear in the
/// parameter (a grain size seen only through a small lattice correction, say).
ProfileInterval profile_interval(const Setup& s, const Theta& best, double chi2_min, int index, double linear_sigma,
                                 int max_iterations) {
  const double lower_bound = std::log(s.parameters.spec[index].lower);
  const double upper_bound = std::log(s.parameters.spec[index].upper);
  auto delta_chi2 = [&](double value, Theta& start) {
    start[index] = value;
    const LocalFit f = solve_local(s, start, max_iterations, index);
    start = f.theta;
    return f.chi2 - chi2_min;
  };
  ProfileInterval interval;
  for (int side : {-1, +1}) {
    const double bound = side < 0 ? lower_bound : upper_bound;
    double inside = best[index];  // Delta chi^2 < 1 here
    double step = std::clamp(std::isfinite(linear_sigma) ? linear_sigma : 0.1, 1e-3, 1.0);
    Theta start = best;
    std::optional<double> outside;
    while (!outside) {
      const double trial = best[index] + side * step;
      if (side * (trial - bound) >= 0.0) {
        if (delta_chi2(bound, start) < 1.0) break;  // open: the bound is within 1 sigma
        outside = bound;
      } else if (delta_chi2(trial, start) >= 1.0) {
        outside = trial;
      } else {
        inside = trial;
        step *= 2.0;
      }
    }
    if (!outside) continue;
    // Bisection on Delta chi^2 = 1 to 1e-3 in ln units (0.1% relative).
    Theta from = best;
    while (std::abs(*outside - inside) > 1e-3) {
      const double middle = 0.5 * (inside + *outside);
      Theta trial_start = from;
      if (delta_chi2(middle, trial_start) >= 1.0) {
        outside = middle;
      } else {
        inside = middle;
        from = trial_start;
      }
    }
    (side < 0 ? interval.lower : interval.upper) = 0.5 * (inside + *outside);
    // A profile can close at 1 sigma and still flatten out towards the bound (a weak preference
    // for a finite value, as noise can fake): demand the bound itself be excluded at 2 sigma.
    Theta at_bound = best;
    if (delta_chi2(bound, at_bound) < 4.0) interval.bounded_at_2_sigma = false;
  }
  return interval;
}

void analyze(const Setup& s, const Theta& theta, const FitOptions& options, FitResult& result) {
  const Eigen::MatrixXd J = whitened_jacobian(s, theta);
  const JacobianAnalysis analysis = analyze_jacobian(J, kRankTolerance);
  result.covariance = ceres_covariance(s, theta);
  result.singular_values = analysis.singular_values;
  result.rank = analysis.rank;

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
      const double tol = 1e-6;
      r.at_bound = theta[i] <= std::log(spec.lower) + tol || theta[i] >= std::log(spec.upper) - tol;
      r.log_sigma = d.log_sigma;
      r.sigma = r.value * d.log_sigma;
      bool profile_closed = true;
      if (options.profile_likelihood) {
        const ProfileInterval interval =
            profile_interval(s, theta, chi2_at(s, theta), i, d.log_sigma, options.max_iterations);
        if (interval.lower) r.profile_lower = std::exp(*interval.lower);
        if (interval.upper) r.profile_upper = std::exp(*interval.upper);
        profile_closed = interval.lower && interval.upper && interval.bounded_at_2_sigma &&
                         0.5 * (*interval.upper - *interval.lower) < options.determined_log_sigma;
      }
      // At a bound the prior, not the data, holds the value; and both the linearisation and the
      // profile must agree before a value is called determined.
      r.determined = d.determined && !r.at_bound && profile_closed;
    }
    result.parameters.push_back(r);
  }

  std::array<Jet3, 3> t;
  for (int i = 0; i < kParameterCount; ++i) t[i] = Jet3(theta[i], i);
  const std::array<Jet3, 4> q = combinations(t, form, s.parameters.density);
  static const std::array<std::array<const char*, 3>, 4> kInfo{{
      {"c0", "m/s", "low-frequency sound speed d sqrt(kappa/m), proportional to sqrt(kappa/d)"},
      {"tau", "s", "relaxation time gamma/kappa of a contact"},
      {"f_star", "Hz", "crossover frequency 1/(2 pi tau) where attenuation bends from f^2 to f^(1/2)"},
      {"gamma_hat", "1", "dimensionless dashpot gamma/sqrt(kappa m)"},
  }};
  for (size_t c = 0; c < q.size(); ++c) {
    const Determination d = determine(free_part(q[c], s.free), analysis, result.covariance, options.determined_log_sigma);
    result.combinations.push_back({kInfo[c][0], kInfo[c][1], kInfo[c][2], q[c].a, d.determined, d.log_sigma,
                                   q[c].a * d.log_sigma});
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
}

Theta with_values(FitParameters& parameters, const Theta& theta) {
  for (int i = 0; i < kParameterCount; ++i) parameters.spec[i].value = std::exp(theta[i]);
  return theta;
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
  const Setup s = make_setup(data, model, parameters, options);
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
  with_values(result.fitted, theta);
  analyze(s, theta, options, result);
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

std::vector<CurvePoint> model_curves(const FitResult& result, const forward::DispersionModel& model,
                                     const std::vector<double>& frequencies_hz) {
  const Predictor predictor(model, result.fitted.damping, result.fitted.density);
  const std::vector<int> free = result.fitted.free_indices();
  const Theta theta = result.fitted.log_values();
  std::array<Jet3, kParameterCount> t;
  for (int i = 0; i < kParameterCount; ++i) t[i] = Jet3(theta[i], i);
  auto sigma_of = [&](const Jet3& q) {
    const Eigen::VectorXd g = free_part(q, free);
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
