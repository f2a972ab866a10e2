#pragma once
// How often the posterior's prior-controlled flag (PosteriorQuantity::prior_dominated) is raised on
// data sets where the answer is known by design. Shared by bench/prior_flag_rates.cpp (the full
// study) and tests/inversion/test_prior_flag.cpp (a small one).
//
// Every set: the lattice chain under the default priors (log-uniform over the search bounds, what
// `sedwave invert --method posterior` uses without --prior) or under site priors, each truth drawn
// log-uniform: d, c0 = d sqrt(kappa / m), gamma_hat = gamma / sqrt(kappa m) and the band's top in
// omega_hat = omega sqrt(m / kappa). Three kinds whose free parameters the data cannot place (every
// one should be flagged):
//   ridge: kappa, d, gamma free; sound speed and attenuation at 20 log-spaced frequencies, the top
//     at omega_hat in [0.02, 0.1], a factor 100 wide: far below the lattice's dispersion the data
//     see c0 and tau = gamma / kappa only, and kappa d gamma is unseen (a straight ridge through
//     all three). d in [0.3, 2] mm, c0 in [1500, 1900] m/s, gamma_hat in [5, 60]; 2-5 % attenuation
//     noise, 0.5-1 % in speed.
//   one-frequency ridge: the same truths, kappa, d, gamma free; ten rows of sound speed and ten of
//     attenuation at one frequency, omega_hat in [0.005, 0.05]: the two numbers are c0 and tau, and
//     kappa d gamma is unseen as in the ridge sets. (Nearer the dispersion, omega_hat in [0.05, 1],
//     the data bound kappa and gamma on both sides, over decades, and leave d open below: such a
//     set has no answer by design for kappa and gamma.)
//   curved ridge: ten rows of attenuation alone at one frequency (as a user with one measurement),
//     omega_hat in [0.05, 1]: one number for three parameters, a curved surface through the prior's
//     box, which the data's information at one draw does not see whole.
// and three whose free parameters the data determine (none should be flagged):
//   well-determined: kappa, d, gamma free; both quantities at 20 frequencies, the top at omega_hat
//     in [1.3, 1.9], a factor 20 wide: the data resolve the dispersion. d in [0.1, 1] mm, c0 in
//     [1500, 1900] m/s, gamma_hat in [0.3, 3]; 1-3 % attenuation noise, 0.2-0.6 % in speed.
//   one-frequency, d known: the same truths, d fixed at its true value (a measured grain size),
//     kappa and gamma free; ten rows of each quantity at one frequency, omega_hat in [0.1, 1].
//   curved valley, d known: kappa, gamma free; attenuation alone at 20 frequencies, the top at
//     omega_hat in [1.3, 1.9], a factor 20 wide: the frequency scale and the dashpot come from the
//     curve's shape, a valley that bends yet closes.
// Site priors know each free parameter to a factor e (log-normal, sd of ln 1, its median the truth
// times e^N(0, 1)). A set of the first three kinds counts as flagged when every free parameter is;
// one of the last three counts as (falsely) flagged when any is.
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

enum class FlagSet { Ridge, OneFrequencyRidge, CurvedRidge, WellDetermined, OneFrequencyKnownD, CurvedValleyKnownD };
enum class FlagPriors { Default, Site };

inline constexpr std::array<FlagSet, 6> kFlagSets{FlagSet::Ridge,          FlagSet::OneFrequencyRidge,
                                                  FlagSet::CurvedRidge,    FlagSet::WellDetermined,
                                                  FlagSet::OneFrequencyKnownD, FlagSet::CurvedValleyKnownD};

/// Whether the data leave every free parameter of such a set to the prior.
inline bool prior_controlled_by_design(FlagSet kind) {
  return kind == FlagSet::Ridge || kind == FlagSet::OneFrequencyRidge || kind == FlagSet::CurvedRidge;
}

inline const char* flag_set_name(FlagSet kind) {
  switch (kind) {
    case FlagSet::Ridge: return "ridge";
    case FlagSet::OneFrequencyRidge: return "one-frequency ridge";
    case FlagSet::CurvedRidge: return "curved ridge";
    case FlagSet::WellDetermined: return "well-determined";
    case FlagSet::OneFrequencyKnownD: return "one frequency, d known";
    case FlagSet::CurvedValleyKnownD: return "curved valley, d known";
  }
  return "";
}

struct FlagSetResult {
  std::array<bool, 3> flagged{};        ///< kappa, d, gamma (d: false where it is fixed)
  std::array<double, 3> prior_share{};  ///< kappa, d, gamma (d: 0 where it is fixed)
  bool d_free = true;
  bool c0_flagged = false, tau_flagged = false;  ///< the derived quantities the ridge sets do determine
  bool converged = false;
};

/// `rows` rows of attenuation (and, with `speed`, of sound speed) at one frequency, each noised as
/// inversion::synthetic_observations noises its rows.
inline inversion::ObservationSet one_frequency_rows(const sediment::SedimentModel& model,
                                                    const inversion::FitParameters& truth, double hz, int rows,
                                                    double alpha_noise, double speed_noise, bool speed,
                                                    std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const sediment::Wave w = model.evaluate(truth.values(), hz, false);
  inversion::ObservationSet set;
  for (int i = 0; i < rows; ++i) {
    const double alpha = w.attenuation * std::exp(alpha_noise * normal(rng));
    set.observations.push_back({inversion::Quantity::Attenuation, hz, alpha, alpha_noise * alpha, "Np/m", "synthetic", i + 1});
    if (speed) {
      set.observations.push_back({inversion::Quantity::SoundSpeed, hz, w.speed * (1.0 + speed_noise * normal(rng)),
                                  speed_noise * w.speed, "m/s", "synthetic", i + 1});
    }
  }
  return set;
}

/// Rows of the set's attenuation alone (the curved valley's band).
inline inversion::ObservationSet attenuation_only(inversion::ObservationSet set) {
  std::erase_if(set.observations, [](const inversion::Observation& o) { return o.quantity != inversion::Quantity::Attenuation; });
  return set;
}

/// `profiles`: the fit computes its likelihood profiles first, as `sedwave invert` does by default,
/// and the flag judges each credible interval against them too (posterior.hpp); without them it
/// has the posterior's own two tests only.
inline FlagSetResult run_flag_set(FlagSet kind, unsigned seed, int index, int steps,
                                  FlagPriors prior_kind = FlagPriors::Default, bool profiles = true) {
  // The first two kinds keep the streams they had before the others were added.
  const unsigned stream = kind == FlagSet::Ridge ? 0u : kind == FlagSet::WellDetermined ? 1u
                                                                                         : static_cast<unsigned>(kind) + 2u;
  std::mt19937_64 rng(seed * 1000033ull + static_cast<unsigned>(index) * 2ull + stream * (stream > 1 ? 7919ull : 1ull));
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  const bool ridge_truths = prior_controlled_by_design(kind);
  const bool one_frequency = kind == FlagSet::OneFrequencyRidge || kind == FlagSet::CurvedRidge ||
                             kind == FlagSet::OneFrequencyKnownD;
  const double d = ridge_truths ? log_uniform(3e-4, 2e-3) : log_uniform(1e-4, 1e-3);
  const double c0 = log_uniform(1500.0, 1900.0);
  const double gamma_hat = ridge_truths ? log_uniform(5.0, 60.0) : log_uniform(0.3, 3.0);
  const double top_omega_hat = kind == FlagSet::Ridge              ? log_uniform(0.02, 0.1)
                               : kind == FlagSet::OneFrequencyRidge ? log_uniform(0.005, 0.05)
                               : kind == FlagSet::OneFrequencyKnownD ? log_uniform(0.1, 1.0)
                               : kind == FlagSet::CurvedRidge       ? log_uniform(0.05, 1.0)
                                                                    : log_uniform(1.3, 1.9);
  const double alpha_noise = ridge_truths ? log_uniform(0.02, 0.05) : log_uniform(0.01, 0.03);
  const double speed_noise = alpha_noise / (ridge_truths ? log_uniform(3.0, 5.0) : 5.0);

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
  inversion::ObservationSet data;
  if (one_frequency) {
    data = one_frequency_rows(*frame, truth, top_hz, 10, alpha_noise, speed_noise, kind != FlagSet::CurvedRidge, rng);
  } else {
    const inversion::SyntheticDesign design{top_hz / (kind == FlagSet::Ridge ? 100.0 : 20.0), top_hz, 20, alpha_noise,
                                            speed_noise, seed * 7919u + static_cast<unsigned>(index)};
    data = inversion::synthetic_observations(*frame, truth, design);
    if (kind == FlagSet::CurvedValleyKnownD) data = attenuation_only(std::move(data));
  }
  const inversion::FitOptions fit_options{.method = inversion::FitMethod::Global, .profile_likelihood = profiles};
  inversion::FitParameters start;  // kappa, d, gamma free from their defaults, as a user starts
  const bool d_known = kind == FlagSet::OneFrequencyKnownD || kind == FlagSet::CurvedValleyKnownD;
  if (d_known) {
    start.spec[start.index_of("d")].value = d;
    start.spec[start.index_of("d")].free = false;
  }
  const inversion::FitResult best = inversion::fit(data, *frame, start, fit_options);
  std::vector<std::string> prior_items;
  if (prior_kind == FlagPriors::Site) {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const int i : {truth.index_of("kappa"), truth.index_of("d"), truth.index_of("gamma")}) {
      const double median = truth.spec[i].value * std::exp(normal(rng));
      if (!start.spec[i].free) continue;
      char item[96];
      std::snprintf(item, sizeof item, "%s=log-normal:%.17g,1", truth.spec[i].name.c_str(), median);
      prior_items.emplace_back(item);
    }
  }
  const inversion::PosteriorResult posterior =
      inversion::sample_posterior(data, *frame, best, inversion::make_priors(best.fitted, prior_items), fit_options,
                                  {.steps = steps, .seed = seed + static_cast<unsigned>(index)});
  FlagSetResult r;
  r.converged = posterior.converged;
  r.d_free = !d_known;
  for (const inversion::PosteriorQuantity& q : posterior.parameters) {
    const std::size_t i = q.name == "kappa" ? 0 : q.name == "d" ? 1 : 2;
    r.flagged[i] = q.prior_dominated;
    r.prior_share[i] = q.prior_share;
  }
  for (const inversion::PosteriorQuantity& q : posterior.derived) {
    if (q.name == "c0") r.c0_flagged = q.prior_dominated;
    if (q.name == "tau") r.tau_flagged = q.prior_dominated;
  }
  return r;
}

/// Whether the set counts as flagged (see the header comment).
inline bool set_flagged(FlagSet kind, const FlagSetResult& r) {
  return prior_controlled_by_design(kind) ? r.flagged[0] && (r.flagged[1] || !r.d_free) && r.flagged[2]
                                          : r.flagged[0] || r.flagged[1] || r.flagged[2];
}

}  // namespace sedwave::bench
