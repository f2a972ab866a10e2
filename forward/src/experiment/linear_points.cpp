#include "sedwave/forward/experiment/linear_points.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "sedwave/forward/linear/long_wavelength.hpp"
#include "sedwave/io/fingerprint.hpp"

namespace sedwave::forward::experiment {

using namespace linear;  // the points are the linear engine's results

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

std::string member_engine_tag(int k, int n) {
  return "sedwave-linear (member " + std::to_string(k) + " of " + std::to_string(n) + ")";
}

table::PointFunction member_point_function(const LinearChannel& member, const channel::DriveSettings& drive) {
  return [&member, &drive](MPI_Comm, double omega_hat, double gamma_hat) {
    channel::DriveSettings point_drive = drive;
    point_drive.omega_hat = omega_hat;
    point_drive.gamma_hat = gamma_hat;
    const LinearResult r = member.respond(point_drive);
    const channel::PropagationFit& f = r.fit;
    const bool finite = std::isfinite(f.alpha) && std::isfinite(f.sigma_alpha) && std::isfinite(f.c) &&
                        std::isfinite(f.sigma_c) && f.c > 0.0;
    if (!r.ok()) return table::unresolved_point(r.problem, r.solve_seconds);
    if (!finite) return table::unresolved_point("the propagation fit gave no finite alpha_hat and c_hat", r.solve_seconds);
    return table::PointResult{table::PointStatus::ok, f.alpha, f.c, f.sigma_alpha, f.sigma_c, r.solve_seconds, {}};
  };
}

namespace {

/// (k, n) of a member table's engine tag, or nothing.
std::optional<std::pair<int, int>> member_of(const std::string& engine) {
  int k = -1, n = -1;
  char end = 0;
  if (std::sscanf(engine.c_str(), "sedwave-linear (member %d of %d%c", &k, &n, &end) != 3 || end != ')') return std::nullopt;
  if (k < 0 || n < 1 || k >= n || member_engine_tag(k, n) != engine) return std::nullopt;
  return std::make_pair(k, n);
}

}  // namespace

table::DispersionTable merge_member_tables(std::span<const table::DispersionTable> members,
                                           std::span<const std::string> names) {
  if (members.empty() || members.size() != names.size()) throw std::invalid_argument("merge: no member tables");
  const table::DispersionTable& first = members.front();
  std::set<int> seen;
  std::map<int, std::string> packing_hashes;  // by member index, so in member order
  int ensemble = 0;
  for (std::size_t m = 0; m < members.size(); ++m) {
    const table::DispersionTable& t = members[m];
    const auto tag = member_of(t.metadata().engine);
    if (!tag) {
      throw std::invalid_argument("merge: " + names[m] + " is not a member table (engine '" + t.metadata().engine +
                                  "'; make one with sedwave table --member K)");
    }
    if (m == 0) ensemble = tag->second;
    if (tag->second != ensemble) throw std::invalid_argument("merge: " + names[m] + " belongs to an ensemble of " +
                                                             std::to_string(tag->second) + ", " + names[0] + " to one of " +
                                                             std::to_string(ensemble));
    if (!seen.insert(tag->first).second) {
      throw std::invalid_argument("merge: " + names[m] + " is member " + std::to_string(tag->first) + " again");
    }
    packing_hashes[tag->first] = t.metadata().packing_hash;
    if (!(t.grid() == first.grid())) throw std::invalid_argument("merge: " + names[m] + " has another grid than " + names[0]);
    if (t.metadata().scene_toml != first.metadata().scene_toml) {
      throw std::invalid_argument("merge: " + names[m] + " was computed from another scene than " + names[0]);
    }
    std::size_t missing = 0;
    for (std::size_t g = 0; g < t.n_gamma(); ++g)
      for (std::size_t w = 0; w < t.n_omega(); ++w) missing += t.at(g, w).status == table::PointStatus::missing ? 1 : 0;
    if (missing > 0) {
      throw std::invalid_argument("merge: " + names[m] + " has " + std::to_string(missing) +
                                  " points still missing; finish it first (rerun its sedwave table command)");
    }
  }
  table::TableMetadata metadata = first.metadata();
  metadata.engine = "sedwave-linear";
  metadata.code_version.clear();
  // As `sedwave table` records an ensemble computed in one run: a hash of the members' hashes, in order.
  std::vector<std::string> hashes;
  for (const auto& [k, hash] : packing_hashes) hashes.push_back(hash);
  metadata.packing_hash = io::combined_fingerprint(hashes);
  metadata.packings = static_cast<int>(seen.size());
  std::string which;
  for (const int k : seen) which += (which.empty() ? "" : ", ") + std::to_string(k);
  metadata.definitions += "\nMerged by sedwave merge: mean and standard error over members " + which + " of " +
                          std::to_string(ensemble) + " (member k: the scene's seed + k).";
  table::DispersionTable out(first.grid(), metadata);
  for (std::size_t g = 0; g < out.n_gamma(); ++g) {
    for (std::size_t w = 0; w < out.n_omega(); ++w) {
      std::vector<double> alpha, c;
      double seconds = 0.0;
      std::string problem;
      for (std::size_t m = 0; m < members.size(); ++m) {
        const table::PointResult& p = members[m].at(g, w);
        seconds += p.wall_seconds;
        if (p.status != table::PointStatus::ok && problem.empty()) problem = p.reason;
        alpha.push_back(p.alpha_hat);
        c.push_back(p.c_hat);
      }
      if (!problem.empty()) {
        out.set(g, w, table::unresolved_point(problem, seconds));
        continue;
      }
      const MeanAndError a = mean_and_standard_error(alpha), v = mean_and_standard_error(c);
      const bool single = members.size() == 1;
      const table::PointResult& only = members.front().at(g, w);
      out.set(g, w, table::point_from_measurement("", a.mean, single ? only.sigma_alpha_hat : a.standard_error, v.mean,
                                                  single ? only.sigma_c_hat : v.standard_error, seconds));
    }
  }
  return out;
}


table::PointFunction long_wavelength_point_function(const std::vector<LinearChannel>& members,
                                                    channel::DriveAxis axis) {
  // Every point on a diagonal of a log grid with equal steps on both axes has the same x: solve each
  // x once (keyed to 1e-9 in ln x, far below any grid's spacing).
  auto solved = std::make_shared<std::map<long long, std::vector<LongWavelengthLimit>>>();
  return [&members, axis, solved](MPI_Comm, double omega_hat, double gamma_hat) {
    const double x = omega_hat * gamma_hat;
    const long long key = x > 0.0 ? std::llround(std::log(x) * 1e9) : std::numeric_limits<long long>::min();
    auto [entry, fresh] = solved->try_emplace(key);
    if (fresh) {
      for (const LinearChannel& member : members) entry->second.push_back(long_wavelength_limit(member, x, axis));
    }
    std::vector<double> alpha, c;
    double seconds = 0.0;
    for (const LongWavelengthLimit& l : entry->second) {
      alpha.push_back(omega_hat * l.alpha_over_omega);
      c.push_back(l.c_hat);
      if (fresh) seconds += l.solve_seconds;
    }
    const MeanAndError a = mean_and_standard_error(alpha), v = mean_and_standard_error(c);
    return table::point_from_measurement(members.empty() ? "empty ensemble" : "", a.mean, a.standard_error, v.mean,
                                         v.standard_error, seconds);
  };
}

}  // namespace sedwave::forward::experiment
