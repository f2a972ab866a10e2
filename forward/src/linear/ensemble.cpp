#include "sedwave/forward/linear/ensemble.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

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
  const auto n = static_cast<double>(e.members.size());
  for (const LinearResult& r : e.members) {
    e.alpha_hat += r.fit.alpha / n;
    e.c_hat += r.fit.c / n;
  }
  if (e.members.size() == 1) {
    e.sigma_alpha_hat = e.members.front().fit.sigma_alpha;
    e.sigma_c_hat = e.members.front().fit.sigma_c;
    return e;
  }
  double var_alpha = 0.0, var_c = 0.0;
  for (const LinearResult& r : e.members) {
    var_alpha += (r.fit.alpha - e.alpha_hat) * (r.fit.alpha - e.alpha_hat) / (n - 1.0);
    var_c += (r.fit.c - e.c_hat) * (r.fit.c - e.c_hat) / (n - 1.0);
  }
  e.sigma_alpha_hat = std::sqrt(var_alpha / n);
  e.sigma_c_hat = std::sqrt(var_c / n);
  return e;
}

table::PointResult point_from_ensemble(const EnsembleResult& e) {
  return table::point_from_measurement(e.problem, e.alpha_hat, e.sigma_alpha_hat, e.c_hat, e.sigma_c_hat,
                                       e.solve_seconds);
}

table::PointFunction linear_point_function(const std::vector<LinearChannel>& members,
                                           const channel::DriveSettings& drive) {
  return [&members, &drive](MPI_Comm, double omega_hat, double gamma_hat) {
    channel::DriveSettings point_drive = drive;
    point_drive.omega_hat = omega_hat;
    point_drive.gamma_hat = gamma_hat;
    return point_from_ensemble(respond(members, point_drive));
  };
}

}  // namespace sedwave::forward::linear
