// Does the default posterior converge? Synthetic sets with fixed seeds, 5 per model family
// (the dry lattice chain, the saturated chain with its permeability from Kozeny-Carman or as a
// parameter of its own, Biot-Stoll, EDFM, grain-shearing, VGS(lambda), in this order): the
// truth is the family's defaults with each of its typical free parameters (2-3,
// sediment::typical_free_parameters) moved by a factor e^(0.3 N(0,1)); 20 log-spaced frequencies
// over 100 Hz - 100 kHz, 5 % attenuation and 1 % sound-speed noise. Each set is fitted (global) with
// those parameters free, then sampled with sample_posterior's defaults (an adaptive run length,
// capped by PosteriorOptions::steps) under default priors; prints per set the steps run, the
// largest autocorrelation time, the smallest ESS, the widest 95 % interval (ln of its upper over its
// lower end: a run that missed part of a ridge shows a narrower one), the rungs of its tempering
// ladder (0: one ensemble), the wall time and whether it converged. With --quadrature, also each
// parameter's 95 % interval width (ln) against brute-force quadrature of the same posterior
// (marginal_quadrature.hpp; about 10^6 evaluations per set).
//
//   build/bin/bench_posterior_defaults [--quadrature] [sets per family=5]
//                                      [DIR: also write the sets there as CSV; - none]
//                                      [FAMILY...: only these families, by their index in the table (0-6)]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "marginal_quadrature.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/saturated_granular.hpp"

namespace {

using namespace sedwave;

struct SyntheticSet {
  std::shared_ptr<const sediment::SedimentModel> model;
  inversion::FitParameters truth;  ///< free: the parameters to fit
  inversion::ObservationSet data;
  unsigned seed = 0;
};

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    out.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

// Set `index` of a family, from fixed seeds: the same sets on every machine and run.
SyntheticSet make_set(const std::shared_ptr<const sediment::SedimentModel>& model, std::size_t family, int index) {
  SyntheticSet set{model, inversion::FitParameters(model->parameters()), {}, 0};
  set.seed = static_cast<unsigned>(1000 * family + static_cast<std::size_t>(index) + 1);
  std::mt19937_64 rng(set.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::vector<std::string> typical = split(sediment::typical_free_parameters(*model));
  for (const std::string& name : typical) {
    auto& spec = set.truth.spec[set.truth.index_of(name)];
    spec.value = std::clamp(spec.value * std::exp(0.3 * normal(rng)), spec.lower * 1.01, spec.upper / 1.01);
  }
  const inversion::SyntheticDesign design{100.0, 1e5, 20, 0.05, 0.01, set.seed};
  set.data = inversion::synthetic_observations(*model, set.truth, design);
  set.truth.set_free_from_list(sediment::typical_free_parameters(*model));
  return set;
}

// The 7 families in a fixed order (the order of the seeds): sediment::model_examples(), with the
// saturated chain also in its Kozeny-Carman form (permeability from d and porosity), just before the
// form with permeability as a parameter, which the catalog lists.
std::vector<std::shared_ptr<const sediment::SedimentModel>> bench_families() {
  std::vector<std::shared_ptr<const sediment::SedimentModel>> out;
  for (auto& model : sediment::model_examples()) {
    const auto* saturated = dynamic_cast<const sediment::SaturatedGranularModel*>(model.get());
    if (saturated && saturated->permeability_from() == sediment::PermeabilityFrom::Parameter) {
      out.push_back(sediment::make_sediment_model(model->name(), {sediment::DampingForm::Gamma, false}));
    }
    out.push_back(model);
  }
  return out;
}

std::string label(const sediment::SedimentModel& model) {
  const auto* saturated = dynamic_cast<const sediment::SaturatedGranularModel*>(&model);
  if (!saturated) return model.name();
  return model.name() + (saturated->permeability_from() == sediment::PermeabilityFrom::Parameter
                             ? " (permeability a parameter)"
                             : " (Kozeny-Carman)");
}

std::string free_names(const inversion::FitParameters& p) {
  std::string out;
  for (int i : p.free_indices()) out += (out.empty() ? "" : ",") + p.spec[i].name;
  return out;
}

// Each free parameter's 95 % width (ln) in the samples and by quadrature, on one line.
void print_against_quadrature(const SyntheticSet& set, const inversion::FitResult& best,
                              const inversion::FitOptions& fit_options, const inversion::PosteriorResult& p) {
  const auto integrand =
      inversion::evidence_integrand(set.data, *set.model, best, inversion::make_priors(best.fitted, {}), fit_options);
  const bench::MarginalIntervals reference = bench::marginal_intervals_by_quadrature(integrand, best);
  std::printf("     95 %% widths (ln), sampled / quadrature:");
  for (std::size_t j = 0; j < p.parameters.size(); ++j) {
    const auto& q = p.parameters[j];
    std::printf(" %s %.2f / %.2f%s", q.name.c_str(), std::log(q.upper_95 / q.lower_95),
                reference.upper_95[j] - reference.lower_95[j], reference.resolved[j] ? "" : " (unresolved)");
  }
  if (p.parameters.size() == 3) {
    const bench::MarginalIntervals slices = bench::marginal_intervals_by_slices(integrand, reference.box);
    std::printf("; by slices:");
    for (std::size_t j = 0; j < 3; ++j) std::printf(" %.2f", slices.upper_95[j] - slices.lower_95[j]);
  }
  // Draws outside the box the quadrature integrated: mass that its coarse first grid did not see.
  Eigen::Index outside = 0;
  for (Eigen::Index r = 0; r < p.samples.rows(); ++r) {
    for (std::size_t j = 0; j < p.parameters.size(); ++j) {
      const double x = std::log(p.samples(r, static_cast<Eigen::Index>(j)));
      if (x < reference.box.lo[j] || x > reference.box.hi[j]) {
        ++outside;
        break;
      }
    }
  }
  std::printf("; draws outside its box %.1f %%\n",
              100.0 * static_cast<double>(outside) / static_cast<double>(p.samples.rows()));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const auto flag = std::find(args.begin(), args.end(), "--quadrature");
  const bool quadrature = flag != args.end();
  if (quadrature) args.erase(flag);
  const int per_family = args.size() > 0 ? std::atoi(args[0].c_str()) : 5;
  const std::filesystem::path dir = args.size() > 1 && args[1] != "-" ? args[1] : "";
  std::vector<std::size_t> only;
  for (std::size_t a = 2; a < args.size(); ++a) only.push_back(static_cast<std::size_t>(std::atoi(args[a].c_str())));
  if (!dir.empty()) std::filesystem::create_directories(dir);
  const inversion::PosteriorOptions defaults;
  std::printf("default posterior (cap %d steps, checked every %d) on %d synthetic sets per family\n", defaults.steps,
              defaults.check_every, per_family);
  std::printf("%-40s %4s %-24s %6s %7s %7s %6s %6s %5s %7s %s\n", "model", "set", "free", "steps", "tau", "ESS",
              "accept", "ln95", "rungs", "s", "verdict");
  int sets = 0, converged = 0;
  double longest = 0.0;
  const auto families = bench_families();
  for (std::size_t f = 0; f < families.size(); ++f) {
    if (!only.empty() && std::find(only.begin(), only.end(), f) == only.end()) continue;
    for (int k = 0; k < per_family; ++k) {
      const SyntheticSet set = make_set(families[f], f, k);
      const std::string name = label(*families[f]);
      if (!dir.empty()) {
        inversion::write_observation_csv(
            dir / ("set_" + std::to_string(f) + "_" + std::to_string(k) + ".csv"), set.data,
            {"synthetic set " + std::to_string(k) + " of " + name + ", seed " + std::to_string(set.seed) +
             " (bench/posterior_defaults.cpp); free: " + free_names(set.truth)});
      }
      const inversion::FitOptions fit_options{.method = inversion::FitMethod::Global, .profile_likelihood = false};
      const inversion::FitResult best = inversion::fit(set.data, *set.model, set.truth, fit_options);
      const inversion::PosteriorResult p = inversion::sample_posterior(
          set.data, *set.model, best, inversion::make_priors(best.fitted, {}), fit_options, defaults);
      double tau = 0.0, ess = 1e300, width = 0.0;
      for (const auto& q : p.parameters) {
        width = std::max(width, std::log(q.upper_95 / q.lower_95));
        tau = std::max(tau, static_cast<double>(p.steps - p.steps / 2) * p.walkers / q.effective_samples);
        ess = std::min(ess, q.effective_samples);
      }
      ++sets;
      converged += p.converged;
      longest = std::max(longest, p.wall_seconds);
      std::printf("%-40s %4d %-24s %6d %7.1f %7.0f %6.2f %6.2f %5d %7.2f %s\n", name.c_str(), k,
                  free_names(set.truth).c_str(), p.steps, tau, ess, p.acceptance, width, p.temperatures,
                  p.wall_seconds, p.converged ? "converged" : "NOT CONVERGED");
      if (quadrature) print_against_quadrature(set, best, fit_options, p);
      std::fflush(stdout);
    }
  }
  std::printf("%d of %d converged; longest run %.1f s\n", converged, sets, longest);
  return converged == sets ? 0 : 3;
}
