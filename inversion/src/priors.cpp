#include "sedwave/inversion/priors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "short_number.hpp"

namespace sedwave::inversion {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

/// Standard normal CDF.
double phi(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

/// ln of the normal density N(x; mean, sd), truncated to [lo, hi].
double truncated_normal_log_density(double x, double mean, double sd, double lo, double hi) {
  const double mass = phi((hi - mean) / sd) - phi((lo - mean) / sd);
  const double z = (x - mean) / sd;
  return -0.5 * z * z - std::log(sd * std::sqrt(2.0 * std::numbers::pi)) - std::log(mass);
}

/// A draw from N(mean, sd^2) truncated to [lo, hi]: by the normal itself while that lands inside
/// often enough, else by a flat proposal on [lo, hi] under the density's maximum there. Both are
/// exact rejection samplers, so the draw follows the truncated normal whichever one ends.
double truncated_normal_draw(double mean, double sd, double lo, double hi, sampling::RandomStream& random) {
  for (int attempt = 0; attempt < 64; ++attempt) {
    const double x = mean + sd * random.normal();
    if (x >= lo && x <= hi) return x;
  }
  const double mode = std::clamp(mean, lo, hi);
  for (int attempt = 0; attempt < 1000000; ++attempt) {
    const double x = lo + (hi - lo) * random.uniform();
    const double log_ratio = (std::pow((mode - mean) / sd, 2) - std::pow((x - mean) / sd, 2)) / 2.0;
    if (std::log(random.uniform()) < log_ratio) return x;
  }
  throw std::invalid_argument("a normal prior truncated to its bounds has almost no mass there: widen the bounds "
                              "or move the prior");
}

}  // namespace

std::pair<double, double> Prior::support() const {
  const bool flat = kind == PriorKind::Uniform || kind == PriorKind::LogUniform;
  return {std::max(lower, flat ? a : lower), std::min(upper, flat ? b : upper)};
}

double Prior::log_density_theta(double theta) const {
  const double value = std::exp(theta);
  const auto [lo, hi] = support();
  // The support is tested in theta, where the fit's values live: exp(ln(bound)) may round to just
  // outside the bound, and a best fit on its bound must stay inside the prior.
  if (!(theta >= std::log(lo) && theta <= std::log(hi))) return kMinusInfinity;
  switch (kind) {
    case PriorKind::Uniform: return theta - std::log(hi - lo);  // p(v) = 1/(hi-lo), times v
    case PriorKind::LogUniform: return -std::log(std::log(hi / lo));
    case PriorKind::Normal: return truncated_normal_log_density(value, a, b, lo, hi) + theta;
    default: return truncated_normal_log_density(theta, std::log(a), b, std::log(lo), std::log(hi));
  }
}

double Prior::draw_theta(sampling::RandomStream& random) const {
  const auto [lo, hi] = support();
  switch (kind) {
    case PriorKind::Uniform: return std::log(lo + (hi - lo) * random.uniform());
    case PriorKind::LogUniform: return std::log(lo) + std::log(hi / lo) * random.uniform();
    case PriorKind::Normal: return std::log(truncated_normal_draw(a, b, lo, hi, random));
    default: return truncated_normal_draw(std::log(a), b, std::log(lo), std::log(hi), random);
  }
}

std::string Prior::describe_shape(const std::string& unit) const {
  const std::string u = unit == "1" ? "" : " " + unit;
  switch (kind) {
    case PriorKind::Uniform: return "uniform(" + short_number(a) + " .. " + short_number(b) + u + ")";
    case PriorKind::LogUniform:
      return "log-uniform(" + short_number(std::max(a, lower)) + " .. " + short_number(std::min(b, upper)) + u + ")";
    case PriorKind::Normal: return "normal(mean " + short_number(a) + u + ", sd " + short_number(b) + u + ")";
    default: return "log-normal(median " + short_number(a) + u + ", sd of ln " + short_number(b) + ")";
  }
}

std::string Prior::describe(const std::string& unit) const {
  return describe_shape(unit) + " on the bounds [" + short_number(lower) + ", " + short_number(upper) + "] (" +
         source + ")";
}

Prior default_prior(const ParameterSpec& spec) {
  return {PriorKind::LogUniform, spec.lower, spec.upper, "default", spec.lower, spec.upper};
}

Prior parse_prior(const std::string& text, const ParameterSpec& spec) {
  const std::string accepted = "accepted: uniform:A,B | log-uniform:A,B | normal:MEAN,SD | log-normal:MEDIAN,SD_LN";
  const auto colon = text.find(':');
  const auto comma = text.find(',', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || comma == std::string::npos) {
    throw std::invalid_argument("--prior " + spec.name + "=" + text + ": expected KIND:A,B (" + accepted + ")");
  }
  const std::string kind = text.substr(0, colon);
  Prior p{PriorKind::Uniform, 0.0, 0.0, "command line", spec.lower, spec.upper};
  if (kind == "uniform") p.kind = PriorKind::Uniform;
  else if (kind == "log-uniform") p.kind = PriorKind::LogUniform;
  else if (kind == "normal") p.kind = PriorKind::Normal;
  else if (kind == "log-normal") p.kind = PriorKind::LogNormal;
  else throw std::invalid_argument("--prior " + spec.name + "=" + text + ": unknown kind '" + kind + "' (" + accepted + ")");
  const auto read = [&](const std::string& s) {
    std::size_t used = 0;
    double x = std::numeric_limits<double>::quiet_NaN();
    try {
      x = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || !std::isfinite(x)) {
      throw std::invalid_argument("--prior " + spec.name + "=" + text + ": '" + s + "' is not a finite number");
    }
    return x;
  };
  p.a = read(text.substr(colon + 1, comma - colon - 1));
  p.b = read(text.substr(comma + 1));
  check_prior(p, spec, "--prior " + spec.name + "=" + text + ": ");
  return p;
}

void check_prior(const Prior& p, const ParameterSpec& spec, const std::string& where) {
  const bool flat = p.kind == PriorKind::Uniform || p.kind == PriorKind::LogUniform;
  if (flat && !(p.a < p.b)) throw std::invalid_argument(where + "needs A < B");
  if (flat && (p.b <= spec.lower || p.a >= spec.upper)) {
    throw std::invalid_argument(where + "[A, B] does not meet the search bounds [" + short_number(spec.lower) + ", " +
                                short_number(spec.upper) + "] " + spec.unit);
  }
  if (p.kind == PriorKind::LogUniform && !(p.a > 0.0)) throw std::invalid_argument(where + "needs A > 0");
  if (!flat && !(p.b > 0.0)) throw std::invalid_argument(where + "the sd must be positive");
  if (p.kind == PriorKind::LogNormal && !(p.a > 0.0)) throw std::invalid_argument(where + "the median must be positive");
}

std::vector<Prior> default_priors(const FitParameters& parameters) {
  std::vector<Prior> priors;
  for (const ParameterSpec& s : parameters.spec) priors.push_back(default_prior(s));
  return priors;
}

void apply_priors(const FitParameters& parameters, const std::vector<std::string>& items, const std::string& source,
                  std::vector<Prior>& priors) {
  std::set<std::string> seen;
  for (const std::string& item : items) {
    const auto at = item.find('=');
    if (at == std::string::npos) throw std::invalid_argument("--prior '" + item + "': expected NAME=KIND:A,B");
    const std::string name = item.substr(0, at);
    const int i = parameters.index_of(name);
    if (!parameters.spec[i].free) {
      throw std::invalid_argument("--prior '" + item + "': " + name + " is fixed; name it in --fit to give it a prior");
    }
    if (!seen.insert(name).second) throw std::invalid_argument("--prior names '" + name + "' twice");
    Prior p = parse_prior(item.substr(at + 1), parameters.spec[i]);
    p.source = source;
    priors[i] = p;
  }
}

std::vector<Prior> make_priors(const FitParameters& parameters, const std::vector<std::string>& items) {
  std::vector<Prior> priors = default_priors(parameters);
  apply_priors(parameters, items, "command line", priors);
  return priors;
}

double log_prior(const FitParameters& parameters, const std::vector<Prior>& priors, const std::vector<double>& theta) {
  double sum = 0.0;
  for (int i : parameters.free_indices()) sum += priors[i].log_density_theta(theta[i]);
  return sum;
}

}  // namespace sedwave::inversion
