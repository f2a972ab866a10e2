#pragma once
// Prior distributions of a model's parameters: what a user knows before the data.
//
// Kinds (values in the parameter's SI unit):
//   uniform:A,B        flat in the value on [A, B]
//   log-uniform:A,B    flat in ln(value) on [A, B] (scale-free: each decade as likely)
//   normal:MEAN,SD     Gaussian in the value (truncated to the search bounds)
//   log-normal:MEDIAN,SD_LN   Gaussian in ln(value) with median MEDIAN and sd SD_LN of ln(value)
// A parameter without a prior gets the default: log-uniform over its search bounds (broad but
// physical: the bounds lie inside its physical range).
//
// The fit and the sampler work in theta = ln(value), so every density here is returned in theta:
// p(theta) = p(value) * value (the Jacobian of value = e^theta). Densities are normalised over the
// search bounds, so a log evidence can use them.
#include <string>
#include <utility>
#include <vector>

#include "sedwave/inversion/parameters.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::inversion {

enum class PriorKind { Uniform, LogUniform, Normal, LogNormal };

struct Prior {
  PriorKind kind = PriorKind::LogUniform;
  double a = 0.0;  ///< lower end, mean or median [unit]
  double b = 0.0;  ///< upper end [unit], sd [unit] (normal) or sd of ln(value) (log-normal)
  std::string source = "default";  ///< "default", "command line", or what derived it
  double lower = 0.0;  ///< support: the search bounds [unit]
  double upper = 0.0;

  /// ln p(theta) at theta = ln(value), normalised over [lower, upper]; -inf outside the support.
  [[nodiscard]] double log_density_theta(double theta) const;
  /// One independent draw of theta = ln(value) from exactly that density (rejection sampling).
  [[nodiscard]] double draw_theta(sampling::RandomStream& random) const;
  /// Where the density is non-zero [unit]: the search bounds, narrowed by a flat prior's own ends.
  [[nodiscard]] std::pair<double, double> support() const;
  /// The distribution alone, e.g. "log-normal(median 8.2e4 N/m, sd of ln 0.5)".
  [[nodiscard]] std::string describe_shape(const std::string& unit) const;
  /// One line, e.g. "log-normal(median 8.2e4 N/m, sd_ln 0.5) on [1e3, 1e7] (command line)".
  [[nodiscard]] std::string describe(const std::string& unit) const;
};

/// The default prior of a parameter: log-uniform over its search bounds.
[[nodiscard]] Prior default_prior(const ParameterSpec& spec);

/// "KIND:A,B" for a parameter (its spec gives the support and unit). Throws std::invalid_argument
/// naming the option text, the kind and the accepted forms; refuses a prior whose support does not
/// meet the search bounds, a non-positive sd, or A >= B for the flat kinds.
[[nodiscard]] Prior parse_prior(const std::string& text, const ParameterSpec& spec);

/// Throws std::invalid_argument starting with `where` unless `prior` is usable on the search bounds of
/// `spec`: A < B and [A, B] meeting the bounds for the flat kinds, A > 0 for the logarithmic ones, a
/// positive sd for the others.
void check_prior(const Prior& prior, const ParameterSpec& spec, const std::string& where);

/// One default prior per parameter of `parameters` (fixed ones included, unused).
[[nodiscard]] std::vector<Prior> default_priors(const FitParameters& parameters);

/// "NAME=KIND:A,B" items replace the priors of their parameters, recorded with `source`. Throws
/// std::invalid_argument for an unknown name, one named twice, or a prior on a fixed parameter.
void apply_priors(const FitParameters& parameters, const std::vector<std::string>& items, const std::string& source,
                  std::vector<Prior>& priors);

/// default_priors, then the command line's items.
[[nodiscard]] std::vector<Prior> make_priors(const FitParameters& parameters, const std::vector<std::string>& items);

/// Sum of the free parameters' ln p(theta_i) (independent priors).
[[nodiscard]] double log_prior(const FitParameters& parameters, const std::vector<Prior>& priors,
                               const std::vector<double>& theta);

}  // namespace sedwave::inversion
