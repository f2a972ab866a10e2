#pragma once
// Coverage of the 68 % profile-likelihood intervals that `sedwave invert` reports: synthetic data
// sets drawn from known parameters (lattice chain model) are fitted back, and each interval of a
// parameter or derived quantity is checked for the truth. A calibrated interval contains it in 68 % of
// the data sets. Shared by bench/profile_coverage.cpp (the full study) and a small ctest version.
//
// Draws, each log-uniform: gamma_hat in [0.01, 300], d in [0.05, 2] mm, attenuation noise in
// [1, 10] % (sound-speed noise a fifth of it, as in field data), low-frequency speed in
// [1500, 1900] m/s (fixes kappa = c0^2 m / d^2), and the band's top omega_hat in [0.05, 1.9]
// (frequencies over a factor 500 below it, 30 points): from data that see only the continuum limit
// (d unseen) to data that resolve the lattice's dispersion.
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/plausibility.hpp"
#include "sedwave/inversion/residuals.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::bench {

/// The quantities whose intervals are checked, in report order.
inline const std::array<const char*, 8> kCoverageQuantities{"kappa", "d",         "gamma",           "c0",
                                                            "tau",   "gamma_hat", "kappa_over_hertz", "f_star"};

struct Truth {
  inversion::FitParameters parameters;
  std::array<double, 8> values;  ///< of kCoverageQuantities
  double gamma_hat, top_omega_hat, alpha_noise;
};

inline Truth draw_truth(std::mt19937_64& rng) {
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  Truth t;
  t.gamma_hat = log_uniform(0.01, 300.0);
  const double d = log_uniform(5e-5, 2e-3);
  t.alpha_noise = log_uniform(0.01, 0.10);
  const double c0 = log_uniform(1500.0, 1900.0);
  t.top_omega_hat = log_uniform(0.05, 1.9);
  const double density = 2650.0;
  const double m = forward::grain_mass(density, d);
  const double kappa = c0 * c0 * m / (d * d);
  const double gamma = t.gamma_hat * std::sqrt(kappa * m);
  t.parameters.spec[t.parameters.index_of("rho_s")].value = density;
  t.parameters.spec[t.parameters.index_of("kappa")].value = kappa;
  t.parameters.spec[t.parameters.index_of("d")].value = d;
  t.parameters.spec[t.parameters.index_of("gamma")].value = gamma;
  const double tau = gamma / kappa;
  t.values = {kappa, d, gamma, c0, tau, t.gamma_hat, kappa / inversion::quartz_hertz_kappa(d),
              1.0 / (2.0 * std::numbers::pi * tau)};
  return t;
}

/// One quantity's interval in one data set.
struct IntervalCheck {
  bool contains = false;    ///< the truth lies in the interval (an open end reaches the search bound)
  bool closed = false;      ///< both ends finite
  bool determined = false;  ///< the report calls the quantity determined (closed, narrow, not at a bound)
  /// The design determines it: the linearised analysis of noise-free data at the truth (which
  /// depends on the band, the sigmas and the truth, not on the noise drawn) calls it determined.
  /// Coverage among these is free of the selection effect of conditioning on the noisy data.
  bool design_determined = false;
};

struct DataSetResult {
  Truth truth;
  std::array<IntervalCheck, 8> checks;
  double chi2 = 0.0;
  int dof = 0;
};

/// The linearised analysis at the truth of the data's noise-free values (same band and sigmas).
inline inversion::FitResult design_analysis(const inversion::ObservationSet& data, const forward::DispersionModel& model,
                                            const inversion::FitParameters& truth) {
  inversion::ObservationSet clean = data;
  const auto frame = inversion::grain_contact_model(model, truth.damping_form());
  const std::vector<double> values = truth.values();
  for (inversion::Observation& o : clean.observations) {
    o.value = inversion::predicted_value(o, frame->evaluate(values, o.frequency_hz, false));
  }
  inversion::FitOptions linear;
  linear.method = inversion::FitMethod::Ceres;
  linear.profile_likelihood = false;
  return inversion::fit(clean, model, truth, linear);
}

/// Synthesises data set `index` of a study seeded by `seed`, fits it back, checks each interval.
inline DataSetResult run_data_set(unsigned seed, int index) {
  std::mt19937_64 rng(seed * 1000003ull + static_cast<unsigned>(index));
  DataSetResult r;
  r.truth = draw_truth(rng);
  const forward::LatticeModel lattice;
  const double m = forward::grain_mass(r.truth.parameters.spec[r.truth.parameters.index_of("rho_s")].value, r.truth.values[1]);
  const double omega_scale = std::sqrt(r.truth.values[0] / m);  // omega = omega_hat sqrt(kappa/m)
  const double top_hz = r.truth.top_omega_hat * omega_scale / (2.0 * std::numbers::pi);
  const inversion::SyntheticDesign design{top_hz / 500.0, top_hz, 30, r.truth.alpha_noise,
                                          r.truth.alpha_noise / 5.0, seed * 7919u + static_cast<unsigned>(index)};
  const inversion::ObservationSet data = inversion::synthetic_observations(lattice, r.truth.parameters, design);
  const inversion::FitResult fit = inversion::fit(data, lattice, inversion::FitParameters{}, inversion::FitOptions{});
  const inversion::FitResult at_truth = design_analysis(data, lattice, r.truth.parameters);
  r.chi2 = fit.chi2;
  r.dof = fit.dof;
  auto check = [](double truth, const std::optional<double>& lo, const std::optional<double>& hi, bool determined) {
    return IntervalCheck{(!lo || truth >= *lo) && (!hi || truth <= *hi), lo.has_value() && hi.has_value(), determined};
  };
  for (size_t q = 0; q < kCoverageQuantities.size(); ++q) {
    const std::string name = kCoverageQuantities[q];
    for (const auto& p : fit.parameters) {
      if (p.name == name) r.checks[q] = check(r.truth.values[q], p.profile_lower, p.profile_upper, p.determined);
    }
    for (const auto& c : fit.derived) {
      if (c.name == name) r.checks[q] = check(r.truth.values[q], c.profile_lower, c.profile_upper, c.determined);
    }
    for (const auto& p : at_truth.parameters) {
      if (p.name == name) r.checks[q].design_determined = p.determined;
    }
    for (const auto& c : at_truth.derived) {
      if (c.name == name) r.checks[q].design_determined = c.determined;
    }
  }
  return r;
}

/// Binomial 1-sigma of a coverage estimated from n data sets at the nominal rate p.
inline double coverage_sigma(int n, double p = 0.68) { return std::sqrt(p * (1.0 - p) / std::max(n, 1)); }

}  // namespace sedwave::bench

namespace sedwave::bench {

/// Whether each open side of a parameter's interval is really open. A side is open where chi^2 stays
/// within 1 of its minimum up to the parameter's search bound, or where only the other parameters'
/// search bounds raise it (profile.hpp: along kappa d gamma, d reaches its bound first). So the fit
/// with that parameter fixed at its search bound must lie within Delta chi^2 = 1 (+ 0.05 for the
/// solvers' tolerance) of the best fit: refitted by the global search within the search bounds, or
/// else with the other parameters' bounds lifted (widened 10^12 times each way), refitted locally
/// from the best fit moved along the unseen kappa d gamma (all three scaled by the factor that takes
/// the held one to its bound: c0 and tau stay). Returns {sides checked, sides that are not open}.
inline std::pair<int, int> verify_open_sides(unsigned seed, int index) {
  std::mt19937_64 rng(seed * 1000003ull + static_cast<unsigned>(index));
  const Truth truth = draw_truth(rng);
  const forward::LatticeModel lattice;
  const double m = forward::grain_mass(truth.parameters.spec[truth.parameters.index_of("rho_s")].value, truth.values[1]);
  const double top_hz = truth.top_omega_hat * std::sqrt(truth.values[0] / m) / (2.0 * std::numbers::pi);
  const inversion::SyntheticDesign design{top_hz / 500.0, top_hz, 30, truth.alpha_noise, truth.alpha_noise / 5.0,
                                          seed * 7919u + static_cast<unsigned>(index)};
  const inversion::ObservationSet data = inversion::synthetic_observations(lattice, truth.parameters, design);
  const inversion::FitResult fit = inversion::fit(data, lattice, inversion::FitParameters{}, inversion::FitOptions{});
  int checked = 0, wrong = 0;
  const inversion::FitOptions quick{.profile_likelihood = false};
  const inversion::FitOptions local{.method = inversion::FitMethod::Ceres, .profile_likelihood = false};
  const std::vector<int> free = fit.fitted.free_indices();  // kappa, d, gamma
  for (const int i : free) {
    const auto& p = fit.parameters[static_cast<size_t>(i)];
    for (bool lower : {true, false}) {
      if ((lower ? p.profile_lower : p.profile_upper).has_value()) continue;
      inversion::FitParameters held = fit.fitted;
      held.spec[i].value = lower ? held.spec[i].lower : held.spec[i].upper;
      held.spec[i].free = false;
      ++checked;
      if (inversion::fit(data, lattice, held, quick).chi2 <= fit.chi2 + 1.05) continue;
      const double scale = held.spec[i].value / p.value;
      for (const int j : free) {
        if (j == i) continue;
        held.spec[j].lower *= 1e-12;
        held.spec[j].upper *= 1e12;
        held.spec[j].value *= scale;
      }
      if (inversion::fit(data, lattice, held, local).chi2 > fit.chi2 + 1.05) ++wrong;
    }
  }
  return {checked, wrong};
}

}  // namespace sedwave::bench
