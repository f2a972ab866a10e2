#pragma once
// An ensemble of independently generated packings driven alike: a single disordered channel
// scatters, so alpha_hat and c_hat are the ensemble mean with the standard error of the mean
// (from the spread between packings, which includes each member's own fit error). With one member
// the member's own fit errors are kept.
#include <span>
#include <string>
#include <vector>

#include "sedwave/forward/linear/linear_channel.hpp"

namespace sedwave::forward::linear {

struct EnsembleResult {
  std::vector<LinearResult> members;
  double alpha_hat = 0.0, sigma_alpha_hat = 0.0;
  double c_hat = 0.0, sigma_c_hat = 0.0;
  double reflection = 0.0;  ///< largest over the members (absorbing layer's reflection coefficient)
  std::string warning;      ///< the first member warning, if any
  std::string problem;      ///< a member's problem (then nothing was measured)
  double solve_seconds = 0.0;
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

/// The mean of one number over the members and its standard error (the spread between members over
/// sqrt(n); 0 for a single member).
struct MeanAndError {
  double mean = 0.0;
  double standard_error = 0.0;
};
[[nodiscard]] MeanAndError mean_and_standard_error(std::span<const double> values);

/// Drives every member with `drive` and combines the results.
[[nodiscard]] EnsembleResult respond(const std::vector<LinearChannel>& members, const channel::DriveSettings& drive);

}  // namespace sedwave::forward::linear
