#include "sedwave/forward/experiment/time_domain_points.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sedwave::forward::experiment {

table::PointResult point_from_acoustic(const channel::AcousticResult& result) {
  const channel::PropagationFit& fit = result.fit;
  // A point whose windows still hold a decaying transient after every extension is biased by more
  // than the steadiness tolerance: a table must not interpolate through it. The count goes up front
  // ("not steady after N ...: <the halves' values>"): a table cell keeps 159 bytes of a reason.
  std::string problem = result.problem;
  if (problem.empty() && !result.warning.empty()) {
    constexpr std::string_view kHead = "not steady";
    problem = result.warning;
    const std::string count = " after " + std::to_string(result.extensions) + " extension(s) of the run";
    if (problem.starts_with(kHead)) problem.insert(kHead.size(), count);
    else problem += count;
  }
  return table::point_from_measurement(problem, fit.alpha, fit.sigma_alpha, fit.c, fit.sigma_c, result.wall_seconds);
}

std::vector<std::vector<double>> pulse_bands(const std::vector<double>& omega_hats) {
  std::vector<std::vector<double>> bands;
  for (const double w : omega_hats) {
    if (bands.empty() || w > kPulseBandRatio * bands.back().front()) bands.emplace_back();
    bands.back().push_back(w);
  }
  return bands;
}

table::PointFunction dem_point_function(const channel::PreparedChannel& packing, const dem::ContactSpec& contact,
                                 const channel::DriveSettings& drive, const table::TableGrid& grid) {
  if (!drive.pulse) {
    return [&packing, &contact, &drive](MPI_Comm group, double omega_hat, double gamma_hat) {
      channel::DriveSettings point_drive = drive;
      point_drive.omega_hat = omega_hat;
      point_drive.gamma_hat = gamma_hat;
      return point_from_acoustic(channel::run_acoustic(group, packing, contact, point_drive));
    };
  }
  // The last pulse run of this group, kept for the next points of its band.
  struct LastPulse {
    double gamma_hat = std::numeric_limits<double>::quiet_NaN();
    std::size_t band = 0;
    channel::AcousticResult run;
  };
  auto last = std::make_shared<LastPulse>();
  auto bands = std::make_shared<const std::vector<std::vector<double>>>(pulse_bands(grid.omega_hat));
  return [&packing, &contact, &drive, last, bands](MPI_Comm group, double omega_hat, double gamma_hat) {
    std::size_t band = 0;
    while (band < bands->size() && std::find((*bands)[band].begin(), (*bands)[band].end(), omega_hat) == (*bands)[band].end()) ++band;
    if (band == bands->size()) throw std::invalid_argument("pulse table: omega_hat " + std::to_string(omega_hat) + " is not on the grid");
    if (!(last->gamma_hat == gamma_hat && last->band == band)) {
      const std::vector<double>& frequencies = (*bands)[band];
      channel::DriveSettings d = drive;
      d.gamma_hat = gamma_hat;
      channel::PulseBand pulse = *drive.pulse;  // its shape (pulse or chirp); the band is the grid's
      // A band of one frequency still needs a width: +-25 % around it.
      pulse.omega_hat_min = frequencies.size() > 1 ? frequencies.front() : frequencies.front() / 1.25;
      pulse.omega_hat_max = frequencies.size() > 1 ? frequencies.back() : frequencies.back() * 1.25;
      pulse.frequencies = static_cast<int>(frequencies.size());
      pulse.measured = frequencies;
      d.pulse = pulse;
      last->gamma_hat = std::numeric_limits<double>::quiet_NaN();  // stays unset if the run throws
      last->run = channel::run_acoustic(group, packing, contact, d);
      last->gamma_hat = gamma_hat;
      last->band = band;
    }
    for (const channel::SpectralResult& p : last->run.spectrum) {
      if (p.omega_hat == omega_hat) {
        return table::point_from_measurement(p.problem, p.fit.alpha, p.fit.sigma_alpha, p.fit.c, p.fit.sigma_c,
                                      last->run.wall_seconds);
      }
    }
    return table::point_from_measurement(last->run.problem.empty() ? "the pulse run measured no spectrum" : last->run.problem,
                                  0.0, 0.0, 0.0, 0.0, last->run.wall_seconds);
  };
}

}  // namespace sedwave::forward::experiment
