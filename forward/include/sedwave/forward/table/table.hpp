#pragma once
// A dispersion table in memory: alpha_hat and c_hat measured (by the DEM channel, or computed by a
// theory) on a grid of omega_hat x gamma_hat, with uncertainties, a status per point and the
// metadata needed to reproduce it. Files: table_file.hpp; interpolation: table_model.hpp;
// format and accuracy: docs/tables.md.
//
// Units: everything is dimensionless (docs/physics.md): omega_hat = omega sqrt(m/kappa),
// gamma_hat = gamma / sqrt(kappa m), alpha_hat = alpha d [Np per grain diameter],
// c_hat = c / (d sqrt(kappa/m)); wall times are seconds.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/forward/spacing.hpp"

namespace sedwave::forward::table {

/// The grid: strictly ascending, positive, finite values (interpolation works in their logs).
struct TableGrid {
  std::vector<double> omega_hat;
  std::vector<double> gamma_hat;

  [[nodiscard]] std::size_t size() const { return omega_hat.size() * gamma_hat.size(); }
  /// Throws std::invalid_argument unless both axes are non-empty, positive, finite and ascending.
  void validate() const;
  friend bool operator==(const TableGrid&, const TableGrid&) = default;
};

using forward::log_spaced;  // a grid's axes are log-spaced (spacing.hpp)

/// Where a table point stands. The numeric codes are part of the file format.
enum class PointStatus : std::int8_t {
  missing = 0,     ///< not computed yet
  ok = 1,          ///< values and sigmas valid
  unresolved = 2,  ///< the channel length or run time cannot resolve it; values NaN, reason says why
  failed = 3,      ///< the computation failed; values NaN, reason says why
};

[[nodiscard]] std::string_view to_string(PointStatus status);

/// The result at one grid point.
struct PointResult {
  PointStatus status = PointStatus::missing;
  double alpha_hat = 0.0;
  double c_hat = 0.0;
  double sigma_alpha_hat = 0.0;
  double sigma_c_hat = 0.0;
  double wall_seconds = 0.0;  ///< time spent computing the point [s]
  std::string reason;         ///< why a point is unresolved or failed (empty when ok)
};

/// A finished point that is not ok: NaN values, the reason kept.
[[nodiscard]] PointResult unresolved_point(std::string reason, double wall_seconds = 0.0);
[[nodiscard]] PointResult failed_point(std::string reason, double wall_seconds = 0.0);

/// Provenance stored with a table.
struct TableMetadata {
  std::string scene_toml;    ///< the scene file the points were computed from, verbatim
  std::string engine;        ///< what computed the points, e.g. "sedwave-dem" or "lattice-theory"
  std::string code_version;  ///< sedwave version; filled in on write when empty
  std::string definitions;   ///< units and definitions; filled in on write when empty
  /// Hash of the packing(s) every point starts from (io::Fingerprint); empty where none, or in
  /// tables written before it was recorded. A resumed table must start from the same packing.
  std::string packing_hash;
  /// Independent packings the per-point sigma spans: 1 = one packing, whose sigma is the
  /// measurement's own uncertainty and leaves out packing-to-packing variation; n >= 2 = the
  /// standard error of the mean over n packings, which includes it; 0 = a closed form or not
  /// recorded (tables written before it was stored). sigma_meaning() says it in words.
  int packings = 0;
  /// The pore fluid of the scene's drive in its dimensionless groups (docs/fluid.md), one line;
  /// empty for a dry table (or one written before it was recorded).
  std::string pore_fluid{};

  friend bool operator==(const TableMetadata&, const TableMetadata&) = default;
};

/// What a table's sigma includes, in words (stored beside `packings` as the attribute sigma_includes).
[[nodiscard]] std::string sigma_meaning(const TableMetadata& metadata);

/// The text stored as TableMetadata::definitions by default.
[[nodiscard]] std::string_view standard_definitions();

/// Index of a grid point.
struct GridIndex {
  std::size_t i_gamma = 0;
  std::size_t i_omega = 0;
  friend bool operator==(const GridIndex&, const GridIndex&) = default;
};

/// Grid, metadata and one PointResult per grid point (row-major: [i_gamma][i_omega]).
class DispersionTable {
 public:
  /// All points start missing. Validates the grid.
  DispersionTable(TableGrid grid, TableMetadata metadata);

  [[nodiscard]] const TableGrid& grid() const { return grid_; }
  [[nodiscard]] const TableMetadata& metadata() const { return metadata_; }
  [[nodiscard]] std::size_t n_omega() const { return grid_.omega_hat.size(); }
  [[nodiscard]] std::size_t n_gamma() const { return grid_.gamma_hat.size(); }

  /// Bounds-checked access (std::out_of_range).
  [[nodiscard]] const PointResult& at(std::size_t i_gamma, std::size_t i_omega) const;
  void set(std::size_t i_gamma, std::size_t i_omega, PointResult result);

 private:
  [[nodiscard]] std::size_t flat(std::size_t i_gamma, std::size_t i_omega) const;

  TableGrid grid_;
  TableMetadata metadata_;
  std::vector<PointResult> points_;
};

}  // namespace sedwave::forward::table
