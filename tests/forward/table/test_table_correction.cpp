// The table model's correction scheme (interpolate=correction): the lattice theory as a surrogate,
// the table interpolated as a smooth correction to it. Truths are closed forms: the lattice theory
// itself, and the theory times a known smooth factor.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "../derivative_check.hpp"
#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/forward/table/table_file.hpp"
#include "sedwave/forward/table/table_model.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward::table {
namespace {

namespace fs = std::filesystem;

TableMetadata metadata() { return {"", "lattice-theory-times-factor", "", "", ""}; }

/// ln of a smooth factor (not a polynomial in the logs, so interpolating it has a genuine error).
double log_factor(double omega_hat, double gamma_hat) {
  const double x = std::log(omega_hat), y = std::log(gamma_hat);
  return 0.1 * x + 0.05 * y + 0.08 * std::sin(0.7 * x) * std::cos(0.4 * y);
}

/// The lattice theory times exp(scale * log_factor) on alpha_hat and exp(0.5 scale * log_factor) on
/// c_hat, with a 1 % sigma.
DispersionTable factor_table(const TableGrid& grid, double scale) {
  DispersionTable table(grid, metadata());
  for (std::size_t g = 0; g < table.n_gamma(); ++g) {
    for (std::size_t w = 0; w < table.n_omega(); ++w) {
      const double omega = grid.omega_hat[w], gamma = grid.gamma_hat[g];
      const DispersionPoint t = LatticeModel().evaluate(omega, gamma);
      const double f = log_factor(omega, gamma);
      const double alpha = t.alpha_hat * std::exp(scale * f), c = t.c_hat * std::exp(0.5 * scale * f);
      table.set(g, w, {PointStatus::ok, alpha, c, 0.01 * alpha, 0.01 * c, 1.0, ""});
    }
  }
  return table;
}

/// Random points strictly inside the grid's range, log-uniform.
std::vector<std::pair<double, double>> interior_points(const TableGrid& grid, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto between = [&](const std::vector<double>& axis) { return axis.front() * std::pow(axis.back() / axis.front(), u(rng)); };
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i < n; ++i) points.emplace_back(between(grid.omega_hat), between(grid.gamma_hat));
  return points;
}

double relative(double a, double b) { return std::abs(a / b - 1.0); }

// A table of the lattice theory has correction 0: the correction scheme returns the theory itself,
// values and derivatives, anywhere inside, also across the undamped band edge omega_hat = 2.
TEST(TableCorrection, ReproducesATheoryTableToRoundOff) {
  const TableGrid grid{log_spaced(1e-3, 3.0, 9), log_spaced(1e-2, 1e2, 5)};  // deliberately coarse
  const TableModel model(factor_table(grid, 0.0), "theory", OutsideTable::error, Interpolation::correction);
  const TableModel direct(factor_table(grid, 0.0), "theory");
  double worst = 0.0, worst_gradient = 0.0, worst_direct = 0.0;
  for (const auto& [w, g] : interior_points(grid, 2000, 7)) {
    const DispersionPoint p = model.evaluate(w, g), t = LatticeModel().evaluate(w, g);
    worst = std::max({worst, relative(p.alpha_hat, t.alpha_hat), relative(p.c_hat, t.c_hat)});
    worst_gradient = std::max({worst_gradient, std::abs(p.d_alpha_hat.d_omega_hat - t.d_alpha_hat.d_omega_hat) * w / t.alpha_hat,
                               std::abs(p.d_alpha_hat.d_gamma_hat - t.d_alpha_hat.d_gamma_hat) * g / t.alpha_hat,
                               std::abs(p.d_c_hat.d_omega_hat - t.d_c_hat.d_omega_hat) * w / t.c_hat,
                               std::abs(p.d_c_hat.d_gamma_hat - t.d_c_hat.d_gamma_hat) * g / t.c_hat});
    worst_direct = std::max(worst_direct, relative(direct.evaluate(w, g).alpha_hat, t.alpha_hat));
    EXPECT_NEAR(p.sigma_alpha_hat / p.alpha_hat, 0.01, 1e-14);
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_gradient, 1e-12);
  EXPECT_GT(worst_direct, 1e-2);  // the grid is coarse: directly interpolated it is far off
}

// The theory times a smooth factor: the correction scheme only has to interpolate the factor, the
// direct scheme also the theory's crossover at omega_hat gamma_hat ~ 1 and its dispersion.
TEST(TableCorrection, BeatsDirectInterpolationOnACoarseGrid) {
  const TableGrid grid{log_spaced(1e-3, 1.5, 11), log_spaced(1e-2, 1e2, 9)};  // 3.2 x 2 points per decade
  const DispersionTable table = factor_table(grid, 1.0);
  const TableModel correction(table, "t", OutsideTable::error, Interpolation::correction);
  const TableModel direct(table, "t");
  double err_correction = 0.0, err_direct = 0.0;
  for (const auto& [w, g] : interior_points(grid, 3000, 11)) {
    const DispersionPoint t = LatticeModel().evaluate(w, g);
    const double f = log_factor(w, g);
    const double alpha = t.alpha_hat * std::exp(f), c = t.c_hat * std::exp(0.5 * f);
    const DispersionPoint a = correction.evaluate(w, g), b = direct.evaluate(w, g);
    err_correction = std::max({err_correction, relative(a.alpha_hat, alpha), relative(a.c_hat, c)});
    err_direct = std::max({err_direct, relative(b.alpha_hat, alpha), relative(b.c_hat, c)});
  }
  std::printf("theory x smooth factor, 11 x 9 grid: max relative error direct %.2e, correction %.2e (ratio %.0f)\n",
              err_direct, err_correction, err_direct / err_correction);
  EXPECT_LT(err_correction, 2e-3);
  EXPECT_GT(err_direct / err_correction, 20.0);

  // A factor that is a plane in the logs (a power law) is reproduced exactly.
  DispersionTable plane(grid, metadata());
  for (std::size_t g = 0; g < grid.gamma_hat.size(); ++g) {
    for (std::size_t w = 0; w < grid.omega_hat.size(); ++w) {
      const double omega = grid.omega_hat[w], gamma = grid.gamma_hat[g];
      const DispersionPoint t = LatticeModel().evaluate(omega, gamma);
      const double k = std::exp(0.1 * std::log(omega) + 0.05 * std::log(gamma));
      plane.set(g, w, {PointStatus::ok, t.alpha_hat * k, t.c_hat, 0.0, 0.0, 1.0, ""});
    }
  }
  const TableModel plane_model(std::move(plane), "plane", OutsideTable::error, Interpolation::correction);
  double worst = 0.0;
  for (const auto& [w, g] : interior_points(grid, 500, 3)) {
    const double exact = LatticeModel().evaluate(w, g).alpha_hat * std::exp(0.1 * std::log(w) + 0.05 * std::log(g));
    worst = std::max(worst, relative(plane_model.evaluate(w, g).alpha_hat, exact));
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(TableCorrection, DerivativesMatchCentralDifferences) {
  const TableGrid grid{log_spaced(1e-3, 3.0, 15), log_spaced(1e-2, 1e2, 9)};
  const TableModel model(factor_table(grid, 1.0), "t", OutsideTable::error, Interpolation::correction);
  for (const std::size_t w : {0u, 5u, 9u, 12u, 13u}) {  // 12, 13: around and above the band edge
    for (const std::size_t g : {0u, 4u, 7u}) {
      const double omega = grid.omega_hat[w] * std::pow(grid.omega_hat[w + 1] / grid.omega_hat[w], 0.37);
      const double gamma = grid.gamma_hat[g] * std::pow(grid.gamma_hat[g + 1] / grid.gamma_hat[g], 0.61);
      testing::expect_gradients_match_finite_differences(model, omega, gamma, 1e-7);
    }
  }
}

// Outside the table with extrapolate=theory: the theory times the correction held at the nearest
// point of the table's range, continuous at the edge; the bare theory where that point is unresolved.
TEST(TableCorrection, OutsideHoldsTheCorrectionAtTheEdge) {
  const TableGrid grid{log_spaced(0.01, 1.0, 9), log_spaced(0.1, 10.0, 5)};
  DispersionTable table = factor_table(grid, 1.0);
  const TableModel model(table, "t", OutsideTable::lattice_theory, Interpolation::correction);
  const LatticeModel theory;
  const double w0 = grid.omega_hat.front(), g_node = grid.gamma_hat[2], g_top = grid.gamma_hat.back();
  // Below the table at a gamma_hat node: the theory times the factor at (w0, gamma_hat).
  const DispersionPoint below = model.evaluate(1e-4, g_node);
  EXPECT_NEAR(below.alpha_hat / (theory.evaluate(1e-4, g_node).alpha_hat * std::exp(log_factor(w0, g_node))), 1.0, 1e-13);
  EXPECT_NEAR(below.c_hat / (theory.evaluate(1e-4, g_node).c_hat * std::exp(0.5 * log_factor(w0, g_node))), 1.0, 1e-13);
  EXPECT_NEAR(below.sigma_alpha_hat / below.alpha_hat, 0.01, 1e-14);
  // Beyond a corner both coordinates are held: the factor of the corner.
  const DispersionPoint corner = model.evaluate(1e-4, 1e3);
  EXPECT_NEAR(corner.alpha_hat / (theory.evaluate(1e-4, 1e3).alpha_hat * std::exp(log_factor(w0, g_top))), 1.0, 1e-13);
  EXPECT_EQ(model.fallback_count(), 2u);
  // Continuous across the edge (the direct scheme's fallback jumps by the factor there).
  const double g = 1.3;
  const DispersionPoint in = model.evaluate(w0 * (1.0 + 1e-12), g), out = model.evaluate(w0 * (1.0 - 1e-12), g);
  EXPECT_NEAR(out.alpha_hat / in.alpha_hat, 1.0, 1e-10);
  EXPECT_NEAR(out.c_hat / in.c_hat, 1.0, 1e-10);
  EXPECT_NEAR(out.d_alpha_hat.d_gamma_hat / in.d_alpha_hat.d_gamma_hat, 1.0, 1e-8);  // along the edge: C1
  EXPECT_EQ(model.fallback_count(), 3u);
  // Exact derivatives of what is returned out there: the correction varies along the edge only.
  testing::expect_gradients_match_finite_differences(model, 1e-3, 1.3, 1e-7);
  testing::expect_gradients_match_finite_differences(model, 3.0, 0.37, 1e-7);
  testing::expect_gradients_match_finite_differences(model, 3.0, 40.0, 1e-7);
  // The nearest edge point in a cell with an unresolved corner: the bare theory.
  table.set(0, 0, unresolved_point("channel too short"));
  const TableModel ragged(std::move(table), "t", OutsideTable::lattice_theory, Interpolation::correction);
  EXPECT_EQ(ragged.evaluate(1e-4, 0.05).alpha_hat, theory.evaluate(1e-4, 0.05).alpha_hat);
  EXPECT_EQ(ragged.fallback_count(), 1u);
  // Without extrapolate the correction scheme refuses outside points like the direct one.
  const TableModel strict(factor_table(grid, 1.0), "t", OutsideTable::error, Interpolation::correction);
  EXPECT_THROW((void)strict.evaluate(1e-4, g_node), std::domain_error);
}

// Where the lattice theory has no positive, finite value (here alpha_hat underflows to 0: an almost
// undamped chain far below its band edge) a correction table cannot be built; direct still can.
TEST(TableCorrection, RefusesPointsWhereTheTheoryHasNoValue) {
  const TableGrid grid{{1e-170, 1e-169}, {1e-170, 1e-169}};
  ASSERT_EQ(LatticeModel().evaluate(1e-170, 1e-170).alpha_hat, 0.0);  // omega_hat^2 gamma_hat / 2 underflows
  DispersionTable table(grid, metadata());
  for (std::size_t g = 0; g < 2; ++g) {
    for (std::size_t w = 0; w < 2; ++w) table.set(g, w, {PointStatus::ok, 1e-3, 1.0, 0.0, 0.0, 1.0, ""});
  }
  EXPECT_NO_THROW(TableModel(table, "t"));
  try {
    const TableModel model(table, "t", OutsideTable::error, Interpolation::correction);
    FAIL() << "a correction table where the theory vanishes was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("lattice theory has no positive, finite value"), std::string::npos) << message;
    EXPECT_NE(message.find("interpolate=direct"), std::string::npos) << message;
  }
}

TEST(TableCorrection, SpecOptionParsesAndUnknownValuesAreRefused) {
  const fs::path file = fs::temp_directory_path() / ("sedwave_correction_" + std::to_string(::getpid()) + ".h5");
  fs::remove(file);
  write_table(file, factor_table({log_spaced(0.01, 1.0, 5), log_spaced(0.1, 10.0, 3)}, 1.0));
  const std::string spec = "table:" + file.string();
  auto table_model = [](const std::unique_ptr<DispersionModel>& m) { return dynamic_cast<const TableModel*>(m.get()); };
  {
    const auto m = make_dispersion_model(spec);
    EXPECT_EQ(table_model(m)->interpolation(), Interpolation::direct);  // the default
    EXPECT_THROW((void)m->evaluate(1e-3, 1.0), std::domain_error);
  }
  {
    const auto m = make_dispersion_model(spec + "?interpolate=correction");
    EXPECT_EQ(table_model(m)->interpolation(), Interpolation::correction);
    EXPECT_EQ(m->name(), spec);
    EXPECT_THROW((void)m->evaluate(1e-3, 1.0), std::domain_error);
  }
  {
    const auto m = make_dispersion_model(spec + "?interpolate=correction&extrapolate=theory");
    EXPECT_EQ(table_model(m)->interpolation(), Interpolation::correction);
    (void)m->evaluate(1e-3, 1.0);
    EXPECT_EQ(table_model(m)->fallback_count(), 1u);
  }
  {
    const auto m = make_dispersion_model(spec + "?extrapolate=long-wavelength&interpolate=direct");
    EXPECT_EQ(table_model(m)->interpolation(), Interpolation::direct);
    (void)m->evaluate(1e-3, 20.0);  // its images (0.01, 2) and (0.032, 0.63) lie in the table
    EXPECT_EQ(table_model(m)->extrapolated_count(), 1u);
  }
  for (const std::string bad : {"?interpolate=spline", "?interpolate=correction&interpolate=direct",
                                "?extrapolate=theory&", "?interpolate=correction&extrapolate=maybe"}) {
    try {
      (void)make_dispersion_model(spec + bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("interpolate=direct, interpolate=correction"), std::string::npos) << message;
      EXPECT_NE(message.find("extrapolate=long-wavelength"), std::string::npos) << message;
    }
  }
  fs::remove(file);
}

}  // namespace
}  // namespace sedwave::forward::table
