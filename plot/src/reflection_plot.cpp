#include "sedwave/plot/reflection_plot.hpp"

#include <sstream>

namespace sedwave::plot {

namespace {

constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
                                    "#7f7f7f", "#bcbd22", "#17becf"};

const char* colour(std::size_t i) { return kColours[i % (sizeof kColours / sizeof kColours[0])]; }

/// A gnuplot single-quoted string (a quote is doubled).
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

}  // namespace

PlotOutcome draw_bottom_loss_plot(const std::filesystem::path& dir, const std::string& title,
                                  const std::vector<std::string>& frequencies, const std::string& band,
                                  bool posterior_band) {
  std::ostringstream g;
  g << "set datafile separator ','\nset title " << quoted(title) << " noenhanced\n"
    << "set xlabel 'grazing angle (deg)'\nset ylabel 'bottom loss -20 log_{10}|R| (dB)'\n"
    << "set xrange [0:90]\nset yrange [0:*]\nset grid\nset key top left\n";
  g << "plot ";
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const std::string& f = frequencies[i];
    if (posterior_band) {  // shaded first, so that the curves lie on top
      const auto between = [&](int low, int high) {
        return "'reflection_band.csv' skip " + std::to_string(kReflectionBandCsvHeaderLines) + " using 2:($1==" + f +
               " ? $" + std::to_string(low) + " : NaN):($1==" + f + " ? $" + std::to_string(high) + " : NaN)";
      };
      g << (i ? ", \\\n  " : "") << between(3, 7) << " with filledcurves fs transparent solid 0.15 lc rgb '"
        << colour(i) << "' title " << quoted(f + " Hz posterior 95 %") << ", \\\n  " << between(4, 6)
        << " with filledcurves fs transparent solid 0.3 lc rgb '" << colour(i) << "' title "
        << quoted(f + " Hz posterior 68 %") << ", \\\n  ";
    } else if (i) {
      g << ", \\\n  ";
    }
    g << "'reflection.csv' skip " << kReflectionCsvHeaderLines << " using 2:($1==" << f
      << " ? $7 : NaN) with lines lw 1.5 lc rgb '" << colour(i) << "' title " << quoted(f + " Hz");
    if (!band.empty()) {
      g << ", \\\n  '' skip " << kReflectionCsvHeaderLines << " using 2:($1==" << f
        << " ? $9 : NaN) with lines lw 2 dt 2 lc rgb '" << colour(i) << "' title " << quoted(f + " Hz, " + band);
    }
  }
  g << "\n";
  return run_gnuplot(dir, "bottom_loss", "1000,700", g.str());
}

PlotOutcome draw_bottom_loss_fit_plot(const std::filesystem::path& dir, const std::string& title,
                                      const std::vector<double>& frequencies) {
  std::ostringstream g;
  g.precision(10);
  g << "set datafile separator ','\nset title " << quoted(title) << " noenhanced\n"
    << "set xlabel 'grazing angle (deg)'\nset ylabel 'bottom loss -20 log_{10}|R| (dB)'\n"
    << "set xrange [0:90]\nset grid\nset key top left\nplot ";
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    std::ostringstream f;
    f.precision(10);
    f << frequencies[i];
    g << (i ? ", \\\n  " : "") << "'bottom_loss_curves.csv' skip 2 using 2:($1==" << f.str()
      << " ? $3 : NaN) with lines lw 1.5 lc rgb '" << colour(i) << "' title " << quoted(f.str() + " Hz fit")
      << ", \\\n  'observations.csv' skip 4 using 10:($1==2 && $2==" << f.str()
      << " ? $3 : NaN):4 with yerrorbars pt 7 ps 0.6 lc rgb '" << colour(i) << "' title " << quoted(f.str() + " Hz data");
  }
  g << "\n";
  return run_gnuplot(dir, "bottom_loss_fit", "1000,700", g.str());
}

PlotOutcome draw_waves_plot(const std::filesystem::path& dir, const std::string& title,
                            const std::vector<std::string>& parts, const std::vector<bool>& has_shear) {
  std::ostringstream g;
  const auto curves = [&](int p_column, int s_column) {
    g << "plot ";
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const std::size_t k = i + 1;
      g << (i ? ", \\\n  " : "") << "'media.csv' skip " << kMediaCsvHeaderLines << " using 2:($1==" << k << " ? $"
        << p_column << " : NaN) with lines lw 1.5 lc rgb '" << colour(i) << "' title " << quoted(parts[i] + ": P");
      if (has_shear[i]) {
        g << ", \\\n  '' skip " << kMediaCsvHeaderLines << " using 2:($1==" << k << " ? $" << s_column
          << " : NaN) with lines lw 1.5 dt 2 lc rgb '" << colour(i) << "' title " << quoted(parts[i] + ": S");
      }
    }
    g << "\n";
  };
  g << "set datafile separator ','\nset multiplot layout 2,1 title " << quoted(title) << " noenhanced\n"
    << "set logscale x\nset format x '10^{%L}'\nset grid\nset key outside right\n"
    << "set xlabel 'frequency (Hz)'\nset ylabel 'phase speed (m/s)'\n";
  curves(3, 5);
  g << "set logscale y\nset format y '10^{%L}'\nset ylabel 'attenuation (dB/m)'\n";
  curves(4, 6);
  g << "unset multiplot\nunset logscale\nset format x '%g'\nset format y '%g'\n";
  return run_gnuplot(dir, "waves", "1150,1000", g.str());
}

}  // namespace sedwave::plot
