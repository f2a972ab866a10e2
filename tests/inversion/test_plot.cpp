// The fit's plotting outputs: observations.csv keeps its columns and adds the model and normalised
// residual at the end; the gnuplot script draws a residual panel per quantity, marks the points the
// model misses by more than 3 sigma, and writes the fitted values and chi^2/dof on the figure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "sedwave/plot/plot.hpp"
#include "sedwave/inversion/report.hpp"

namespace sedwave::inversion {
using plot::CornerFiles;
using plot::draw_corner_plot;
using plot::draw_fit_plot;
using plot::PlotOutcome;
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

PointResidual point(Quantity quantity, double frequency_hz, double value, double sigma, double model,
                    double normalized) {
  PointResidual p;
  p.observation.quantity = quantity;
  p.observation.frequency_hz = frequency_hz;
  p.observation.value = value;
  p.sigma = sigma;
  p.model = model;
  p.normalized = normalized;
  return p;
}

/// A fit of three attenuation and two sound-speed points, one attenuation point missed by 5 sigma.
FitResult small_fit() {
  FitResult r;
  r.model = "lattice";
  r.parameters = {{"kappa", "N/m", 1e6, true, false, true, 0.1, 1e5, std::nullopt, std::nullopt},
                  {"d", "m", 3e-4, false, false, true, 0.0, 0.0, std::nullopt, std::nullopt}};
  r.derived = {{"c0", "m/s", "", 1600.0, true, 0.01, 16.0, {}, {}}};
  r.residuals = {point(Quantity::Attenuation, 100.0, 1e-3, 1e-4, 1.1e-3, 0.5),
                 point(Quantity::Attenuation, 300.0, 1e-2, 1e-3, 0.9e-2, -0.4),
                 point(Quantity::Attenuation, 1000.0, 1e-1, 1e-2, 1.6e-1, 5.0),
                 point(Quantity::SoundSpeed, 100.0, 1600.0, 10.0, 1601.0, 0.1),
                 point(Quantity::SoundSpeed, 600.0, 1600.0, 10.0, 1598.0, -0.2)};
  r.chi2 = 25.46;
  r.n_observations = 5;
  r.dof = 4;
  r.converged = true;
  return r;
}

class FitPlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device random;
    do {
      dir_ = fs::temp_directory_path() / ("sedwave_test_plot_" + std::to_string(random()));
    } while (!fs::create_directory(dir_));
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

TEST_F(FitPlotTest, ObservationsTableAddsModelAndNormalisedResidualAtTheEnd) {
  write_observations_table(dir_ / "observations.csv", ObservationSet{}, small_fit());
  const std::string text = read_text(dir_ / "observations.csv");
  EXPECT_NE(text.find("# sedwave observations as fitted; quantity 0 = attenuation [Np/m], 1 = sound speed [m/s]"),
            std::string::npos);
  EXPECT_NE(text.find("\nquantity,frequency_hz,value,sigma,display_value,display_sigma,model_value,"
                      "display_model_value,normalized_residual,grazing_angle_deg\n"),
            std::string::npos);
  const auto row_start = text.find("\n0,1000,");
  ASSERT_NE(row_start, std::string::npos) << text;
  std::vector<double> row;
  std::stringstream cells(text.substr(row_start + 1, text.find('\n', row_start + 1) - row_start - 1));
  for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
  ASSERT_EQ(row.size(), 9U);  // no grazing angle: not a reflection row
  EXPECT_DOUBLE_EQ(row[4], 0.1 * kDecibelPerNeper);   // display value, dB/m
  EXPECT_DOUBLE_EQ(row[6], 0.16);                     // model, Np/m
  EXPECT_DOUBLE_EQ(row[7], 0.16 * kDecibelPerNeper);  // model, dB/m
  // The fit's residual is model minus observed; the table's is observed minus model.
  EXPECT_DOUBLE_EQ(row[8], -5.0);
}

TEST_F(FitPlotTest, ScriptDrawsResidualPanelsMarksMissesAndStatesTheFit) {
  const FitResult fit = small_fit();
  write_observations_table(dir_ / "observations.csv", ObservationSet{}, fit);
  write_curves_csv(dir_ / "curves.csv",
                   {{50.0, 0, 0, 0, 0, 1e-4, 1e-5, 1600.0, 5.0}, {2000.0, 0, 0, 0, 0, 0.3, 0.03, 1610.0, 5.0}},
                   std::nullopt);
  const PlotOutcome outcome = draw_fit_plot(dir_, "test fit", false, fit);
  const std::string script = read_text(dir_ / "fit.gp");

  // Both terminals draw the same figure: two quantities, each with a residual panel.
  EXPECT_EQ(count(script, "set ylabel '(obs − model)/σ'"), 4U);
  EXPECT_EQ(count(script, "missed by > 3σ (1 point)"), 2U) << "only the attenuation panel has a miss";
  EXPECT_NE(script.find("κ = 1e+06 ± 1e+05 N/m,   d = 0.0003 m (fixed)"), std::string::npos) << script;
  EXPECT_NE(script.find("c_0 = 1600 ± 16 m/s;   χ^2/ν = 25.46/4 = 6.37"), std::string::npos) << script;
  EXPECT_NE(script.find("set xrange [50:2000]"), std::string::npos) << "the data's band widened by 2";

  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(outcome.drawn) << outcome.message;
    EXPECT_TRUE(fs::exists(dir_ / "fit.png"));
  } else {
    EXPECT_NE(outcome.message.find("gnuplot not found"), std::string::npos) << outcome.message;
  }
}

// A model without a dry grain-contact frame (Biot-Stoll, EDFM, ...) has no dimensionless curve: its
// curves.csv leaves those columns out instead of filling them with NaN, and the plot finds its
// columns by name.
TEST_F(FitPlotTest, CurvesOfAModelWithoutAFrameHaveNoDimensionlessColumns) {
  const FitResult fit = small_fit();
  write_observations_table(dir_ / "observations.csv", ObservationSet{}, fit);
  const double none = kNotApplicable;
  write_curves_csv(dir_ / "curves.csv",
                   {{50.0, none, none, none, none, 1e-4, 1e-5, 1600.0, 5.0},
                    {2000.0, none, none, none, none, 0.3, 0.03, 1610.0, 5.0}},
                   std::nullopt);
  const std::string curves = read_text(dir_ / "curves.csv");
  EXPECT_NE(curves.find("\nfrequency_hz,alpha_np_per_m,alpha_np_per_m_sigma,alpha_db_per_m,"), std::string::npos)
      << curves;
  EXPECT_EQ(curves.find("nan"), std::string::npos) << curves;
  (void)draw_fit_plot(dir_, "test fit", false, fit);
  const std::string script = read_text(dir_ / "fit.gp");
  EXPECT_NE(script.find("using 1:4 with lines"), std::string::npos) << "attenuation in dB/m is column 4";
  EXPECT_NE(script.find("using 1:6 with lines"), std::string::npos) << "sound speed is column 6";

  write_curves_csv(dir_ / "curves.csv", {{50.0, 0.01, 1.0, 1e-3, 1.0, 1e-4, 1e-5, 1600.0, 5.0}}, std::nullopt);
  EXPECT_NE(read_text(dir_ / "curves.csv").find("\nfrequency_hz,omega_hat,gamma_hat,alpha_hat,c_hat,alpha_np_per_m,"),
            std::string::npos);
  (void)draw_fit_plot(dir_, "test fit", false, fit);
  EXPECT_NE(read_text(dir_ / "fit.gp").find("using 1:8 with lines"), std::string::npos) << "with the frame's columns";
}

// The corner plot of k parameters: k histograms on the diagonal, k(k-1)/2 pair panels below with
// their 68 % and 95 % contours, physical values on log axes, the best fit marked; with gnuplot
// installed the figure is drawn.
TEST(CornerPlot, DrawsEveryMarginalAndEveryPair) {
  const fs::path dir = fs::temp_directory_path() / ("sedwave_corner_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream samples(dir / "posterior_samples.csv");
    samples << "# test samples\nkappa,d,gamma\n";
    std::mt19937_64 rng(1);
    std::normal_distribution<double> n(0.0, 0.3);
    for (int i = 0; i < 4000; ++i) {
      samples << 1e6 * std::exp(n(rng)) << ',' << 3e-4 * std::exp(n(rng)) << ',' << 5.0 * std::exp(n(rng)) << '\n';
    }
  }
  CornerFiles files;
  files.best_fit = {1e6, 3e-4, 5.0};
  const PlotOutcome outcome = draw_corner_plot(dir, {"kappa", "d", "gamma"}, {"N/m", "m", "kg/s"}, files);
  const std::string script = read_text(dir / "posterior_corner.gp");
  EXPECT_NE(script.find("layout 3,3"), std::string::npos);
  EXPECT_EQ(count(script, "with histeps"), 2u * 3u);  // PNG and SVG
  EXPECT_EQ(count(script, "with dots"), 2u * 3u);
  EXPECT_EQ(count(script, "set cntrparam levels discrete"), 2u * 3u * 2u);  // 3 pairs, 68 % and 95 %
  EXPECT_EQ(count(script, "set logscale x"), 2u * 6u);                      // every panel, SI values
  EXPECT_EQ(count(script, "with points pt 7"), 2u * 3u);                   // the best fit in each pair
  for (const char* column : {"using 1:2 ", "using 1:3 ", "using 2:3 "}) EXPECT_NE(script.find(column), std::string::npos);
  // The two levels of the first pair: the bins above the 68 % level hold 68 % of the density (and
  // not much more: the next bin down would cross it), those above the 95 % level 95 %.
  std::vector<double> levels;
  for (std::size_t at = script.find("levels discrete "); at != std::string::npos && levels.size() < 2;
       at = script.find("levels discrete ", at + 1)) {
    levels.push_back(std::strtod(script.c_str() + at + 16, nullptr));
  }
  ASSERT_EQ(levels.size(), 2u);
  EXPECT_GT(levels[0], levels[1]);
  std::ifstream density(dir / "posterior_corner_density.dat");
  std::string line;
  std::getline(density, line);  // the header
  std::vector<double> bins;
  while (bins.size() < 900 && std::getline(density, line)) {
    if (line.empty()) continue;
    double x = 0, y = 0, h = 0;
    std::istringstream(line) >> x >> y >> h;
    EXPECT_GT(x, 0.0);  // SI values, not their logarithms
    bins.push_back(h);
  }
  ASSERT_EQ(bins.size(), 900u);
  double total = 0, above68 = 0, above95 = 0;
  for (double h : bins) {
    total += h;
    if (h >= levels[0]) above68 += h;
    if (h >= levels[1]) above95 += h;
  }
  EXPECT_NEAR(above68 / total, 0.68, 0.03);
  EXPECT_NEAR(above95 / total, 0.95, 0.02);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(outcome.drawn) << outcome.message;
    EXPECT_GT(fs::file_size(dir / "posterior_corner.png"), 1000u);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sedwave::inversion
