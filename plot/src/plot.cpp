#include "sedwave/plot/plot.hpp"

#include "sedwave/io/atomic_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

#include "sedwave/io/atomic_file.hpp"

namespace sedwave::plot {

using namespace inversion;
namespace {

// Columns of the files the script reads (report.cpp writes them).
//   curves.csv: found by name in its header (CurveColumns): which columns it has depends on the model.
//   observations.csv: 1 quantity, 2 f, 5/6 display value and sigma, 9 normalised residual.
constexpr int kCurvesHeaderLines = 2;

/// Where curves.csv holds what the fit plot draws (1-based, as gnuplot counts); each value column is
/// followed by its sigma.
struct CurveColumns {
  int attenuation_db = 0, speed = 0, ratio = 0;  ///< ratio: 0 where the file has none
};

/// The columns of DIR/curves.csv, from its header line. Throws std::runtime_error naming the file
/// where it cannot be read or lacks a column the plot needs.
CurveColumns curve_columns(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  for (int k = 0; k < kCurvesHeaderLines && std::getline(in, line); ++k) {
  }
  std::vector<std::string> names;
  std::stringstream fields(line);
  for (std::string field; std::getline(fields, field, ',');) names.push_back(field);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    return at == names.end() ? 0 : static_cast<int>(at - names.begin()) + 1;
  };
  const CurveColumns c{column("alpha_db_per_m"), column("sound_speed_m_per_s"), column("sound_speed_ratio")};
  if (c.attenuation_db == 0 || c.speed == 0) throw std::runtime_error(file.string() + " has no curve columns");
  return c;
}
constexpr int kObservationsHeaderLines = 4;
constexpr int kObservedFrequency = 2, kObservedValue = 5, kObservedSigma = 6, kObservedResidual = 9;

/// The frequency axis reaches this factor beyond the lowest and highest observed frequency: enough
/// to see the curve's trend leave the data, not so much that an extrapolation dominates the figure.
constexpr double kBandMargin = 2.0;

/// The attenuation axis reaches this factor beyond the data's smallest and largest values.
constexpr double kLogAxisMargin = 1.3;

/// A point further than this from the model, in its own sigmas, is marked as a miss: beyond chance
/// for any data set of the size one fits (p = 0.0027 per point).
constexpr double kMisfitSigma = 3.0;

const char* const kBandColour = "#c6dbef";
const char* const kCurveColour = "#08519c";
const char* const kDataColour = "#252525";
const char* const kMisfitColour = "#d94801";
const char* const kOutsideColour = "#ececec";

/// `s` in single quotes, each quote inside it written as `quote`.
std::string single_quoted(const std::string& s, const std::string& quote) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? quote : std::string(1, c);
  return q + "'";
}

std::string shell_quote(const std::string& s) { return single_quoted(s, "'\\''"); }

/// A gnuplot single-quoted string: no escapes are processed inside, a quote is doubled.
std::string gnuplot_string(const std::string& s) { return single_quoted(s, "''"); }

/// What one quantity's panels need to know about its observations.
struct QuantityPanel {
  Quantity quantity;
  int code;  ///< the quantity column of observations.csv
  double lowest_hz = std::numeric_limits<double>::infinity();
  double highest_hz = 0.0;
  int misfits = 0;  ///< points the model misses by more than kMisfitSigma
  double largest_residual = 0.0;  ///< of |normalised residual|
  double smallest_value = std::numeric_limits<double>::infinity();  ///< of data, error bars and model [SI]
  double largest_value = 0.0;
};

std::vector<QuantityPanel> panels_with_data(const FitResult& result) {
  std::vector<QuantityPanel> panels{{Quantity::Attenuation, 0}, {Quantity::SoundSpeed, 1}};
  for (const PointResidual& p : result.residuals) {
    // Panels of the compressional wave against frequency; bottom loss is drawn by `sedwave reflect`.
    if (p.observation.quantity != Quantity::Attenuation && p.observation.quantity != Quantity::SoundSpeed) continue;
    QuantityPanel& panel = panels[p.observation.quantity == Quantity::Attenuation ? 0 : 1];
    panel.lowest_hz = std::min(panel.lowest_hz, p.observation.frequency_hz);
    panel.highest_hz = std::max(panel.highest_hz, p.observation.frequency_hz);
    panel.misfits += std::abs(p.normalized) > kMisfitSigma ? 1 : 0;
    panel.largest_residual = std::max(panel.largest_residual, std::abs(p.normalized));
    const double low = p.observation.value - p.sigma;
    panel.smallest_value = std::min({panel.smallest_value, low > 0.0 ? low : p.observation.value, p.model});
    panel.largest_value = std::max({panel.largest_value, p.observation.value + p.sigma, p.model});
  }
  std::erase_if(panels, [](const QuantityPanel& p) { return p.highest_hz == 0.0; });
  return panels;
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

/// Parameter and derived quantity names as gnuplot enhanced text.
std::string symbol(const std::string& name) {
  if (name == "kappa") return "κ";
  if (name == "gamma") return "γ";
  if (name == "en") return "e_n";
  if (name == "c0") return "c_0";
  if (name == "tau") return "τ";
  if (name == "f_star") return "f_*";
  if (name == "gamma_hat") return "γ̂";
  if (name == "kappa_over_hertz") return "κ/κ_{Hertz}";
  return name;
}

std::string value_text(const std::string& name, const std::string& unit, double value, double sigma, bool free,
                       bool determined) {
  // A value the data do not determine is wherever the solver stopped along a flat direction: the
  // figure names the parameter and says so, without a number that would read as an answer.
  if (free && !determined) return symbol(name) + " not determined";
  std::string text = symbol(name) + " = " + format("%.4g", value);
  if (free && determined) text += " ± " + format("%.2g", sigma);
  if (unit != "1") text += " " + unit;
  if (!free) text += " (fixed)";
  return text;
}

/// The fitted parameters, one line.
std::string parameter_line(const FitResult& r) {
  std::string line;
  for (const ParameterResult& p : r.parameters) {
    line += (line.empty() ? "" : ",   ") + value_text(p.name, p.unit, p.value, p.sigma, p.free, p.determined);
  }
  return line;
}

/// The derived quantities the data determine, and the goodness of fit, one line.
std::string determined_line(const FitResult& r) {
  std::string line;
  for (const DerivedResult& c : r.derived) {
    if (c.determined) line += (line.empty() ? "" : ",   ") + value_text(c.name, c.unit, c.value, c.sigma, true, true);
  }
  if (!line.empty()) line += ";   ";
  line += "χ^2/ν = " + format("%.4g", r.chi2) + "/" + std::to_string(r.dof);
  if (r.dof > 0) line += " = " + format("%.3g", r.chi2 / r.dof);
  if (!r.converged) line += "   NOT CONVERGED";
  return line;
}

/// Where a panel sits on the page, in screen fractions.
struct PanelBox {
  double top, bottom;
};

/// Panels leave the right of the page to their keys, so no key covers data.
constexpr double kPanelLeft = 0.1, kPanelRight = 0.74;

void place(std::ostringstream& g, PanelBox box) {
  g << "set lmargin at screen " << kPanelLeft << "\nset rmargin at screen " << kPanelRight << "\n"
    << "set tmargin at screen " << box.top << "\nset bmargin at screen " << box.bottom << "\n";
}

/// Greys out the frequencies beyond the quantity's observations, where the curve is a prediction.
void shade_outside_band(std::ostringstream& g, const QuantityPanel& panel) {
  g << "set object 1 rect from graph 0, graph 0 to first " << panel.lowest_hz << ", graph 1 behind fc rgb '"
    << kOutsideColour << "' fs solid 1.0 noborder\n"
    << "set object 2 rect from first " << panel.highest_hz << ", graph 0 to graph 1, graph 1 behind fc rgb '"
    << kOutsideColour << "' fs solid 1.0 noborder\n";
}

/// The observations of one quantity (NaN elsewhere), optionally only those the model misses.
std::string observed(const QuantityPanel& panel, int column, bool misfits_only) {
  std::ostringstream s;
  s << "($1 == " << panel.code;
  if (misfits_only) s << " && abs($" << kObservedResidual << ") > " << kMisfitSigma;
  s << " ? $" << column << " : NaN)";
  return s.str();
}

std::string misfit_title(const QuantityPanel& panel) {
  return gnuplot_string("missed by > " + format("%g", kMisfitSigma) + "σ (" + std::to_string(panel.misfits) +
                        (panel.misfits == 1 ? " point)" : " points)"));
}

/// Open symbols, so that an error bar shows through its marker.
const std::string kDataStyle = std::string("pt 6 ps 0.6 lw 1.2 lc rgb '") + kDataColour + "'";
const std::string kMisfitStyle = std::string("pt 8 ps 1.1 lw 1.5 lc rgb '") + kMisfitColour + "'";

/// The "using" columns of a curve's lower and upper 1-sigma edges. Attenuation is fitted in log
/// space, so its band is too: value * exp(-+sigma/value), which stays positive on a log axis however
/// wide the band is and equals value -+ sigma where sigma is small.
std::string band_edges(int value, bool attenuation) {
  // A stream, not string concatenation: GCC 12 warns falsely (-Wrestrict) on "(" + std::string.
  std::ostringstream edges;
  const int v = value, s = value + 1;
  if (attenuation) {
    edges << "($" << v << "*exp(-$" << s << "/$" << v << ")):($" << v << "*exp($" << s << "/$" << v << "))";
  } else {
    edges << "($" << v << "-$" << s << "):($" << v << "+$" << s << ")";
  }
  return edges.str();
}

/// The frame of a quantity's value panel: its place, the band outside the data greyed, the key on
/// the right, and the value axis (attenuation on a log axis spanning the data).
void value_axis(std::ostringstream& g, const QuantityPanel& panel, bool ratio_axis, PanelBox box) {
  place(g, box);
  shade_outside_band(g, panel);
  g << "set format x ''\nunset xlabel\nset offsets 0, 0, graph 0.06, graph 0.06\nset autoscale yfix\n"
    << "set key at screen " << kPanelRight + 0.015 << ", screen " << box.top
    << " left top Left reverse samplen 2 spacing 1.3 box lc rgb '#bbbbbb'\n";
  if (panel.quantity == Quantity::Attenuation) {
    // The axis spans the data, not the curve's extrapolation: over the data's own decades the error
    // bars stay visible on a log axis.
    g << "set logscale y\nset format y '10^{%L}'\nset ylabel 'attenuation (dB/m)'\nset yrange ["
      << panel.smallest_value * kDecibelPerNeper / kLogAxisMargin << ":"
      << panel.largest_value * kDecibelPerNeper * kLogAxisMargin << "]\n";
  } else {
    g << "unset logscale y\nset format y '%g'\nset ylabel "
      << gnuplot_string(ratio_axis ? "sound speed / water sound speed" : "sound speed (m/s)") << "\n";
  }
}

/// Data, model curve and its band for one quantity. Drawing order is back to front: band, curve,
/// error bars, then the misfits on top, so nothing hides the error bars.
void main_panel(std::ostringstream& g, const QuantityPanel& panel, bool ratio_axis, const CurveColumns& columns,
                PanelBox box) {
  const bool attenuation = panel.quantity == Quantity::Attenuation;
  const int value = attenuation ? columns.attenuation_db : ratio_axis && columns.ratio ? columns.ratio : columns.speed;
  value_axis(g, panel, ratio_axis, box);
  g << "plot 'curves.csv' skip " << kCurvesHeaderLines << " using 1:" << band_edges(value, attenuation)
    << " with filledcurves fc rgb '" << kBandColour << "' title 'model ±1σ (covariance)', \\\n"
    << "  '' skip " << kCurvesHeaderLines << " using 1:" << value << " with lines lw 1.5 lc rgb '" << kCurveColour
    << "' title 'fitted model', \\\n"
    << "  'observations.csv' skip " << kObservationsHeaderLines << " using " << kObservedFrequency << ":"
    << observed(panel, kObservedValue, false) << ":" << kObservedSigma
    << " with yerrorbars " << kDataStyle << " title 'observations ±1σ'";
  if (panel.misfits > 0) {
    g << ", \\\n  '' skip " << kObservationsHeaderLines << " using " << kObservedFrequency << ":"
      << observed(panel, kObservedValue, true) << " with points " << kMisfitStyle << " title " << misfit_title(panel);
  }
  g << ", \\\n  NaN with boxes fs solid 1.0 fc rgb '" << kOutsideColour << "' title 'no data here'\n";
}

/// About five labelled tics on a residual axis from -half_range to half_range.
int residual_tic_step(double half_range) {
  if (half_range < 3.5) return 1;
  if (half_range < 7.0) return 2;
  if (half_range < 14.0) return 4;
  return 10;
}

/// The frame of a residual panel, symmetric about zero and at least ±2.5 so the ±2 guides always
/// show, and the start of its plot command: the guide lines at 0, ±1 and ±2.
void residual_axis(std::ostringstream& g, const QuantityPanel& panel, PanelBox box, double largest_residual) {
  place(g, box);
  shade_outside_band(g, panel);
  const double half_range = 1.25 * std::max(2.5, largest_residual);
  g << "unset logscale y\nset format x '10^{%L}'\nset format y '%g'\nset xlabel 'frequency (Hz)'\n"
    << "set offsets 0, 0, 0, 0\nset ytics " << residual_tic_step(half_range) << "\n"
    << "set ylabel '(obs − model)/σ'\nset yrange [" << -half_range << ":" << half_range << "]\nunset key\n"
    << "plot 0 with lines lw 1 lc rgb '#555555', \\\n"
    << "  1 with lines dt 2 lc rgb '#777777', -1 with lines dt 2 lc rgb '#777777', \\\n"
    << "  2 with lines dt 3 lc rgb '#777777', -2 with lines dt 3 lc rgb '#777777'";
}

void end_residual_panel(std::ostringstream& g) {
  g << "\nset yrange [*:*]\nset ytics autofreq\nunset object 1\nunset object 2\n";
}

/// Normalised residuals (observed - model)/sigma with guide lines at 0, ±1 and ±2.
void residual_panel(std::ostringstream& g, const QuantityPanel& panel, PanelBox box) {
  residual_axis(g, panel, box, panel.largest_residual);
  g << ", \\\n  'observations.csv' skip " << kObservationsHeaderLines << " using " << kObservedFrequency << ":"
    << observed(panel, kObservedResidual, false) << " with points " << kDataStyle;
  if (panel.misfits > 0) {
    g << ", \\\n  '' skip " << kObservationsHeaderLines << " using " << kObservedFrequency << ":"
      << observed(panel, kObservedResidual, true) << " with points " << kMisfitStyle;
  }
  end_residual_panel(g);
}

/// Where each quantity's panels go: an equal slice of the page below the summary lines, 7/10 for the
/// values and the rest for the residuals, with room under the residuals for the frequency axis.
struct PanelPair {
  PanelBox values, residuals;
};

std::vector<PanelPair> layout(std::size_t quantities, double top) {
  const double bottom = 0.0, axis_room = 0.07;
  const double slice = (top - bottom) / static_cast<double>(std::max<size_t>(quantities, 1));
  std::vector<PanelPair> pairs;
  for (size_t i = 0; i < quantities; ++i) {
    const double slice_top = top - slice * static_cast<double>(i);
    const double split = slice_top - 0.7 * (slice - axis_room);
    pairs.push_back({{slice_top, split}, {split, slice_top - slice + axis_room}});
  }
  return pairs;
}

/// The common head of a multiplot over frequency: the data's band widened by kBandMargin.
void frequency_multiplot(std::ostringstream& g, const std::string& title, const std::vector<QuantityPanel>& panels) {
  double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;
  for (const QuantityPanel& p : panels) {
    lowest = std::min(lowest, p.lowest_hz);
    highest = std::max(highest, p.highest_hz);
  }
  g << "set encoding utf8\nset multiplot title " << gnuplot_string(title) << " font ',13' noenhanced\n"
    << "set datafile separator ','\nset grid lc rgb '#dddddd'\nset logscale x\nset mxtics 10\n"
    << "set xrange [" << lowest / kBandMargin << ":" << highest * kBandMargin << "]\n";
}

/// Title and fit summary on top, then for each quantity a data panel above its residual panel,
/// all on one frequency axis.
std::string plot_body(const std::string& title, bool ratio_axis, const CurveColumns& columns, const FitResult& result) {
  const std::vector<QuantityPanel> panels = panels_with_data(result);
  std::ostringstream g;
  frequency_multiplot(g, title, panels);
  g << "set label 1 " << gnuplot_string(parameter_line(result)) << " at screen 0.5, screen 0.945 center\n"
    << "set label 2 " << gnuplot_string(determined_line(result)) << " at screen 0.5, screen 0.92 center\n";
  const std::vector<PanelPair> boxes = layout(panels.size(), 0.9);
  for (size_t i = 0; i < panels.size(); ++i) {
    main_panel(g, panels[i], ratio_axis, columns, boxes[i].values);
    if (i == 0) g << "unset label 1\nunset label 2\n";
    residual_panel(g, panels[i], boxes[i].residuals);
  }
  g << "unset multiplot\n";
  return g.str();
}

const char* const kModelColours[] = {"#08519c", "#d94801", "#238b45", "#6a51a3", "#a50f15", "#525252"};

std::string model_colour(std::size_t i) { return kModelColours[i % std::size(kModelColours)]; }

/// Header lines of the band and residual files (predictive.cpp writes them).
constexpr int kBandHeaderLines = 2;
/// The band file's first quantile column of a quantity: attenuation 2-6, speed 7-11, ratio 12-16.
int first_quantile_column(const QuantityPanel& panel, bool ratio_axis) {
  return panel.quantity == Quantity::Attenuation ? 2 : ratio_axis ? 12 : 7;
}

/// Each model's 95 % and 68 % bands and median, then the observations on top.
void band_panel(std::ostringstream& g, const QuantityPanel& panel, bool ratio_axis, PanelBox box,
                const std::vector<BandFile>& bands, const std::string& residuals_file) {
  value_axis(g, panel, ratio_axis, box);
  const int q = first_quantile_column(panel, ratio_axis);
  g << "plot ";
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const std::string file = gnuplot_string(bands[i].file), colour = model_colour(i);
    const std::string label = bands.size() == 1 ? "posterior" : bands[i].label;
    g << file << " skip " << kBandHeaderLines << " using 1:" << q << ":" << q + 4 << " with filledcurves fc rgb '"
      << colour << "' fs transparent solid 0.15 noborder title " << gnuplot_string(label + " 95 %") << ", \\\n  "
      << file << " skip " << kBandHeaderLines << " using 1:" << q + 1 << ":" << q + 3 << " with filledcurves fc rgb '"
      << colour << "' fs transparent solid 0.35 noborder title " << gnuplot_string(label + " 68 %") << ", \\\n  "
      << file << " skip " << kBandHeaderLines << " using 1:" << q + 2 << " with lines lw 1.5 lc rgb '" << colour
      << "' title " << gnuplot_string(label + " median") << ", \\\n  ";
  }
  g << gnuplot_string(residuals_file) << " skip " << kBandHeaderLines << " using 2:($1 == " << panel.code
    << " ? $3 : NaN):4 with yerrorbars " << kDataStyle << " title 'observations ±1σ', \\\n"
    << "  NaN with boxes fs solid 1.0 fc rgb '" << kOutsideColour << "' title 'no data here'\n";
}

/// Each model's residuals from its band's median, in its colour.
void band_residual_panel(std::ostringstream& g, const QuantityPanel& panel, PanelBox box,
                         const std::vector<BandFile>& bands, const std::string& residuals_file, double largest) {
  residual_axis(g, panel, box, largest);
  for (std::size_t i = 0; i < bands.size(); ++i) {
    g << ", \\\n  " << gnuplot_string(residuals_file) << " skip " << kBandHeaderLines << " using 2:($1 == "
      << panel.code << " ? column(" << 5 + i << ") : NaN) with points pt 6 ps 0.7 lw 1.2 lc rgb '" << model_colour(i)
      << "'";
  }
  end_residual_panel(g);
}

std::string predictive_body(const std::string& title, bool ratio_axis, const FitResult& any_fit,
                            const std::vector<BandFile>& bands, const std::string& residuals_file,
                            double largest_residual) {
  const std::vector<QuantityPanel> panels = panels_with_data(any_fit);
  std::ostringstream g;
  frequency_multiplot(g, title, panels);
  const std::vector<PanelPair> boxes = layout(panels.size(), 0.94);
  for (size_t i = 0; i < panels.size(); ++i) {
    band_panel(g, panels[i], ratio_axis, boxes[i].values, bands, residuals_file);
    band_residual_panel(g, panels[i], boxes[i].residuals, bands, residuals_file, largest_residual);
  }
  g << "unset multiplot\n";
  return g.str();
}

/// The largest |residual| in a residuals file (columns 5 on), for the residual axis's range.
double largest_residual_in(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  double largest = 0.0;
  for (int skipped = 0; skipped < kBandHeaderLines && std::getline(in, line); ++skipped) {
  }
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string field;
    for (int column = 1; std::getline(fields, field, ','); ++column) {
      if (column < 5) continue;
      const double r = std::strtod(field.c_str(), nullptr);
      if (std::isfinite(r)) largest = std::max(largest, std::abs(r));
    }
  }
  return largest;
}

}  // namespace

PlotOutcome run_gnuplot(const std::filesystem::path& dir, const std::string& stem, const std::string& size,
                        const std::string& body) {
  const std::string script_name = stem + ".gp";
  try {
    io::write_text_atomically(dir / script_name, [&](std::ostream& script) {
      script << "# gnuplot script written by sedwave; re-run with: gnuplot " << script_name << "\n"
             << "if (!exists('png_file')) png_file = '" << stem << ".png'\nif (!exists('svg_file')) svg_file = '" << stem
             << ".svg'\n"
             << "set terminal pngcairo size " << size << " enhanced font 'Sans,11'\nset output png_file\n"
             << body << "set terminal svg size " << size << " enhanced font 'Sans,11'\nset output svg_file\n" << body;
    });
  } catch (const std::exception& e) {
    return {false, std::string("plot skipped: ") + e.what()};
  }
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    return {false, "plot skipped: gnuplot not found (apt-get install gnuplot-nox); script left in " +
                       (dir / script_name).string()};
  }
  try {
    io::AtomicFile png(dir / (stem + ".png")), svg(dir / (stem + ".svg"));
    const std::string command = "cd " + shell_quote(dir.string()) + " && gnuplot -e " +
                                shell_quote("png_file='" + png.temporary().filename().string() + "'; svg_file='" +
                                            svg.temporary().filename().string() + "'") +
                                " " + shell_quote(script_name) + " > gnuplot.log 2>&1";
    if (std::system(command.c_str()) != 0) {
      return {false, "plot skipped: gnuplot failed, see " + (dir / "gnuplot.log").string()};
    }
    png.commit();
    svg.commit();
  } catch (const std::exception& e) {
    return {false, std::string("plot skipped: ") + e.what()};
  }
  return {true, "plot written to " + (dir / (stem + ".png")).string() + " and " + stem + ".svg"};
}

namespace {

// ---- The corner plot ------------------------------------------------------------------------------
// As corner.py draws one (Foreman-Mackey 2016, JOSS 1, 24): physical values on log axes (the
// parameters span decades), each marginal on the diagonal, each pair's draws below it with the
// contours of the smallest regions holding 68 % and 95 % of the draws (a 2D histogram in ln space,
// smoothed over neighbouring bins), and the best fit marked. The histograms are computed here and
// written to STEM_density.dat; gnuplot contours them (set contour) and draws the panels.

constexpr int kCornerBins = 30;
constexpr double kCornerLevels[2] = {0.68, 0.95};

/// The draws of a samples file (two header lines, one column per parameter, SI values).
std::vector<std::vector<double>> read_draws(const std::filesystem::path& file, std::size_t columns) {
  std::vector<std::vector<double>> draws(columns);
  std::ifstream in(file);
  std::string line;
  for (int skipped = 0; skipped < 2 && std::getline(in, line); ++skipped) {
  }
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string field;
    for (std::size_t c = 0; c < columns && std::getline(fields, field, ','); ++c) {
      draws[c].push_back(std::strtod(field.c_str(), nullptr));
    }
  }
  return draws;
}

/// One parameter's axis: log when every draw is positive (ln of the value is binned), else linear.
struct CornerAxis {
  bool log = true;
  double lo = 0.0, hi = 1.0;  ///< binned coordinate (ln value on a log axis)
  [[nodiscard]] double coordinate(double x) const { return log ? std::log(x) : x; }
  [[nodiscard]] double value(double c) const { return log ? std::exp(c) : c; }
  [[nodiscard]] std::size_t bin(double x) const {
    const double f = (coordinate(x) - lo) / (hi - lo);
    return static_cast<std::size_t>(std::clamp(static_cast<int>(f * kCornerBins), 0, kCornerBins - 1));
  }
  [[nodiscard]] double centre(std::size_t b) const {
    return value(lo + (hi - lo) * (static_cast<double>(b) + 0.5) / kCornerBins);
  }
};

CornerAxis corner_axis(const std::vector<double>& draws) {
  CornerAxis a;
  a.log = !draws.empty() && std::all_of(draws.begin(), draws.end(), [](double x) { return x > 0.0 && std::isfinite(x); });
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double x : draws) {
    if (!std::isfinite(a.coordinate(x))) continue;
    lo = std::min(lo, a.coordinate(x));
    hi = std::max(hi, a.coordinate(x));
  }
  if (!(hi > lo)) {  // one value (or none): a band around it
    const double mid = std::isfinite(lo) ? lo : 0.0, half = std::max(1e-6, 1e-3 * std::abs(mid));
    lo = mid - half;
    hi = mid + half;
  }
  a.lo = lo;
  a.hi = hi;
  return a;
}

/// Readable ticks: three round values spread over the axis, with the fewest significant digits
/// (from two) that keep each within 5 % of the axis of where it belongs.
std::string corner_tics(const CornerAxis& a) {
  std::ostringstream t;
  t << "(";
  for (int k = 0; k < 3; ++k) {
    const double at = a.lo + (a.hi - a.lo) * (0.15 + 0.35 * k);
    char label[32];
    for (int digits = 2; digits <= 6; ++digits) {
      std::snprintf(label, sizeof label, "%.*g", digits, a.value(at));
      if (std::abs(a.coordinate(std::strtod(label, nullptr)) - at) < 0.05 * (a.hi - a.lo)) break;
    }
    t << (k ? ", " : "") << "'" << label << "' " << std::strtod(label, nullptr);
  }
  return t.str() + ")";
}

/// A kCornerBins x kCornerBins histogram, bin (i, j) at i * kCornerBins + j.
using Histogram2 = std::vector<double>;

/// 3x3 smoothing of a histogram (weights 1-2-1 in each direction), as corner.py smooths before
/// contouring: single bins' noise would otherwise fray the contours.
Histogram2 smoothed(const Histogram2& h) {
  Histogram2 out(h.size(), 0.0);
  constexpr int n = kCornerBins;
  const auto at = [](int i, int j) { return static_cast<std::size_t>(i * n + j); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double sum = 0.0, weight = 0.0;
      for (int di = -1; di <= 1; ++di) {
        for (int dj = -1; dj <= 1; ++dj) {
          if (i + di < 0 || i + di >= n || j + dj < 0 || j + dj >= n) continue;
          const double w = (di == 0 ? 2.0 : 1.0) * (dj == 0 ? 2.0 : 1.0);
          sum += w * h[at(i + di, j + dj)];
          weight += w;
        }
      }
      out[at(i, j)] = sum / weight;
    }
  }
  return out;
}

/// The density above which the bins hold `mass` of the total (highest bins first).
double level_holding(std::vector<double> density, double mass) {
  std::sort(density.begin(), density.end(), std::greater<>());
  double total = 0.0;
  for (double d : density) total += d;
  double cumulative = 0.0;
  for (double d : density) {
    cumulative += d;
    if (cumulative >= mass * total) return d;
  }
  return density.empty() ? 0.0 : density.back();
}

/// The smoothed joint histogram of parameters x and y.
Histogram2 joint_histogram(const std::vector<double>& xs, const std::vector<double>& ys, const CornerAxis& ax,
                           const CornerAxis& ay) {
  const auto n = static_cast<std::size_t>(kCornerBins);
  Histogram2 h(n * n, 0.0);
  for (std::size_t k = 0; k < std::min(xs.size(), ys.size()); ++k) h[ax.bin(xs[k]) * n + ay.bin(ys[k])] += 1.0;
  return smoothed(h);
}

/// Writes STEM_density.dat: for each pair (row > col) a grid block "x y density" (gnuplot index
/// = pair number), then a block of every fourth draw (one column per parameter), then for each
/// parameter a block "value density" of its marginal. Returns the two contour levels of each pair.
std::vector<std::array<double, 2>> write_corner_density(const std::filesystem::path& file,
                                                        const std::vector<std::vector<double>>& draws,
                                                        const std::vector<CornerAxis>& axes) {
  const std::size_t k = draws.size(), n = static_cast<std::size_t>(kCornerBins);
  std::vector<std::array<double, 2>> levels;
  io::write_text_atomically(file, [&](std::ostream& out) {
    out << "# corner plot densities (sedwave): per pair x y density on a " << n << "x" << n
        << " grid of ln values, then every fourth draw, then per parameter value density; SI units\n";
    for (std::size_t row = 1; row < k; ++row) {
      for (std::size_t col = 0; col < row; ++col) {
        const Histogram2 h = joint_histogram(draws[col], draws[row], axes[col], axes[row]);
        levels.push_back({level_holding(h, kCornerLevels[0]), level_holding(h, kCornerLevels[1])});
        for (std::size_t i = 0; i < n; ++i) {
          for (std::size_t j = 0; j < n; ++j) {
            out << axes[col].centre(i) << " " << axes[row].centre(j) << " " << h[i * n + j] << "\n";
          }
          out << "\n";
        }
        out << "\n";
      }
    }
    // Every fourth draw, all columns (the pairs' scatter; gnuplot reads one separator per script).
    for (std::size_t d = 0; d < (k > 0 ? draws[0].size() : 0); d += 4) {
      for (std::size_t p = 0; p < k; ++p) out << (p ? " " : "") << draws[p][d];
      out << "\n";
    }
    out << "\n\n";
    for (std::size_t p = 0; p < k; ++p) {
      std::vector<double> h(n, 0.0);
      for (double x : draws[p]) h[axes[p].bin(x)] += 1.0;
      for (std::size_t b = 0; b < n; ++b) out << axes[p].centre(b) << " " << h[b] << "\n";
      out << "\n\n";
    }
  });
  return levels;
}

/// One panel's axis: range, scale, round ticks, and its label where the panel is on the edge.
void corner_axis_commands(std::ostream& g, char which, const CornerAxis& a, const std::string& label) {
  g << "set " << which << "tics " << corner_tics(a) << (which == 'x' ? " rotate by 30 right" : " format '% h'")
    << "\nset " << which << "range [" << a.value(a.lo) << ":" << a.value(a.hi) << "]\n"
    << (a.log ? std::string("set logscale ") + which + "\n" : std::string()) << "set " << which << "label "
    << gnuplot_string(label) << " font ',9' noenhanced\n";
}

std::string corner_body(const CornerFiles& files, const std::string& density_file, const std::vector<std::string>& names,
                        const std::vector<std::string>& units, const std::vector<CornerAxis>& axes,
                        const std::vector<std::array<double, 2>>& levels) {
  const std::string density = gnuplot_string(density_file);
  const std::size_t k = names.size(), draws_block = levels.size(), marginal_block = levels.size() + 1;
  const bool marked = files.best_fit.size() == k;
  const auto label = [&](std::size_t p) { return names[p] + " [" + units[p] + "]"; };
  std::ostringstream g;
  // reset: the body runs twice (PNG, SVG), and the last panel's ranges and log axes must not reach
  // the second run's contouring (terminal and output survive a reset). The contours go first, into
  // datablocks: gnuplot contours splot's grid.
  g << "reset\nset encoding utf8\nset datafile separator whitespace\nset contour base\nunset surface\nset view map\n";
  for (std::size_t pair = 0; pair < levels.size(); ++pair) {
    for (std::size_t l = 0; l < 2; ++l) {
      g << "set cntrparam levels discrete " << levels[pair][l] << "\nset table $c" << pair << "_" << l << "\nsplot "
        << density << " index " << pair << " using 1:2:3 with lines\nunset table\n";
    }
  }
  g << "unset contour\nset surface\nset key off\nset tics font ',8'\n"
    << "set multiplot layout " << k << "," << k << " title "
    << gnuplot_string(files.title + ": marginals, pairs with 68 % and 95 % contours" +
                      (marked ? ", best fit in red" : std::string()))
    << " font ',12' noenhanced\n";
  const std::string mark_style = std::string(" nohead lc rgb '") + kMisfitColour + "' lw 1.2\n";
  std::size_t pair = 0;
  for (std::size_t row = 0; row < k; ++row) {
    for (std::size_t col = 0; col < k; ++col) {
      if (col > row) {
        g << "set multiplot next\n";
        continue;
      }
      g << "unset label\nunset arrow\nunset logscale\n";
      corner_axis_commands(g, 'x', axes[col], row == k - 1 ? label(col) : "");
      if (marked) {
        g << "set arrow from first " << files.best_fit[col] << ", graph 0 to first " << files.best_fit[col]
          << ", graph 1" << mark_style;
      }
      if (col == row) {
        g << "set ytics auto format ''\nset autoscale y\nset ylabel ''\nplot " << density << " index "
          << marginal_block + col << " using 1:2 with histeps lw 1.5 lc rgb '" << kCurveColour << "'\n";
        continue;
      }
      corner_axis_commands(g, 'y', axes[row], col == 0 ? label(row) : "");
      if (marked) {
        g << "set arrow from graph 0, first " << files.best_fit[row] << " to graph 1, first " << files.best_fit[row]
          << mark_style;
      }
      g << "plot " << density << " index " << draws_block << " using " << col + 1 << ":" << row + 1
        << " with dots lc rgb '#b0b0b0', $c" << pair << "_1 using 1:2 with lines lw 1.2 lc rgb '#6baed6', $c" << pair
        << "_0 using 1:2 with lines lw 1.8 lc rgb '" << kCurveColour << "'";
      if (marked) {
        g << ", '+' using (" << files.best_fit[col] << "):(" << files.best_fit[row]
          << ") every ::0::0 with points pt 7 ps 0.9 lc rgb '" << kMisfitColour << "'";
      }
      g << "\n";
      ++pair;
    }
  }
  g << "unset multiplot\n";
  return g.str();
}

}  // namespace

PlotOutcome draw_fit_plot(const std::filesystem::path& dir, const std::string& title, bool ratio_axis,
                          const FitResult& result) {
  CurveColumns columns;
  try {
    columns = curve_columns(dir / "curves.csv");
  } catch (const std::exception& e) {
    return {false, std::string("plot skipped: ") + e.what()};
  }
  if (panels_with_data(result).empty()) return {false, kNoWaveRows};
  return run_gnuplot(dir, "fit", "1150,1250", plot_body(title, ratio_axis, columns, result));
}

PlotOutcome draw_corner_plot(const std::filesystem::path& dir, const std::vector<std::string>& names,
                             const std::vector<std::string>& units, const CornerFiles& files) {
  const std::string density_file = files.stem + "_density.dat";
  std::vector<std::array<double, 2>> levels;
  std::vector<CornerAxis> axes;
  try {
    const std::vector<std::vector<double>> draws = read_draws(dir / files.samples, names.size());
    for (const auto& column : draws) axes.push_back(corner_axis(column));
    levels = write_corner_density(dir / density_file, draws, axes);
  } catch (const std::exception& e) {
    return {false, std::string("plot skipped: ") + e.what()};
  }
  return run_gnuplot(dir, files.stem, "1000,1000", corner_body(files, density_file, names, units, axes, levels));
}

PlotOutcome draw_predictive_plot(const std::filesystem::path& dir, const std::string& stem, const std::string& title,
                                 bool ratio_axis, const FitResult& any_fit, const std::vector<BandFile>& bands,
                                 const std::string& residuals_file) {
  if (panels_with_data(any_fit).empty()) return {false, kNoWaveRows};
  const double largest = largest_residual_in(dir / residuals_file);
  return run_gnuplot(dir, stem, "1150,1250",
                     predictive_body(title, ratio_axis, any_fit, bands, residuals_file, largest));
}

}  // namespace sedwave::plot
