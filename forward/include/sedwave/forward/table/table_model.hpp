#pragma once
// A forward model that interpolates a dispersion table (docs/tables.md).
//
// Interpolation: ln alpha_hat and ln c_hat as functions of (ln omega_hat, ln gamma_hat) by a bicubic
// Hermite surface whose node slopes come from three-point finite differences (exact for quadratics,
// so power laws alpha_hat ~ omega_hat^p gamma_hat^q are reproduced exactly). The surface is C1
// everywhere, which Ceres needs, and local: a noisy point moves only the cells around it. The
// derivatives returned are the exact derivatives of the interpolant, converted to d/d omega_hat and
// d/d gamma_hat of alpha_hat and c_hat. Sigmas: the relative sigma (sigma/value) is interpolated
// bilinearly in the same log coordinates (not differentiated: the residuals treat it as a constant).
//
// Points that are not ok (unresolved, failed, missing) act like the table's edge: their cells are
// outside. A table with a single gamma_hat (or omega_hat) interpolates along the other axis only and
// accepts only that gamma_hat (its d/d gamma_hat is 0).
//
// Outside the table: std::domain_error naming the point and the table's range, or (options)
//  - the lattice theory, counted by fallback_count(). The theory is not matched to the table at its
//    edge, so a fit that wanders outside sees a jump: the report should say how often that happened;
//  - below the table's resolved omega_hat, its long-wavelength limit, counted by extrapolated_count().
//    When the wavelength is many grains, no grain's inertia matters inside a wavelength: the packing
//    acts as a continuum whose complex modulus is a function of K + i omega C, and since every
//    dashpot is gamma times a fixed matrix, of omega * gamma alone. So alpha_hat / omega_hat and
//    c_hat depend on x = omega_hat * gamma_hat only (exact for the 1D continuum theory). The model
//    therefore answers (omega_hat, gamma_hat) below the table from its image on the lowest column w0
//    above omega_hat that resolves the same x:
//      alpha_hat = (omega_hat / w0) alpha_table(w0, x / w0),  c_hat = c_table(w0, x / w0).
//    How far the table's lowest column still is from that limit is estimated, not assumed: the same
//    mapping from the next column, w1, gives a second estimate f1, and if the distance shrinks like
//    omega_hat^2 (a lattice's dispersion does), column 0 lies (f1 - f0) w0^2 / (w1^2 - w0^2) from the
//    limit. That is added to the sigmas in quadrature (on the lattice theory the true miss is 0.5-1.7
//    of it). The value is continuous where the table ends, its gradient is not; where the column
//    used changes (a ragged edge), the value jumps by about that sigma.
//
// Interpolation::correction (spec option interpolate=correction) uses the 1D lattice theory as a
// surrogate: the same Hermite surface interpolates the correction ln(alpha_table / alpha_lattice),
// ln(c_table / c_lattice) instead of the logs themselves, and the theory's exact values and
// derivatives at the query point are added back. A table that follows the theory up to a smooth
// factor is then interpolated far better than directly (the theory carries the crossover and the
// band edge), and a table of the theory itself is reproduced to round-off. Every ok point needs a
// positive, finite lattice value (refused otherwise). Outside the table with extrapolate=theory,
// a correction model answers the theory times the correction held at the nearest point of the
// table's range (continuous at the edge; counted by fallback_count()); where that edge point's cell
// has a non-ok corner, the bare theory as with direct interpolation.
//
// Units: dimensionless throughout (dispersion.hpp). Thread-safe: evaluate() only reads.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/forward/dispersion.hpp"
#include "sedwave/forward/table/table.hpp"

namespace sedwave::forward::table {

struct GridCell;  // a cell of the interpolation grid (private to the implementation)

/// What to do at a point the table does not cover.
enum class OutsideTable {
  error,           ///< throw std::domain_error
  lattice_theory,  ///< evaluate the 1D lattice theory instead and count it
  long_wavelength, ///< below the resolved omega_hat: the table's continuum limit (above); else error
};

/// What the Hermite surface interpolates.
enum class Interpolation {
  direct,      ///< ln alpha_hat, ln c_hat of the table
  correction,  ///< ln(table / lattice theory) of both; the theory's exact values are added back
};

class TableModel final : public DispersionModel {
 public:
  /// Throws std::invalid_argument if an ok point has a value that is not positive and finite, or a
  /// sigma that is negative or not finite.
  /// With Interpolation::correction, also throws std::invalid_argument if the lattice theory has no
  /// positive, finite alpha_hat or c_hat at an ok point.
  TableModel(DispersionTable table, std::string name, OutsideTable outside = OutsideTable::error,
             Interpolation interpolation = Interpolation::direct);

  /// From a command-line specification "table:FILE" or "table:FILE?OPTION&OPTION" with options
  /// extrapolate=none|theory|long-wavelength and interpolate=direct|correction, each at most once.
  [[nodiscard]] static std::unique_ptr<TableModel> from_spec(std::string_view spec);
  /// The file such a specification names ("table:FILE.h5?..." gives FILE.h5).
  [[nodiscard]] static std::string file_of(std::string_view spec);

  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] DispersionPoint evaluate(double omega_hat, double gamma_hat) const override;
  /// The table's c_hat at its lowest omega_hat and, there, its lowest gamma_hat with an ok point:
  /// the closest the table comes to the static limit (its lattice dispersion there is ~omega_hat^2).
  [[nodiscard]] double long_wavelength_c_hat() const override;
  /// Non-empty for a table of one packing (its sigma leaves out packing-to-packing variation) and
  /// for an engine-made table that does not record how many packings its sigma spans.
  [[nodiscard]] std::string uncertainty_caveat() const override;
  /// fallback_count() and extrapolated_count(), each with a note when it is not zero.
  [[nodiscard]] std::vector<ModelDiagnostic> diagnostics() const override;

  /// How many evaluations fell back to the lattice theory so far.
  [[nodiscard]] std::uint64_t fallback_count() const { return fallbacks_.load(std::memory_order_relaxed); }
  /// How many evaluations used the long-wavelength limit so far.
  [[nodiscard]] std::uint64_t extrapolated_count() const { return extrapolated_.load(std::memory_order_relaxed); }
  [[nodiscard]] const DispersionTable& table() const { return table_; }
  [[nodiscard]] Interpolation interpolation() const { return interpolation_; }

 private:
  struct Interpolant;

  /// The interpolant inside the table, or nothing and the reason the table does not cover the point.
  [[nodiscard]] std::optional<DispersionPoint> inside(double omega_hat, double gamma_hat, std::string& why) const;
  /// The long-wavelength limit (above), or nothing and why appended to `why`.
  [[nodiscard]] std::optional<DispersionPoint> long_wavelength(double omega_hat, double gamma_hat, std::string& why) const;
  [[nodiscard]] DispersionPoint outside(double omega_hat, double gamma_hat, const std::string& why) const;
  /// The surfaces at a cell whose corners are ok, converted to values, derivatives and sigmas; the
  /// surfaces' derivatives along an axis flagged `held` are left out (the correction held there).
  [[nodiscard]] DispersionPoint sample(const GridCell& cell, double omega_hat, double gamma_hat, bool held_x = false,
                                       bool held_y = false) const;
  /// Correction model outside the table: the theory times the correction at the nearest point of the
  /// table's range, or nothing if that point's cell has a non-ok corner.
  [[nodiscard]] std::optional<DispersionPoint> held_correction(double omega_hat, double gamma_hat) const;

  DispersionTable table_;
  std::string name_;
  OutsideTable outside_;
  Interpolation interpolation_;
  std::shared_ptr<const Interpolant> interpolant_;
  mutable std::atomic<std::uint64_t> fallbacks_{0};
  mutable std::atomic<std::uint64_t> extrapolated_{0};
};

}  // namespace sedwave::forward::table
