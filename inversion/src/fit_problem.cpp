#include "fit_problem.hpp"

#include <algorithm>
#include <charconv>
#include <complex>
#include <optional>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::inversion::detail {
namespace {

/// A sigma must be a positive number the residual can divide by without overflow: finite, and at
/// least 1e-12 of the value (no measurement is better).
void check_sigma(const Observation& o, double sigma, bool defaulted) {
  if (std::isfinite(sigma) && sigma > 0.0 && sigma >= 1e-12 * std::abs(o.value)) return;
  std::ostringstream msg;
  msg << o.file << ":" << o.line << ": ";
  if (defaulted) {
    msg << "field 'sigma' is empty and the default relative sigma gives " << sigma
        << ", which is not usable (give --default-sigma a number in [1e-12, 10])";
  } else {
    msg << "field 'sigma' = " << sigma << " is not usable: a 1-sigma uncertainty must be positive, finite and at "
        << "least 1e-12 of the value (" << o.value << ")";
  }
  throw std::invalid_argument(msg.str());
}

/// Attenuation and speed are usually measured at the same frequencies: the model runs once for each.
/// Rows that repeat a quantity, a frequency and a sigma form one group (Setup::RowGroup).
void index_rows(Setup& s) {
  std::map<double, std::size_t> index;
  s.frequencies.clear();
  s.frequency_of.clear();
  for (const Observation& o : s.observations) {
    const auto [at, inserted] = index.emplace(o.frequency_hz, s.frequencies.size());
    if (inserted) s.frequencies.push_back(o.frequency_hz);
    s.frequency_of.push_back(at->second);
  }
  using Key = std::tuple<Quantity, std::size_t, double, double>;
  std::map<Key, std::size_t> group_of;
  std::vector<std::vector<double>> members;
  s.groups.clear();
  s.reflection_groups.clear();
  s.shear_rows = false;
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    const Observation& o = s.observations[r];
    const double sigma = compared_sigma(o, s.sigmas[r]);
    const double angle = is_reflection(o.quantity) ? o.grazing_angle : 0.0;
    const auto [at, inserted] = group_of.emplace(Key{o.quantity, s.frequency_of[r], angle, sigma}, s.groups.size());
    if (inserted) {
      if (is_reflection(o.quantity)) s.reflection_groups.push_back(s.groups.size());
      s.groups.push_back({o.quantity, s.frequency_of[r], angle, 0.0, sigma, 0.0, 0.0});
      members.emplace_back();
    }
    members[at->second].push_back(compared_value(o));
    s.shear_rows = s.shear_rows || is_shear(o.quantity);
  }
  s.residual_count = 0;
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    Setup::RowGroup& group = s.groups[g];
    const std::vector<double>& values = members[g];
    group.count = static_cast<double>(values.size());
    double sum = 0.0;
    for (const double v : values) sum += v;
    group.observed = values.size() == 1 ? values.front() : sum / group.count;
    double squares = 0.0;
    for (const double v : values) squares += (v - group.observed) * (v - group.observed);
    group.scatter = std::sqrt(squares);
    s.residual_count += group.scatter > 0.0 ? 2 : 1;
  }
}

/// The model at every distinct frequency; false where it has no answer (and why, if asked). With
/// shear rows, `shear` receives the shear wave at each frequency too.
bool waves_at(const Setup& s, const std::vector<double>& values, bool derivatives, std::vector<sediment::Wave>& waves,
              std::string* why = nullptr, std::vector<sediment::Wave>* shear = nullptr) {
  waves.resize(s.frequencies.size());
  if (shear) shear->resize(s.shear_rows ? s.frequencies.size() : 0);
  try {
    for (std::size_t k = 0; k < s.frequencies.size(); ++k) {
      waves[k] = s.model->evaluate(values, s.frequencies[k], derivatives);
      if (shear && s.shear_rows) (*shear)[k] = s.model->evaluate_shear(values, s.frequencies[k], derivatives);
    }
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return false;
  }
  return true;
}

/// All observations' residuals as one Ceres cost function over one block per parameter (so any
/// parameter can be held constant): one block of n rows instead of n blocks of one row, which
/// spares Ceres its per-block bookkeeping. A model outside its domain makes the step fail.
class ObservationResiduals final : public ceres::CostFunction {
 public:
  explicit ObservationResiduals(const Setup& s) : setup_(&s) {
    set_num_residuals(static_cast<int>(s.residual_count));
    for (int i = 0; i < s.parameters.size(); ++i) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    Theta theta(static_cast<std::size_t>(setup_->parameters.size()));
    for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = parameters[i][0];
    if (!jacobians) return residuals_at(*setup_, theta, residuals, nullptr);
    Eigen::MatrixXd J;
    if (!residuals_at(*setup_, theta, residuals, &J)) return false;
    for (Eigen::Index i = 0; i < J.cols(); ++i) {
      if (jacobians[i]) Eigen::Map<Eigen::VectorXd>(jacobians[i], J.rows()) = J.col(i);
    }
    return true;
  }

 private:
  const Setup* setup_;
};

/// The residual (ln q(theta) - target) / tolerance of a Constraint, with its exact gradient.
class ConstraintResidual final : public ceres::CostFunction {
 public:
  ConstraintResidual(const Setup& s, const Constraint& c) : setup_(&s), constraint_(c) {
    set_num_residuals(1);
    for (int i = 0; i < s.parameters.size(); ++i) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residual, double** jacobians) const override {
    Theta theta(static_cast<std::size_t>(setup_->parameters.size()));
    for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = parameters[i][0];
    const Differentiated q = constraint_.derived->log_value(*setup_, theta);
    residual[0] = (q.a - constraint_.target) / constraint_.tolerance;
    if (jacobians) {
      for (Eigen::Index i = 0; i < q.v.size(); ++i) {
        if (jacobians[i]) jacobians[i][0] = q.v(i) / constraint_.tolerance;
      }
    }
    return std::isfinite(residual[0]);
  }

 private:
  const Setup* setup_;
  Constraint constraint_;
};

/// Where the fit compares the reflection coefficient: the reflection groups (quantity, frequency,
/// grazing angle), in order.
std::vector<Setup::RowGroup> reflection_points_of_groups(const Setup& s) {
  std::vector<Setup::RowGroup> points;
  for (std::size_t g : s.reflection_groups) points.push_back(s.groups[g]);
  return points;
}

/// The same for every reflection row, in order (a fit's per-row residuals and predictions).
std::vector<Setup::RowGroup> reflection_points_of_rows(const Setup& s) {
  std::vector<Setup::RowGroup> points;
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    const Observation& o = s.observations[r];
    if (is_reflection(o.quantity)) points.push_back({o.quantity, s.frequency_of[r], o.grazing_angle});
  }
  return points;
}

/// The seabed the setup's model describes at parameter values, under the data's water: a half-space
/// of the model, or a layered seabed's stack.
sediment::SeabedModel seabed_at(const Setup& s, const sediment::SedimentModel& model, const std::vector<double>& values) {
  return sediment::seabed_of(model, values, s.water_speed, s.water_density);
}

/// The bottom loss [dB] or |R| at each point for parameter values: water over the seabed the model
/// describes (elastic parts where a model has a shear wave). False where the model has no answer there.
bool reflection_values_at(const Setup& s, const std::vector<double>& values, const std::vector<Setup::RowGroup>& points,
                          std::vector<double>& out, std::string* why = nullptr) {
  out.clear();
  if (points.empty()) return true;
  // The media of each frequency once.
  std::vector<std::optional<sediment::LayeredHalfspace>> media(s.frequencies.size());
  try {
    const sediment::SeabedModel seabed = seabed_at(s, *s.model, values);
    for (const Setup::RowGroup& p : points) {
      const double f = s.frequencies[p.frequency];
      if (!media[p.frequency]) media[p.frequency] = sediment::layered_halfspace_at(seabed, f);
      const std::complex<double> reflection = sediment::reflection_coefficient(*media[p.frequency], p.grazing_angle, f);
      out.push_back(p.quantity == Quantity::BottomLoss ? sediment::bottom_loss_db(reflection) : std::abs(reflection));
    }
  } catch (const std::domain_error& e) {
    if (why) *why = e.what();
    return false;
  } catch (const std::invalid_argument& e) {  // a medium the reflection code refuses (e.g. negative attenuation)
    if (why) *why = e.what();
    return false;
  }
  return std::ranges::all_of(out, [](double x) { return std::isfinite(x); });
}

/// d value / d theta of every reflection group (groups x parameters) by central differences over
/// the free parameters (zero for fixed ones): the reflection code is not differentiated.
bool reflection_derivatives_at(const Setup& s, const Theta& theta, Eigen::MatrixXd& d, std::string* why) {
  const std::vector<Setup::RowGroup> points = reflection_points_of_groups(s);
  d.setZero(static_cast<Eigen::Index>(points.size()), static_cast<Eigen::Index>(theta.size()));
  if (points.empty()) return true;
  for (int i : s.free) {
    Theta up = theta;
    Theta down = theta;
    up[static_cast<std::size_t>(i)] += kBottomLossStep;
    down[static_cast<std::size_t>(i)] -= kBottomLossStep;
    std::vector<double> value_up;
    std::vector<double> value_down;
    if (!reflection_values_at(s, values_of(up), points, value_up) ||
        !reflection_values_at(s, values_of(down), points, value_down)) {
      if (why) *why = "the reflection coefficient cannot be differentiated here (the model has no answer a step away)";
      return false;
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      d(static_cast<Eigen::Index>(k), i) = (value_up[k] - value_down[k]) / (2.0 * kBottomLossStep);
    }
  }
  return true;
}

std::vector<double*> blocks_of(Theta& theta) {
  std::vector<double*> blocks;
  for (double& t : theta) blocks.push_back(&t);
  return blocks;
}

}  // namespace

std::vector<double> values_of(const Theta& theta) {
  std::vector<double> v(theta.size());
  std::transform(theta.begin(), theta.end(), v.begin(), [](double t) { return std::exp(t); });
  return v;
}

Setup make_setup(const ObservationSet& data, const sediment::SedimentModel& model, const FitParameters& parameters,
                 const FitOptions& options) {
  if (data.observations.empty()) throw std::invalid_argument("no observations to fit");
  parameters.require_parameters_of(model);
  parameters.validate();
  Setup s;
  s.observations = data.observations;
  s.model = &model;
  s.parameters = parameters;
  s.free = parameters.free_indices();
  for (const Observation& o : data.observations) {
    const bool missing = !o.sigma.has_value();
    const double sigma = missing ? options.default_relative_sigma * o.value : *o.sigma;
    check_sigma(o, sigma, missing);
    s.sigmas.push_back(sigma);
    s.defaulted.push_back(missing);
  }
  index_rows(s);
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    const Observation& o = s.observations[r];
    if (is_shear(o.quantity) && !model.has_shear()) {
      throw std::invalid_argument(o.file + ":" + std::to_string(o.line) + ": a shear-wave observation, and model '" +
                                  model.name() + "' has no shear wave (sedwave models lists those that do)");
    }
  }
  const auto reflection_row = std::ranges::find_if(s.observations, [](const Observation& o) { return is_reflection(o.quantity); });
  if (reflection_row != s.observations.end()) {
    const Observation& first = *reflection_row;
    if (!data.water_sound_speed) {
      throw std::invalid_argument(first.file + ":" + std::to_string(first.line) +
                                  ": reflection data need the water sound speed ('# water_sound_speed_m_per_s: ...')");
    }
    s.water_speed = *data.water_sound_speed;
    s.water_density = water_density_of(data);
    // Refuses, in the model's words, a model (or a layer's) that fixes no bulk density.
    (void)sediment::layered_halfspace_at(seabed_at(s, model, parameters.values()), first.frequency_hz);
  }
  return s;
}

Setup every_kth_row(const Setup& s, std::size_t stride) {
  Setup subset = s;
  subset.observations.clear();
  subset.sigmas.clear();
  subset.defaulted.clear();
  for (std::size_t i = 0; i < s.observations.size(); i += stride) {
    subset.observations.push_back(s.observations[i]);
    subset.sigmas.push_back(s.sigmas[i]);
    subset.defaulted.push_back(s.defaulted[i]);
  }
  index_rows(subset);
  return subset;
}

long& evaluations_on_this_thread() {
  thread_local long count = 0;
  return count;
}

bool residuals_at(const Setup& s, const Theta& theta, double* residuals, Eigen::MatrixXd* jacobian, std::string* why) {
  ++evaluations_on_this_thread();
  const std::vector<double> values = values_of(theta);
  std::vector<sediment::Wave> waves;
  std::vector<sediment::Wave> shear;
  if (!waves_at(s, values, jacobian != nullptr, waves, why, &shear)) return false;
  const auto n = static_cast<Eigen::Index>(values.size());
  if (jacobian) jacobian->setZero(static_cast<Eigen::Index>(s.residual_count), n);
  Eigen::VectorXd row(n);
  // The reflection groups' values (and their central differences) at once: they share media.
  std::vector<double> reflected;
  Eigen::MatrixXd d_reflected;
  if (!reflection_values_at(s, values, reflection_points_of_groups(s), reflected, why)) return false;
  if (jacobian && !reflection_derivatives_at(s, theta, d_reflected, why)) return false;
  Eigen::Index k = 0;
  std::size_t next_reflection = 0;
  for (const Setup::RowGroup& g : s.groups) {
    double total = g.data_sigma;
    if (is_reflection(g.quantity)) {
      residuals[k] = (reflected[next_reflection] - g.observed) / total;
      if (jacobian) row = d_reflected.row(static_cast<Eigen::Index>(next_reflection)).transpose() / total;
      ++next_reflection;
    } else {
      const sediment::Wave& w = (is_shear(g.quantity) ? shear : waves)[g.frequency];
      if (!whitened_residual(g.quantity, g.observed, g.data_sigma, w, values, residuals[k], jacobian ? row.data() : nullptr,
                             &total)) {
        return false;
      }
    }
    const double weight = g.count == 1.0 ? 1.0 : std::sqrt(g.count);
    residuals[k] *= weight;
    if (jacobian) jacobian->row(k) = weight * row;
    ++k;
    if (g.scatter > 0.0) {
      // The rows' scatter about their mean: what no parameter can change (the model's own sigma, which
      // may, is not differentiated, as in every residual).
      residuals[k++] = g.scatter / total;
    }
  }
  return true;
}

bool row_residuals_at(const Setup& s, const Theta& theta, double* residuals, std::string* why) {
  const std::vector<double> values = values_of(theta);
  std::vector<sediment::Wave> waves;
  std::vector<sediment::Wave> shear;
  if (!waves_at(s, values, false, waves, why, &shear)) return false;
  const std::vector<Setup::RowGroup> points = reflection_points_of_rows(s);
  std::vector<double> reflected;
  if (!reflection_values_at(s, values, points, reflected, why)) return false;
  std::size_t next_reflection = 0;
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    const Observation& o = s.observations[r];
    if (is_reflection(o.quantity)) {
      residuals[r] = (reflected[next_reflection++] - o.value) / s.sigmas[r];
      continue;
    }
    if (!whitened_residual(o, s.sigmas[r], (is_shear(o.quantity) ? shear : waves)[s.frequency_of[r]], values,
                           residuals[r], nullptr)) {
      return false;
    }
  }
  return true;
}

std::vector<double> predictions_at(const Setup& s, const Theta& theta) {
  std::vector<sediment::Wave> waves;
  std::vector<sediment::Wave> shear;
  std::string why;
  if (!waves_at(s, values_of(theta), false, waves, &why, &shear)) throw std::runtime_error(why);
  std::vector<double> out;
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    const Observation& o = s.observations[r];
    out.push_back(predicted_value(o, (is_shear(o.quantity) ? shear : waves)[s.frequency_of[r]]));
  }
  std::vector<double> reflected;
  if (!reflection_values_at(s, values_of(theta), reflection_points_of_rows(s), reflected, &why)) {
    throw std::runtime_error(why);
  }
  std::size_t next_reflection = 0;
  for (std::size_t r = 0; r < s.observations.size(); ++r) {
    if (is_reflection(s.observations[r].quantity)) out[r] = reflected[next_reflection++];
  }
  return out;
}

double chi2_at(const Setup& s, const Theta& theta) {
  std::vector<double> r(s.residual_count);
  if (!residuals_at(s, theta, r.data(), nullptr)) return std::numeric_limits<double>::infinity();
  double chi2 = 0.0;
  for (double x : r) chi2 += x * x;
  return std::isfinite(chi2) ? chi2 : std::numeric_limits<double>::infinity();
}

void build_problem(const Setup& s, Theta& theta, ceres::Problem& problem, int held, const Constraint* constraint) {
  const std::vector<double*> blocks = blocks_of(theta);
  problem.AddResidualBlock(new ObservationResiduals(s), nullptr, blocks);
  if (constraint) problem.AddResidualBlock(new ConstraintResidual(s, *constraint), nullptr, blocks);
  for (int i = 0; i < s.parameters.size(); ++i) {
    const ParameterSpec& spec = s.parameters.spec[i];
    if (!spec.free || i == held) {
      problem.SetParameterBlockConstant(&theta[i]);
      continue;
    }
    problem.SetParameterLowerBound(&theta[i], 0, log_lower(s, i));
    problem.SetParameterUpperBound(&theta[i], 0, log_upper(s, i));
  }
}

LocalFit solve_local(const Setup& s, Theta theta, int max_iterations, int held, const Constraint* constraint) {
  ceres::Problem problem;
  build_problem(s, theta, problem, held, constraint);
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

Eigen::MatrixXd whitened_jacobian(const Setup& s, const Theta& theta) {
  std::vector<double> r(s.residual_count);
  Eigen::MatrixXd all;
  std::string why = "a residual is not defined at the solution (a non-positive model attenuation)";
  if (!residuals_at(s, theta, r.data(), &all, &why)) throw std::runtime_error(why);
  Eigen::MatrixXd J(all.rows(), static_cast<Eigen::Index>(s.free.size()));
  for (std::size_t k = 0; k < s.free.size(); ++k) J.col(static_cast<Eigen::Index>(k)) = all.col(s.free[k]);
  if (!J.allFinite()) {
    throw std::runtime_error("the derivatives of model " + s.model->name() +
                             " are not finite at the fitted point; it cannot be analysed there");
  }
  return J;
}

/// Covariance of the free ln-parameters from ceres::Covariance; a pseudo-inverse when J^T J is
/// singular (eigenvalues below kRankTolerance^2 of the largest dropped).
Eigen::MatrixXd covariance(const Setup& s, Theta theta) {
  ceres::Problem problem;
  build_problem(s, theta, problem);
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.null_space_rank = -1;
  options.min_reciprocal_condition_number = kRankTolerance * kRankTolerance;
  options.num_threads = 1;
  ceres::Covariance solver(options);
  std::vector<const double*> blocks;
  for (int i : s.free) blocks.push_back(&theta[i]);
  const auto n = static_cast<Eigen::Index>(blocks.size());
  Eigen::MatrixXd result = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (!solver.Compute(blocks, &problem)) return result;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dense(n, n);
  solver.GetCovarianceMatrix(blocks, dense.data());
  return dense;
}

}  // namespace sedwave::inversion::detail
