#include "sedwave/forward/experiment/interface_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "sedwave/forward/channel/fft.hpp"

namespace sedwave::forward::experiment {

SpectrumMoments spectrum_moments(const std::vector<double>& k, const std::vector<double>& energy) {
  double total = 0.0, first = 0.0;
  for (std::size_t m = 0; m < k.size(); ++m) total += energy[m], first += k[m] * energy[m];
  if (!(total > 0.0)) return {};
  const double mean = first / total;
  double second = 0.0;
  for (std::size_t m = 0; m < k.size(); ++m) second += (k[m] - mean) * (k[m] - mean) * energy[m];
  return {mean, second / total};
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  if (x.size() < 2) return {};
  double sx = 0.0, sy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i];
  const double mx = sx / n, my = sy / n;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0.0)) return {};
  const double slope = sxy / sxx;
  return {slope, my - slope * mx, syy > 0.0 ? sxy * sxy / (sxx * syy) : 1.0};
}

WavenumberSpread wavenumber_spread(const InterfaceRun& run, double density, double thickness, double spacing) {
  WavenumberSpread out;
  if (run.line_vx.empty()) return out;
  const std::size_t n = run.line_vx.front().size();
  const std::size_t n_fft = channel::next_power_of_two(n);
  for (std::size_t m = 0; m <= n_fft / 2; ++m)
    out.k.push_back(2.0 * std::numbers::pi * static_cast<double>(m) / (static_cast<double>(n_fft) * spacing));
  // Parseval: sum_n |v_n|^2 = (1/N) sum_m |V_m|^2; a strip of the plate's thickness, one node spacing
  // per node, holds (1/2) rho t spacing sum_n |v_n|^2 per unit depth. One-sided: interior bins twice.
  const double scale = 0.5 * density * thickness * spacing / static_cast<double>(n_fft);
  for (std::size_t s = 0; s < run.line_vx.size(); ++s) {
    const auto vx = channel::real_spectrum(run.line_vx[s], n_fft, channel::FourierSign::negative);
    const auto vy = channel::real_spectrum(run.line_vy[s], n_fft, channel::FourierSign::negative);
    std::vector<double> e(out.k.size());
    for (std::size_t m = 0; m < e.size(); ++m) {
      const double fold = (m == 0 || m == n_fft / 2) ? 1.0 : 2.0;
      e[m] = fold * scale * (std::norm(vx[m]) + std::norm(vy[m]));
    }
    double total = 0.0;
    for (const double x : e) total += x;
    out.line_energy.push_back(total);
    out.variance.push_back(spectrum_moments(out.k, e).variance);
    out.energy.push_back(std::move(e));
  }
  // Fit from the line's energy peak (the front has arrived) while it holds 1 % of that peak.
  const auto peak = std::max_element(out.line_energy.begin(), out.line_energy.end());
  out.first = static_cast<std::size_t>(peak - out.line_energy.begin());
  out.last = out.first;
  while (out.last < out.line_energy.size() && out.line_energy[out.last] >= 0.01 * *peak) ++out.last;
  std::vector<double> t(run.series.time.begin() + static_cast<std::ptrdiff_t>(out.first),
                        run.series.time.begin() + static_cast<std::ptrdiff_t>(out.last));
  std::vector<double> v(out.variance.begin() + static_cast<std::ptrdiff_t>(out.first),
                        out.variance.begin() + static_cast<std::ptrdiff_t>(out.last));
  out.growth = fit_line(t, v);
  return out;
}

}  // namespace sedwave::forward::experiment
