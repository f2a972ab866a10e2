#pragma once
// How often the posterior's prior-controlled flag (PosteriorQuantity::prior_dominated) is raised on
// data sets where the answer is known by design. Shared by bench/prior_flag_rates.cpp (the full
// study) and tests/inversion/test_prior_flag.cpp (a small one).
//
// Both kinds of set: the lattice chain with free kappa, d, gamma under the default priors
// (log-uniform over the search bounds, what `sedwave invert --method posterior` uses without
// --prior), sound speed and attenuation at 20 log-spaced frequencies, each truth drawn log-uniform:
//   ridge sets: the band's top at omega_hat = omega sqrt(m / kappa) in [0.02, 0.1], a factor 100
//     wide: far below the lattice's dispersion the data see c0 = d sqrt(kappa / m) and
//     tau = gamma / kappa only, and kappa d gamma is unseen (a ridge through all three). Truths
//     around the held-out set that showed it: d in [0.3, 2] mm, c0 in [1500, 1900] m/s,
//     gamma_hat = gamma / sqrt(kappa m) in [5, 60]; 2-5 % attenuation noise, 0.5-1 % in speed.
//   well-determined sets: the band's top at omega_hat in [1.3, 1.9], a factor 20 wide: the data
//     resolve the dispersion and see all three. d in [0.1, 1] mm, c0 in [1500, 1900] m/s,
//     gamma_hat in [0.3, 3]; 1-3 % attenuation noise, 0.2-0.6 % in speed.
// Either prior: the default, or a site prior that knows each of kappa, d, gamma to a factor e
// (log-normal, sd of ln 1, its median the truth times e^N(0, 1)).
// A ridge set counts as flagged when all of kappa, d and gamma are flagged; a well-determined set
// counts as (falsely) flagged when any of them is.
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "sedwave/forward/theory/lattice.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::bench {

enum class FlagSet { Ridge, WellDetermined };
enum class FlagPriors { Default, Site };

struct FlagSetResult {
  std::array<bool, 3> flagged{};        ///< kappa, d, gamma
  std::array<double, 3> prior_share{};  ///< kappa, d, gamma
  bool c0_flagged = false, tau_flagged = false;  ///< the combinations the ridge sets do determine
  bool converged = false;
};

inline FlagSetResult run_flag_set(FlagSet kind, unsigned seed, int index, int steps,
                                  FlagPriors prior_kind = FlagPriors::Default) {
  std::mt19937_64 rng(seed * 1000033ull + static_cast<unsigned>(index) * 2ull + (kind == FlagSet::Ridge ? 0u : 1u));
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  const bool ridge = kind == FlagSet::Ridge;
  const double d = ridge ? log_uniform(3e-4, 2e-3) : log_uniform(1e-4, 1e-3);
  const double c0 = log_uniform(1500.0, 1900.0);
  const double gamma_hat = ridge ? log_uniform(5.0, 60.0) : log_uniform(0.3, 3.0);
  const double top_omega_hat = ridge ? log_uniform(0.02, 0.1) : log_uniform(1.3, 1.9);
  const double alpha_noise = ridge ? log_uniform(0.02, 0.05) : log_uniform(0.01, 0.03);
  const double speed_noise = alpha_noise / (ridge ? log_uniform(3.0, 5.0) : 5.0);

  inversion::FitParameters truth;
  const double density = truth.spec[truth.index_of("rho_s")].value;
  const double m = forward::grain_mass(density, d);
  const double kappa = c0 * c0 * m / (d * d);
  truth.spec[truth.index_of("kappa")].value = kappa;
  truth.spec[truth.index_of("d")].value = d;
  truth.spec[truth.index_of("gamma")].value = gamma_hat * std::sqrt(kappa * m);

  const forward::LatticeModel lattice;
  const auto frame = inversion::grain_contact_model(lattice, inversion::DampingForm::Gamma);
  const double top_hz = top_omega_hat * std::sqrt(kappa / m) / (2.0 * std::numbers::pi);
  const inversion::SyntheticDesign design{top_hz / (ridge ? 100.0 : 20.0), top_hz, 20, alpha_noise, speed_noise,
                                          seed * 7919u + static_cast<unsigned>(index)};
  const inversion::ObservationSet data = inversion::synthetic_observations(*frame, truth, design);
  const inversion::FitOptions fit_options{.method = inversion::FitMethod::Global, .profile_likelihood = false};
  const inversion::FitParameters start;  // kappa, d, gamma free from their defaults, as a user starts
  const inversion::FitResult best = inversion::fit(data, *frame, start, fit_options);
  std::vector<std::string> prior_items;
  if (prior_kind == FlagPriors::Site) {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const int i : {truth.index_of("kappa"), truth.index_of("d"), truth.index_of("gamma")}) {
      char item[96];
      std::snprintf(item, sizeof item, "%s=log-normal:%.17g,1", truth.spec[i].name.c_str(),
                    truth.spec[i].value * std::exp(normal(rng)));
      prior_items.emplace_back(item);
    }
  }
  const inversion::PosteriorResult posterior =
      inversion::sample_posterior(data, *frame, best, inversion::make_priors(best.fitted, prior_items), fit_options,
                                  {.steps = steps, .seed = seed + static_cast<unsigned>(index)});
  FlagSetResult r;
  r.converged = posterior.converged;
  for (std::size_t i = 0; i < 3; ++i) {
    r.flagged[i] = posterior.parameters[i].prior_dominated;
    r.prior_share[i] = posterior.parameters[i].prior_share;
  }
  for (const inversion::PosteriorQuantity& q : posterior.combinations) {
    if (q.name == "c0") r.c0_flagged = q.prior_dominated;
    if (q.name == "tau") r.tau_flagged = q.prior_dominated;
  }
  return r;
}

/// Whether the set counts as flagged (see the header comment).
inline bool set_flagged(FlagSet kind, const FlagSetResult& r) {
  return kind == FlagSet::Ridge ? r.flagged[0] && r.flagged[1] && r.flagged[2]
                                : r.flagged[0] || r.flagged[1] || r.flagged[2];
}

}  // namespace sedwave::bench
