#include "sedwave/forward/table/table_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>

#include "hermite_surface.hpp"
#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward::table {
namespace {

std::string str(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::vector<double> logs(const std::vector<double>& values) {
  std::vector<double> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = std::log(values[i]);
  return out;
}

void require_usable(const PointResult& p, std::size_t i_gamma, std::size_t i_omega) {
  const auto where = " at (i_gamma=" + std::to_string(i_gamma) + ", i_omega=" + std::to_string(i_omega) + ")";
  if (!(p.alpha_hat > 0.0) || !std::isfinite(p.alpha_hat) || !(p.c_hat > 0.0) || !std::isfinite(p.c_hat)) {
    throw std::invalid_argument("table point" + where + " is ok but alpha_hat=" + str(p.alpha_hat) +
                                ", c_hat=" + str(p.c_hat) + ": ok values must be positive and finite");
  }
  if (!(p.sigma_alpha_hat >= 0.0) || !std::isfinite(p.sigma_alpha_hat) || !(p.sigma_c_hat >= 0.0) ||
      !std::isfinite(p.sigma_c_hat)) {
    throw std::invalid_argument("table point" + where + " has a negative or non-finite sigma");
  }
}

/// The lattice theory where a correction table needs it: positive and finite, or the reason it is not.
bool theory_usable(const DispersionPoint& t) {
  return t.alpha_hat > 0.0 && std::isfinite(t.alpha_hat) && t.c_hat > 0.0 && std::isfinite(t.c_hat) &&
         std::isfinite(t.d_alpha_hat.d_omega_hat) && std::isfinite(t.d_alpha_hat.d_gamma_hat) &&
         std::isfinite(t.d_c_hat.d_omega_hat) && std::isfinite(t.d_c_hat.d_gamma_hat);
}

}  // namespace

/// Everything evaluate() needs, built once from the table.
struct TableModel::Interpolant {
  std::vector<double> log_omega, log_gamma;
  std::vector<bool> usable;  // row-major [i_gamma][i_omega]
  HermiteSurface log_alpha, log_c;
  std::vector<double> relative_sigma_alpha, relative_sigma_c;

  static Interpolant build(const DispersionTable& table, Interpolation interpolation) {
    const std::size_t n = table.grid().size();
    std::vector<bool> usable(n);
    std::vector<double> log_alpha(n, 0.0), log_c(n, 0.0), rel_alpha(n, 0.0), rel_c(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t g = k / table.n_omega(), w = k % table.n_omega();
      const PointResult& p = table.at(g, w);
      usable[k] = p.status == PointStatus::ok;
      if (!usable[k]) continue;
      require_usable(p, g, w);
      log_alpha[k] = std::log(p.alpha_hat);
      log_c[k] = std::log(p.c_hat);
      if (interpolation == Interpolation::correction) {
        const double omega_hat = table.grid().omega_hat[w], gamma_hat = table.grid().gamma_hat[g];
        const DispersionPoint t = LatticeModel().evaluate(omega_hat, gamma_hat);
        if (!theory_usable(t)) {
          throw std::invalid_argument(
              "table point (omega_hat=" + str(omega_hat) + ", gamma_hat=" + str(gamma_hat) +
              ") is ok but the lattice theory has no positive, finite value there (alpha_hat=" + str(t.alpha_hat) +
              ", c_hat=" + str(t.c_hat) +
              "; an undamped chain at or below its band edge, or an underflow): interpolate=correction "
              "divides the table by the theory; use interpolate=direct for this table");
        }
        log_alpha[k] -= std::log(t.alpha_hat);
        log_c[k] -= std::log(t.c_hat);
      }
      rel_alpha[k] = p.sigma_alpha_hat / p.alpha_hat;
      rel_c[k] = p.sigma_c_hat / p.c_hat;
    }
    std::vector<double> x = logs(table.grid().omega_hat), y = logs(table.grid().gamma_hat);
    HermiteSurface alpha(x, y, std::move(log_alpha), usable);
    HermiteSurface c(x, y, std::move(log_c), usable);
    return {std::move(x), std::move(y), std::move(usable), std::move(alpha), std::move(c), std::move(rel_alpha),
            std::move(rel_c)};
  }

  /// The first corner of the cell that is not ok, if any (as a flat index).
  [[nodiscard]] std::optional<std::size_t> unusable_corner(const GridCell& cell) const {
    const std::size_t nx = log_omega.size();
    for (const std::size_t iy : {cell.y.lower, cell.y.upper}) {
      for (const std::size_t ix : {cell.x.lower, cell.x.upper}) {
        if (!usable[iy * nx + ix]) return iy * nx + ix;
      }
    }
    return std::nullopt;
  }
};

TableModel::TableModel(DispersionTable table, std::string name, OutsideTable outside, Interpolation interpolation)
    : table_(std::move(table)),
      name_(std::move(name)),
      outside_(outside),
      interpolation_(interpolation),
      interpolant_(std::make_shared<const Interpolant>(Interpolant::build(table_, interpolation_))) {
  if (outside_ == OutsideTable::long_wavelength && (table_.n_omega() < 2 || table_.n_gamma() < 2)) {
    throw std::invalid_argument(name_ + ": the long-wavelength extrapolation needs at least two omega_hat and two "
                                "gamma_hat in the table");
  }
}

std::string TableModel::file_of(std::string_view spec) {
  constexpr std::string_view prefix = "table:";
  if (!spec.starts_with(prefix)) throw std::invalid_argument("not a table model specification: '" + std::string(spec) + "'");
  return std::string(spec.substr(prefix.size(), spec.find('?') - prefix.size()));
}

std::unique_ptr<TableModel> TableModel::from_spec(std::string_view spec) {
  constexpr std::string_view prefix = "table:";
  const std::string path = file_of(spec);
  spec.remove_prefix(prefix.size());
  const std::size_t question = spec.find('?');
  OutsideTable outside = OutsideTable::error;
  Interpolation interpolation = Interpolation::direct;
  if (question != std::string_view::npos) {
    constexpr std::string_view accepted =
        " (accepted, joined by '&', each at most once: extrapolate=none, extrapolate=theory, "
        "extrapolate=long-wavelength, interpolate=direct, interpolate=correction)";
    std::string_view options = spec.substr(question + 1);
    bool have_extrapolate = false, have_interpolate = false;
    while (true) {
      const std::size_t amp = options.find('&');
      const std::string_view option = options.substr(0, amp);
      bool* seen = option.starts_with("extrapolate=")   ? &have_extrapolate
                   : option.starts_with("interpolate=") ? &have_interpolate
                                                        : nullptr;
      if (seen != nullptr && *seen) {
        throw std::invalid_argument("table model option '" + std::string(option.substr(0, option.find('='))) +
                                    "' given twice in '" + std::string(spec) + "'" + std::string(accepted));
      }
      if (option == "extrapolate=none") {
        outside = OutsideTable::error;
      } else if (option == "extrapolate=theory") {
        outside = OutsideTable::lattice_theory;
      } else if (option == "extrapolate=long-wavelength") {
        outside = OutsideTable::long_wavelength;
      } else if (option == "interpolate=direct") {
        interpolation = Interpolation::direct;
      } else if (option == "interpolate=correction") {
        interpolation = Interpolation::correction;
      } else {
        throw std::invalid_argument("table model option '" + std::string(option) + "' not understood" +
                                    std::string(accepted));
      }
      *seen = true;
      if (amp == std::string_view::npos) break;
      options.remove_prefix(amp + 1);
    }
  }
  if (path.empty()) throw std::invalid_argument("table model needs a file: table:FILE.h5");
  return std::make_unique<TableModel>(read_table(path), "table:" + path, outside, interpolation);
}

std::vector<ModelDiagnostic> TableModel::diagnostics() const {
  const std::uint64_t fallbacks = fallback_count(), extrapolated = extrapolated_count();
  return {
      {"table_fallback_evaluations", fallbacks,
       fallbacks > 0
           ? std::to_string(fallbacks) + " model evaluations fell outside the table and used the 1D lattice theory"
           : std::string()},
      {"table_long_wavelength_evaluations", extrapolated,
       extrapolated > 0 ? std::to_string(extrapolated) + " model evaluations lay below the table's resolved omega_hat "
                                                         "and used its long-wavelength limit (docs/tables.md)"
                        : std::string()},
      // A table's fluid groups are fixed while the fit varies kappa and d: the fit describes a
      // sediment only where mu d / sqrt(kappa m) at the fitted values is the table's mu_hat.
      {"table_pore_fluid", table_.metadata().pore_fluid.empty() ? 0u : 1u,
       table_.metadata().pore_fluid.empty()
           ? std::string()
           : "the table was computed in a pore fluid (" + table_.metadata().pore_fluid +
                 "), fixed while the fit varies kappa and d: check that mu d / sqrt(kappa m) at the fitted values "
                 "matches its mu_hat (docs/fluid.md)"},
  };
}

DispersionPoint TableModel::evaluate(double omega_hat, double gamma_hat) const {
  std::string why;
  if (const auto p = inside(omega_hat, gamma_hat, why)) return *p;
  if (outside_ == OutsideTable::long_wavelength && omega_hat > 0.0 && gamma_hat > 0.0) {
    if (const auto p = long_wavelength(omega_hat, gamma_hat, why)) return *p;
  }
  return outside(omega_hat, gamma_hat, why);
}

std::optional<DispersionPoint> TableModel::inside(double omega_hat, double gamma_hat, std::string& why) const {
  const Interpolant& in = *interpolant_;
  const auto x = omega_hat > 0.0 ? locate(in.log_omega, std::log(omega_hat)) : std::nullopt;
  const auto y = gamma_hat > 0.0 ? locate(in.log_gamma, std::log(gamma_hat)) : std::nullopt;
  if (!x || !y) {
    why = "is outside the table";
    return std::nullopt;
  }
  const GridCell cell{*x, *y};
  if (const auto corner = in.unusable_corner(cell)) {
    const std::size_t g = *corner / table_.n_omega(), w = *corner % table_.n_omega();
    const PointResult& p = table_.at(g, w);
    why = "falls in a cell whose corner (omega_hat=" + str(table_.grid().omega_hat[w]) +
          ", gamma_hat=" + str(table_.grid().gamma_hat[g]) + ") is " + std::string(to_string(p.status)) +
          (p.reason.empty() ? "" : " (" + p.reason + ")");
    return std::nullopt;
  }
  return sample(cell, omega_hat, gamma_hat);
}

DispersionPoint TableModel::sample(const GridCell& cell, double omega_hat, double gamma_hat, bool held_x,
                                   bool held_y) const {
  const Interpolant& in = *interpolant_;
  // Interpolated in logs: alpha = exp(L), so d alpha / d omega_hat = alpha dL/d ln(omega_hat) / omega_hat.
  // A correction surface C multiplies the theory T: alpha = T exp(C), d alpha = exp(C) dT + alpha dC.
  SurfaceSample a = in.log_alpha(cell);
  SurfaceSample c = in.log_c(cell);
  if (held_x) a.d_x = c.d_x = 0.0;
  if (held_y) a.d_y = c.d_y = 0.0;
  DispersionPoint p;
  p.alpha_hat = std::exp(a.value);
  p.c_hat = std::exp(c.value);
  p.d_alpha_hat = {p.alpha_hat * a.d_x / omega_hat, p.alpha_hat * a.d_y / gamma_hat};
  p.d_c_hat = {p.c_hat * c.d_x / omega_hat, p.c_hat * c.d_y / gamma_hat};
  if (interpolation_ == Interpolation::correction) {
    const DispersionPoint t = LatticeModel().evaluate(omega_hat, gamma_hat);
    if (!theory_usable(t)) {
      throw std::domain_error(name_ + ": (omega_hat=" + str(omega_hat) + ", gamma_hat=" + str(gamma_hat) +
                              ") the lattice theory has no positive, finite value here (alpha_hat=" +
                              str(t.alpha_hat) + ", c_hat=" + str(t.c_hat) + "), so interpolate=correction cannot "
                              "add it back");
    }
    const double ka = p.alpha_hat, kc = p.c_hat;  // exp(C)
    p.alpha_hat = t.alpha_hat * ka;
    p.c_hat = t.c_hat * kc;
    p.d_alpha_hat = {ka * t.d_alpha_hat.d_omega_hat + p.alpha_hat * a.d_x / omega_hat,
                     ka * t.d_alpha_hat.d_gamma_hat + p.alpha_hat * a.d_y / gamma_hat};
    p.d_c_hat = {kc * t.d_c_hat.d_omega_hat + p.c_hat * c.d_x / omega_hat,
                 kc * t.d_c_hat.d_gamma_hat + p.c_hat * c.d_y / gamma_hat};
  }
  p.sigma_alpha_hat = p.alpha_hat * bilinear(cell, in.relative_sigma_alpha, in.log_omega.size());
  p.sigma_c_hat = p.c_hat * bilinear(cell, in.relative_sigma_c, in.log_omega.size());
  return p;
}

std::optional<DispersionPoint> TableModel::held_correction(double omega_hat, double gamma_hat) const {
  const Interpolant& in = *interpolant_;
  if (!(omega_hat > 0.0) || !(gamma_hat > 0.0) || !std::isfinite(omega_hat) || !std::isfinite(gamma_hat)) {
    return std::nullopt;
  }
  const double lx = std::log(omega_hat), ly = std::log(gamma_hat);
  const double cx = std::clamp(lx, in.log_omega.front(), in.log_omega.back());
  const double cy = std::clamp(ly, in.log_gamma.front(), in.log_gamma.back());
  const auto x = locate(in.log_omega, cx);
  const auto y = locate(in.log_gamma, cy);
  if (!x || !y) return std::nullopt;
  const GridCell cell{*x, *y};
  if (in.unusable_corner(cell)) return std::nullopt;
  return sample(cell, omega_hat, gamma_hat, cx != lx, cy != ly);
}

std::optional<DispersionPoint> TableModel::long_wavelength(double omega_hat, double gamma_hat, std::string& why) const {
  // The images of the point on columns k and k + 1: the table's points at the same
  // x = omega_hat gamma_hat, alpha_hat scaled by omega_hat / w. Column k is the lowest above the point
  // where both images are resolved (a channel resolves less of the low-omega_hat end as x and with it
  // the wavelength grows, so the table's usable edge is ragged).
  const std::vector<double>& columns = table_.grid().omega_hat;
  const double x = omega_hat * gamma_hat;
  std::string first_miss;
  for (std::size_t k = 0; k + 1 < columns.size(); ++k) {
    const double w0 = columns[k], w1 = columns[k + 1];
    if (w0 <= omega_hat) continue;
    std::string miss;
    const auto p0 = inside(w0, x / w0, miss);
    const auto p1 = p0 ? inside(w1, x / w1, miss) : std::nullopt;
    if (!p0 || !p1) {
      if (first_miss.empty()) {
        first_miss = "; its long-wavelength image (omega_hat=" + str(p0 ? w1 : w0) + ", gamma_hat=" + str(x / (p0 ? w1 : w0)) +
                     ") " + miss + ", and no higher column resolves both images";
      }
      continue;
    }
    const double s0 = omega_hat / w0, s1 = omega_hat / w1;
    // With g0 = x / w0: d g0 / d omega_hat = gamma_hat / w0, d g0 / d gamma_hat = s0.
    const double dg_dw = gamma_hat / w0;
    DispersionPoint p;
    p.alpha_hat = s0 * p0->alpha_hat;
    p.c_hat = p0->c_hat;
    p.d_alpha_hat = {p0->alpha_hat / w0 + s0 * p0->d_alpha_hat.d_gamma_hat * dg_dw, s0 * p0->d_alpha_hat.d_gamma_hat * s0};
    p.d_c_hat = {p0->d_c_hat.d_gamma_hat * dg_dw, p0->d_c_hat.d_gamma_hat * s0};
    // The distance of column k from the limit, if it shrinks like omega_hat^2 (the leading correction
    // of a lattice's dispersion): the images differ by D = f1 - f0, and f0 - f(0) = D w0^2 / (w1^2 - w0^2).
    const double to_limit = w0 * w0 / (w1 * w1 - w0 * w0);
    p.sigma_alpha_hat = std::hypot(s0 * p0->sigma_alpha_hat, to_limit * (s1 * p1->alpha_hat - p.alpha_hat));
    p.sigma_c_hat = std::hypot(p0->sigma_c_hat, to_limit * (p1->c_hat - p.c_hat));
    extrapolated_.fetch_add(1, std::memory_order_relaxed);
    return p;
  }
  why += first_miss.empty() ? "; no column above it to take a long-wavelength image from" : first_miss;
  return std::nullopt;
}

DispersionPoint TableModel::outside(double omega_hat, double gamma_hat, const std::string& why) const {
  if (outside_ == OutsideTable::lattice_theory) {
    fallbacks_.fetch_add(1, std::memory_order_relaxed);
    if (interpolation_ == Interpolation::correction) {
      if (const auto p = held_correction(omega_hat, gamma_hat)) return *p;
    }
    return LatticeModel().evaluate(omega_hat, gamma_hat);
  }
  const TableGrid& grid = table_.grid();
  // Field data sit far below a driven table's omega_hat (0.3 mm sand at 10 kHz: omega_hat ~ 1e-2):
  // name the table that covers them rather than an extrapolation.
  const std::string make_instead =
      omega_hat < grid.omega_hat.front()
          ? "; for omega_hat this low make a long-wavelength table, e.g. `sedwave table "
            "data/scenes/field_w3_long_wavelength.toml --engine long_wavelength --packing "
            "data/tables/field_w3.packing.h5 --out TABLE.h5` (docs/tables.md, \"Field frequencies\")"
          : "";
  throw std::domain_error(name_ + ": (omega_hat=" + str(omega_hat) + ", gamma_hat=" + str(gamma_hat) + ") " + why +
                          "; the table covers omega_hat in [" + str(grid.omega_hat.front()) + ", " +
                          str(grid.omega_hat.back()) + "], gamma_hat in [" + str(grid.gamma_hat.front()) + ", " +
                          str(grid.gamma_hat.back()) + "]" + make_instead);
}

}  // namespace sedwave::forward::table

namespace sedwave::forward::table {

double TableModel::long_wavelength_c_hat() const {
  for (std::size_t w = 0; w < table_.n_omega(); ++w) {
    for (std::size_t g = 0; g < table_.n_gamma(); ++g) {
      const PointResult& p = table_.at(g, w);
      if (p.status == PointStatus::ok) return p.c_hat;
    }
  }
  throw std::domain_error("table " + name_ + " has no ok point");
}

std::string TableModel::uncertainty_caveat() const {
  const TableMetadata& m = table_.metadata();
  if (m.packings == 1) {
    return "table '" + name_ + "' was computed on one packing: its sigma leaves out packing-to-packing " +
           "variation (for W = 3 channels of 10^4 grains about 1-2 % in c_hat and 1-25 % in alpha_hat), so " +
           "every interval is too narrow; make the table over an ensemble of packings (docs/tables.md, " +
           "\"What a table's sigma includes\")";
  }
  if (m.packings == 0 && m.engine.starts_with("sedwave-")) {
    return "table '" + name_ + "' does not record how many packings its sigma spans (" + m.engine +
           ", written before this was stored): packing-to-packing variation may be missing from it";
  }
  return {};
}

}  // namespace sedwave::forward::table
