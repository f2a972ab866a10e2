#include "sedwave/forward/table/table.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace sedwave::forward::table {
namespace {

void validate_axis(const std::vector<double>& axis, const char* name) {
  if (axis.empty()) throw std::invalid_argument(std::string("table grid: ") + name + " axis is empty");
  for (std::size_t i = 0; i < axis.size(); ++i) {
    if (!(axis[i] > 0.0) || !std::isfinite(axis[i])) {
      throw std::invalid_argument(std::string("table grid: ") + name + "[" + std::to_string(i) +
                                  "] must be positive and finite (interpolation works in logs)");
    }
    if (i > 0 && !(axis[i] > axis[i - 1])) {
      throw std::invalid_argument(std::string("table grid: ") + name + " must be strictly ascending at index " +
                                  std::to_string(i));
    }
  }
}

PointResult not_ok_point(PointStatus status, std::string reason, double wall_seconds) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  return {status, nan, nan, nan, nan, wall_seconds, std::move(reason)};
}

}  // namespace

void TableGrid::validate() const {
  validate_axis(omega_hat, "omega_hat");
  validate_axis(gamma_hat, "gamma_hat");
}

std::string_view to_string(PointStatus status) {
  switch (status) {
    case PointStatus::missing: return "missing";
    case PointStatus::ok: return "ok";
    case PointStatus::unresolved: return "unresolved";
    case PointStatus::failed: return "failed";
  }
  return "invalid";
}

PointResult unresolved_point(std::string reason, double wall_seconds) {
  return not_ok_point(PointStatus::unresolved, std::move(reason), wall_seconds);
}

PointResult failed_point(std::string reason, double wall_seconds) {
  return not_ok_point(PointStatus::failed, std::move(reason), wall_seconds);
}

std::string sigma_meaning(const TableMetadata& metadata) {
  const int n = metadata.packings;
  if (n == 1) {
    return "one packing: sigma is the measurement's own uncertainty and does NOT include "
           "packing-to-packing variation (docs/tables.md, \"What a table's sigma includes\")";
  }
  if (n >= 2) {
    return "standard error of the mean over " + std::to_string(n) +
           " independent packings: includes packing-to-packing variation";
  }
  return "not recorded (a closed form, or a table written before it was stored)";
}

std::string_view standard_definitions() {
  return "omega_hat = omega sqrt(m/kappa); gamma_hat = gamma / sqrt(kappa m); "
         "alpha_hat = alpha d [Np per grain diameter, amplitude ~ exp(-alpha x)]; "
         "c_hat = c / (d sqrt(kappa/m)); m = rho_s pi d^3 / 6; sigmas are 1-sigma; "
         "wall_seconds in s; 2D datasets are [n_gamma][n_omega]";
}

DispersionTable::DispersionTable(TableGrid grid, TableMetadata metadata)
    : grid_(std::move(grid)), metadata_(std::move(metadata)) {
  grid_.validate();
  points_.resize(grid_.size());
}

std::size_t DispersionTable::flat(std::size_t i_gamma, std::size_t i_omega) const {
  if (i_gamma >= n_gamma() || i_omega >= n_omega()) {
    throw std::out_of_range("table point (i_gamma=" + std::to_string(i_gamma) + ", i_omega=" +
                            std::to_string(i_omega) + ") outside a " + std::to_string(n_gamma()) + " x " +
                            std::to_string(n_omega()) + " grid");
  }
  return i_gamma * n_omega() + i_omega;
}

const PointResult& DispersionTable::at(std::size_t i_gamma, std::size_t i_omega) const {
  return points_[flat(i_gamma, i_omega)];
}

void DispersionTable::set(std::size_t i_gamma, std::size_t i_omega, PointResult result) {
  points_[flat(i_gamma, i_omega)] = std::move(result);
}

}  // namespace sedwave::forward::table
