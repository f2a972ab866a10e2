#pragma once
// The dimensionless units of a prepared channel and where its walls are. Every engine that drives
// a packing (time-domain DEM, linear response) measures in the same units (docs/physics.md):
// lengths in the mean flow-grain diameter d, masses in the mass m of a grain of diameter d (at the
// packing's mean density), stiffness in kappa, so times are in sqrt(m/kappa).
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/dem/fluid.hpp"

namespace sedwave::forward::channel {

struct PackingUnits {
  double diameter = 1.0;      ///< d: mean flow-grain diameter
  double mass = 1.0;          ///< m: mass of a grain of diameter d
  double kappa = 1.0;         ///< contact stiffness (Hooke: kn; Hertz: mean tangent stiffness)
  /// The contact law's damping coefficient per unit gamma_hat: Hooke sqrt(kappa m) (gamma = gamma_hat
  /// sqrt(kappa m) on every contact); Hertz-Tsuji sqrt(kappa m) / (mean Tsuji factor), so the mean
  /// contact's dashpot is gamma_hat sqrt(kappa m).
  double damping_scale = 1.0;
  double wall_surface = 0.0;  ///< z of the driven (lower) wall's mean surface
  double column_top = 0.0;    ///< z of the far (upper) wall's mean surface
  /// 1 - flow-grain volume / (cross-section x column length between the walls' mean surfaces)
  double porosity = 0.0;
  [[nodiscard]] double time() const { return std::sqrt(mass / kappa); }
  [[nodiscard]] double column_length() const { return (column_top - wall_surface) / diameter; }  ///< [d]
};

/// Layers: slabs of equal thickness along z from the driven wall's surface, into which flow grains
/// are grouped for layer-averaged (coherent) displacements. The last layer ends at or below the far
/// wall's surface; a grain beyond either end counts in the nearest layer.
struct LayerGrid {
  double origin = 0.0;     ///< z of the driven wall's surface [length]
  double thickness = 1.0;  ///< [length]
  double thickness_in_diameters = 1.0;
  int count = 1;

  LayerGrid(const PackingUnits& u, double thickness_d)
      : origin(u.wall_surface), thickness(thickness_d * u.diameter), thickness_in_diameters(thickness_d),
        count(std::max(1, static_cast<int>(std::floor((u.column_top - u.wall_surface) / thickness)))) {}
  [[nodiscard]] int index(double z) const {
    return std::clamp(static_cast<int>(std::floor((z - origin) / thickness)), 0, count - 1);
  }
  /// Layer centres [mean diameters from the driven wall's surface]: the z of the layer fits.
  [[nodiscard]] std::vector<double> centres() const {
    std::vector<double> z;
    for (int k = 0; k < count; ++k) z.push_back((k + 0.5) * thickness_in_diameters);
    return z;
  }
};

/// What a static packing's contacts give: means over its contacts of the tangent normal stiffness
/// and of the dashpot per unit damping coefficient, and the grains' static force on the upper wall
/// along z (what holds it in place). Collective over comm; the grains may be spread over its ranks
/// in any way: on one rank from its contact network (find_contacts), else from a DEM force
/// evaluation, whose ghosts see the pairs across ranks (the two agree to round-off).
struct StaticContacts {
  double mean_stiffness = 0.0;
  double mean_dashpot = 0.0;
  double upper_wall_force = 0.0;
};
[[nodiscard]] StaticContacts static_contacts(MPI_Comm comm, const PreparedChannel& packing,
                                             const dem::ContactSpec& contact);

/// Whether packing_units needs the static contacts: a normal law without a single stiffness (Hertz).
[[nodiscard]] bool units_need_static_contacts(const dem::ContactSpec& contact);

/// Units of `packing` (its grains spread over the ranks of comm in any way; collective). kappa is the Hooke kn, or
/// for Hertz (no single stiffness) the mean tangent stiffness of the static contacts: `known` when
/// the caller has them (static_contacts of the same packing and contact law), else found here.
/// Throws parallel::AgreedFailure on every rank when the packing has no flow grains, lacks a wall, or
/// (Hertz) has no contacts.
[[nodiscard]] PackingUnits packing_units(MPI_Comm comm, const PreparedChannel& packing, const dem::ContactSpec& contact,
                                         const StaticContacts* known = nullptr);

/// A pore fluid given in the packing's dimensionless groups (as scene files give it) in the
/// packing's own units: viscosity mu_hat = mu d / sqrt(kappa m), roughness and cutoff in d, density
/// as rho_f / rho_s (rho_s = 6 m / (pi d^3), the density of the grain that defines m). A porosity
/// of 0 stands for the packing's own (PackingUnits::porosity).
[[nodiscard]] dem::FluidSpec fluid_in_packing_units(const dem::FluidSpec& dimensionless, const PackingUnits& u);
/// The dimensionless groups in one line, e.g. "mu_hat 5e-06, roughness 0.001 d, cutoff 0.05 d,
/// lubrication, drag richardson_zaki (porosity of the packing)".
[[nodiscard]] std::string describe_fluid_groups(const dem::FluidSpec& dimensionless);

}  // namespace sedwave::forward::channel
