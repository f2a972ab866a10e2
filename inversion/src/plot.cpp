#include "sedwave/inversion/plot.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace sedwave::inversion {
namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Both panels; curves.csv columns: 1 f, 8/9 alpha dB/m and sigma, 10/11 speed m/s, 12/13 ratio.
std::string plot_body(const std::string& title, bool ratio_axis) {
  const int speed = ratio_axis ? 12 : 10;
  std::ostringstream g;
  g << "set multiplot layout 2,1 title " << '"' << title << '"' << "\n"
    << "set datafile separator ','\n"
    << "set grid\nset key top left\nset xrange [*:*] noextend\nset logscale xy\nset format y '10^{%L}'\nset format x '10^{%L}'\n"
    << "set xlabel 'frequency (Hz)'\nset ylabel 'attenuation (dB/m)'\n"
    << "plot 'curves.csv' skip 2 using 1:(($8-$9) > 0 ? $8-$9 : 1e-300):($8+$9) with filledcurves "
       "fc rgb '#cfe0f5' title 'fit {/Symbol \\261}1{/Symbol s}', \\\n"
    << "  '' skip 2 using 1:8 with lines lw 2 lc rgb '#1f5fbf' title 'fit', \\\n"
    << "  'observations.csv' skip 3 using 2:($1 == 0 ? $5 : NaN):6 with yerrorbars pt 7 ps 0.6 "
       "lc rgb '#c0392b' title 'observations'\n"
    << "unset logscale y\nset format y '%g'\n"
    << "set ylabel '" << (ratio_axis ? "sound speed / water sound speed" : "sound speed (m/s)") << "'\n"
    << "plot 'curves.csv' skip 2 using 1:($" << speed << "-$" << speed + 1 << "):($" << speed << "+$" << speed + 1
    << ") with filledcurves fc rgb '#cfe0f5' title 'fit {/Symbol \\261}1{/Symbol s}', \\\n"
    << "  '' skip 2 using 1:" << speed << " with lines lw 2 lc rgb '#1f5fbf' title 'fit', \\\n"
    << "  'observations.csv' skip 3 using 2:($1 == 1 ? $5 : NaN):6 with yerrorbars pt 7 ps 0.6 "
       "lc rgb '#c0392b' title 'observations'\n"
    << "unset multiplot\n";
  return g.str();
}

}  // namespace

PlotOutcome draw_fit_plot(const std::filesystem::path& dir, const std::string& title, bool ratio_axis) {
  const std::string body = plot_body(title, ratio_axis);
  {
    std::ofstream script(dir / "fit.gp");
    script << "# gnuplot script written by sedwave; re-run with: gnuplot fit.gp\n"
           << "set terminal pngcairo size 900,1000 enhanced font 'Sans,11'\nset output 'fit.png'\n"
           << body << "set terminal svg size 900,1000 enhanced font 'Sans,11'\nset output 'fit.svg'\n"
           << body;
    if (!script) return {false, "plot skipped: cannot write " + (dir / "fit.gp").string()};
  }
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    return {false, "plot skipped: gnuplot not found (apt-get install gnuplot-nox); script left in " +
                       (dir / "fit.gp").string()};
  }
  const std::string command = "cd " + shell_quote(dir.string()) + " && gnuplot fit.gp > gnuplot.log 2>&1";
  if (std::system(command.c_str()) != 0) {
    return {false, "plot skipped: gnuplot failed, see " + (dir / "gnuplot.log").string()};
  }
  return {true, "plot written to " + (dir / "fit.png").string() + " and fit.svg"};
}

}  // namespace sedwave::inversion
