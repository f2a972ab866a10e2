#include "sedwave/forward/linear/long_wavelength.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sedwave::forward::linear {
namespace {

using Complex = std::complex<double>;

/// The force of the free grains on the driven wall per unit wall displacement.
Eigen::Vector3cd force_on_driven_wall(const LinearChannel& c, const Eigen::VectorXcd& u,
                                      const channel::DriveSettings& d) {
  Eigen::Vector3cd total = Eigen::Vector3cd::Zero();
  for (const StaticPair& p : c.network().contacts) {
    const bool i_wall = c.grains()[static_cast<std::size_t>(p.i)].body == channel::kLowerWallBody;
    const bool j_wall = c.grains()[static_cast<std::size_t>(p.j)].body == channel::kLowerWallBody;
    if (i_wall == j_wall) continue;
    const Eigen::Vector3cd on_i = c.contact_force(u, d, p);
    total += i_wall ? on_i : Eigen::Vector3cd(-on_i);
  }
  return total;
}

}  // namespace

LongWavelengthLimit long_wavelength_limit(const LinearChannel& c, double x, channel::DriveAxis axis_kind) {
  if (!(x >= 0.0) || !std::isfinite(x)) throw std::invalid_argument("long-wavelength limit: x must be >= 0");
  if (c.fluid()) {
    // A fluid's dashpots do not scale with gamma: M would depend on omega_hat and gamma_hat apart.
    throw std::invalid_argument("long-wavelength limit: not defined with a pore fluid (its dashpots do not scale "
                                "with gamma, so the modulus is no function of omega_hat * gamma_hat alone)");
  }
  const auto start = std::chrono::steady_clock::now();
  const channel::PackingUnits& units = c.units();
  // A frequency at which the column is a thousandth of a wavelength (c_hat of a packing is O(1) and
  // grows with x): inertia changes the profile by ~(k L)^2 ~ 1e-6, yet the mass matrix still pins
  // grains the contacts leave free (rattlers) at zero.
  channel::DriveSettings d;
  d.axis = axis_kind;
  d.omega_hat = 1e-3 / units.column_length();
  d.gamma_hat = x / d.omega_hat;
  d.far_end = channel::FarEnd::absorbing;
  d.absorbing_strength = 0.0;  // no drag: the far wall is simply fixed
  const Eigen::VectorXcd u = c.displacement(d);
  const int axis = axis_kind == channel::DriveAxis::longitudinal ? 2 : 0;
  const Complex force = force_on_driven_wall(c, u, d)(axis);

  // Strain: least-squares slope of the displacement of every grain with a contact over the interior
  // 60 % of the column (rattlers have none and stay at rest). Density: their mass per volume.
  const std::vector<int>& contacts = c.network().contacts_per_grain;
  const DynamicMatrices& m = c.matrices();
  const double length = units.column_top - units.wall_surface;
  const double lo = units.wall_surface + 0.2 * length, hi = units.wall_surface + 0.8 * length;
  std::vector<double> z;
  std::vector<Complex> w;
  double mass = 0.0;
  for (std::size_t node = 0; node < m.grain_of_node.size(); ++node) {
    const auto g = static_cast<std::size_t>(m.grain_of_node[node]);
    if (contacts[g] == 0) continue;
    mass += c.grains()[g].mass;
    const double zg = c.grains()[g].position.z;
    if (zg < lo || zg > hi) continue;
    z.push_back(zg);
    w.push_back(u(m.dofs_per_node * static_cast<Eigen::Index>(node) + axis));
  }
  if (z.size() < 4) {
    throw std::invalid_argument("long-wavelength limit: fewer than 4 grains with contacts in the column's interior");
  }
  double z_mean = 0.0;
  Complex w_mean = 0.0;
  for (std::size_t k = 0; k < z.size(); ++k) {
    z_mean += z[k] / static_cast<double>(z.size());
    w_mean += w[k] / static_cast<double>(z.size());
  }
  double szz = 0.0;
  Complex szw = 0.0;
  for (std::size_t k = 0; k < z.size(); ++k) {
    szz += (z[k] - z_mean) * (z[k] - z_mean);
    szw += (z[k] - z_mean) * (w[k] - w_mean);
  }
  const Complex slope = szw / szz;
  double residual = 0.0;
  for (std::size_t k = 0; k < z.size(); ++k) residual += std::norm(w[k] - w_mean - slope * (z[k] - z_mean));

  LongWavelengthLimit r;
  r.x = x;
  // Compression (or shear) of the column pushes the wall back: stress -F / A, strain -slope.
  r.modulus = force / (c.cross_section() * slope) / (units.kappa / units.diameter);
  r.density = mass / (c.cross_section() * length) / (units.mass / std::pow(units.diameter, 3));
  const Complex inverse_speed = 1.0 / std::sqrt(r.modulus / r.density);
  r.alpha_over_omega = -inverse_speed.imag();
  r.c_hat = 1.0 / inverse_speed.real();
  r.non_affinity = std::sqrt(residual / static_cast<double>(z.size())) / std::abs(slope * (hi - lo));
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace sedwave::forward::linear
