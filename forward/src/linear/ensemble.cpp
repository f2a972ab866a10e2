#include "sedwave/forward/linear/ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sedwave::forward::linear {

EnsembleResult respond(const std::vector<LinearChannel>& members, const channel::DriveSettings& drive) {
  EnsembleResult e;
  for (const LinearChannel& member : members) {
    e.members.push_back(member.respond(drive));
    const LinearResult& r = e.members.back();
    e.solve_seconds += r.solve_seconds;
    if (e.problem.empty() && !r.ok()) e.problem = r.problem;
    if (e.warning.empty()) e.warning = r.warning;
    e.reflection = std::max(e.reflection, r.waves.reflection);
  }
  if (!e.ok() || e.members.empty()) {
    if (e.members.empty()) e.problem = "empty ensemble";
    return e;
  }
  std::vector<double> alpha, c;
  for (const LinearResult& r : e.members) {
    alpha.push_back(r.fit.alpha);
    c.push_back(r.fit.c);
  }
  const MeanAndError a = mean_and_standard_error(alpha), v = mean_and_standard_error(c);
  e.alpha_hat = a.mean;
  e.c_hat = v.mean;
  if (e.members.size() == 1) {  // a single member keeps its own fit errors
    e.sigma_alpha_hat = e.members.front().fit.sigma_alpha;
    e.sigma_c_hat = e.members.front().fit.sigma_c;
  } else {
    e.sigma_alpha_hat = a.standard_error;
    e.sigma_c_hat = v.standard_error;
  }
  return e;
}

MeanAndError mean_and_standard_error(std::span<const double> values) {
  MeanAndError r;
  const auto n = static_cast<double>(values.size());
  for (const double v : values) r.mean += v / n;
  if (values.size() < 2) return r;
  double variance = 0.0;
  for (const double v : values) variance += (v - r.mean) * (v - r.mean) / (n - 1.0);
  r.standard_error = std::sqrt(variance / n);
  return r;
}

}  // namespace sedwave::forward::linear
