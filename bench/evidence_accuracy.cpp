// Is the evidence as accurate as it says? For every model family (sediment::model_examples()), on
// many synthetic sets it generated (its defaults; 20 log-spaced frequencies over 100 Hz - 100 kHz,
// 5 % attenuation and 1 % sound-speed noise, a different noise realisation per set), with two free
// parameters (the first two of its typical set) under default priors: ln Z from model_evidence
// (default options: importance sampling where its diagnostics allow, parallel tempering elsewhere;
// its seed the set's index plus 1000 per family) against brute-force quadrature of the same integral
// (inversion::evidence_integrand) on the same data. A deterministic method gives one answer per data
// set, so the data vary as well as the seeds. Prints per family the sets within 2 stated sigmas
// (>= 90 % expected), the mean difference with its standard error (within 2 of 0 expected), which
// method served, the likelihood evaluations of the evidence and of the fit's global search; and
// every set that fell back or landed outside 2 stated sigmas, with the refusal or the proposal.
//
// Then the cases the fast path must refuse, each against its own quadrature:
//   ridge:   the lattice chain's kappa and d from sound speeds alone at 100-300 Hz, far below its
//            dispersion (they see c0 = d sqrt(kappa/m) only: a ridge that the default priors'
//            bounds close);
//   bound:   EDFM's porosity and permeability under a log-uniform permeability prior whose upper
//            end lies half a linearised sd above the best fit (the posterior is cut there);
//   bimodal: Biot-Stoll's porosity and permeability from a narrow band (bench/bimodal_case.hpp):
//            two modes, on either side of Biot's attenuation peak in permeability (the
//            quadrature's share of each is printed; every set asked for, the others 5 at most).
//
// The quadrature: bench/evidence_quadrature.hpp (n x n, default 150, then 2n x 2n); its change
// from n to 2n is printed as the reference's own error.
//
//   build/bin/bench_evidence_accuracy [sets=20] [model-substring | =model | ridge | bound | bimodal] [n=150] [method]
//   method: automatic (default: model_evidence's default options), cubature (adaptive cubature on
//   every set, parallel tempering where it fails: its accuracy on every posterior, not only the refused
//   ones) or tempering (parallel tempering on every set: the general fallback's own accuracy)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bimodal_case.hpp"
#include "evidence_quadrature.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using namespace sedwave;

const inversion::FitOptions kFitOptions{.method = inversion::FitMethod::Global, .profile_likelihood = false};
inversion::EvidenceMethod evidence_method = inversion::EvidenceMethod::Automatic;

struct Tally {
  int sets = 0, within = 0, importance = 0, cubature = 0;
  double sum = 0.0, sum_squares = 0.0, stated = 0.0, largest_stated = 0.0, seconds = 0.0, refinement = 0.0;
  long evaluations = 0, largest_evaluations = 0, fit_evaluations = 0;

  void add(const inversion::ModelEvidence& e, const bench::QuadratureEvidence& q, const inversion::FitResult& best,
           double run_seconds) {
    const double d = e.log_evidence - q.log_evidence;
    ++sets;
    within += std::abs(d) <= 2.0 * e.uncertainty;
    importance += e.method == inversion::kImportanceSamplingMethod;
    cubature += e.method == inversion::kCubatureMethod;
    sum += d;
    sum_squares += d * d;
    stated += e.uncertainty;
    largest_stated = std::max(largest_stated, e.uncertainty);
    evaluations += e.evaluations;
    largest_evaluations = std::max(largest_evaluations, static_cast<long>(e.evaluations));
    fit_evaluations += best.global ? best.global->evaluations : 0;
    refinement = std::max(refinement, q.refinement);
    seconds += run_seconds;
  }
  void print(const std::string& name, const std::string& free) const {
    const double mean = sum / sets;
    const double sd = sets > 1 ? std::sqrt(std::max(0.0, (sum_squares - sets * mean * mean) / (sets - 1.0))) : 0.0;
    std::printf("%-22s %-22s %4d/%-4d %7.3f +- %5.3f %7.3f %7.3f %7.3f %3d/%3d/%-3d %8ld %8ld %7ld %7.3f %7.2f\n",
                name.c_str(), free.c_str(), within, sets, mean, sd / std::sqrt(sets), sd, stated / sets,
                largest_stated, importance, cubature, sets - importance - cubature, evaluations / sets, largest_evaluations, fit_evaluations / sets,
                refinement, seconds / sets);
    std::fflush(stdout);
  }
};

/// The model's parameters at their defaults with `free` free.
inversion::FitParameters free_start(const sediment::SedimentModel& model, const std::string& free) {
  inversion::FitParameters start(model.parameters());
  start.set_free_from_list(free);
  return start;
}

/// One set: fit, quadrature, model_evidence.
void run_set(Tally& tally, const sediment::SedimentModel& model, const inversion::ObservationSet& data,
             const inversion::FitParameters& start, const std::vector<std::string>& prior_items, unsigned data_seed,
             unsigned seed, int n, bool upper_at_fit = false, const char* verbose = nullptr) {
  const inversion::FitResult best = inversion::fit(data, model, start, kFitOptions);
  std::vector<std::string> items = prior_items;
  if (upper_at_fit) {
    // A log-uniform prior on the second free parameter from a factor 1e3 below the fit to half its
    // linearised sd above it: the posterior's peak lies at the bound.
    const int i = best.fitted.free_indices()[1];
    const double v = best.fitted.spec[static_cast<std::size_t>(i)].value *
                     std::exp(0.5 * best.parameters[static_cast<std::size_t>(i)].log_sigma);
    char item[128];
    std::snprintf(item, sizeof item, "%s=log-uniform:%.17g,%.17g", best.fitted.spec[static_cast<std::size_t>(i)].name.c_str(),
                  v * 1e-3, v);
    items.emplace_back(item);
  }
  const std::vector<inversion::Prior> priors = inversion::make_priors(best.fitted, items);
  const sampling::PriorAndLikelihood f = inversion::evidence_integrand(data, model, best, priors, kFitOptions);
  const bench::QuadratureEvidence q = bench::quadrature_evidence(f, best, n);
  inversion::EvidenceOptions options;
  options.seed = seed;
  options.method = evidence_method;
  const auto t0 = std::chrono::steady_clock::now();
  const inversion::ModelEvidence e = inversion::model_evidence(data, model, best, priors, kFitOptions, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  tally.add(e, q, best, seconds);
  const bool outside = std::abs(e.log_evidence - q.log_evidence) > 2.0 * e.uncertainty;
  for (int k = 0; k < 2; ++k) {
    // Modes of less than a thousandth of the mass change ln Z by less than any stated error.
    if (q.mode_shares[k].size() < 2 || *std::min_element(q.mode_shares[k].begin(), q.mode_shares[k].end()) < 1e-3) continue;
    std::printf("  %s set %u: the quadrature's marginal of ln %s has %zu modes, with", verbose ? verbose : model.name().c_str(),
                data_seed, best.fitted.spec[static_cast<std::size_t>(best.fitted.free_indices()[static_cast<std::size_t>(k)])].name.c_str(),
                q.mode_shares[k].size());
    for (const double share : q.mode_shares[k]) std::printf(" %.3f", share);
    std::printf(" of the mass (in order of the parameter)\n");
  }
  for (const inversion::LocalMinimum& m : best.other_minima) {
    std::printf("  %s set %u: the fit found another local minimum, chi^2 %.2f (the fit's %.2f) at", verbose ? verbose : model.name().c_str(),
                data_seed, m.chi2, best.chi2);
    for (const int i : best.fitted.free_indices()) {
      std::printf(" %s %.4g", best.fitted.spec[static_cast<std::size_t>(i)].name.c_str(), m.values[static_cast<std::size_t>(i)]);
    }
    std::printf("\n");
  }
  if (verbose || !e.fallback_reason.empty() || outside) {
    std::printf("  %s set %u%s: ln Z %.3f +- %.3f (%s, %d evaluations), quadrature %.3f (+- %.3f); %s\n",
                verbose ? verbose : model.name().c_str(), data_seed, outside ? " (outside 2 sd)" : "",
                e.log_evidence, e.uncertainty, e.method.c_str(), e.evaluations, q.log_evidence, q.refinement,
                e.fallback_reason.empty() ? ("fast path accepted: " + e.advice).c_str()
                                          : ("refused: " + e.fallback_reason + "; " + e.advice).c_str());
  }
}

inversion::SyntheticDesign design(unsigned seed) { return {100.0, 1e5, 20, 0.05, 0.01, seed}; }

}  // namespace

int main(int argc, char** argv) {
  const int sets = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::string only = argc > 2 ? argv[2] : "";
  const int n = argc > 3 ? std::atoi(argv[3]) : 150;
  const std::string method = argc > 4 ? argv[4] : "automatic";
  if (method != "automatic" && method != "cubature" && method != "tempering") {
    std::fprintf(stderr, "bench_evidence_accuracy: method must be automatic, cubature or tempering, not '%s'\n",
                 method.c_str());
    return 2;
  }
  if (method == "cubature") evidence_method = inversion::EvidenceMethod::Cubature;
  if (method == "tempering") evidence_method = inversion::EvidenceMethod::Tempering;
  std::printf("evidence accuracy: model_evidence (%s) on %d noise realisations per family against "
              "quadrature (n = %d); 2 free parameters, default priors\n",
              method == "cubature"    ? "adaptive cubature on every set"
              : method == "tempering" ? "parallel tempering on every set"
                                      : "default options", sets, n);
  std::printf("%-22s %-22s %9s %16s %7s %7s %7s %10s %8s %8s %7s %7s %7s\n", "model", "free", "in 2 sd",
              "mean diff +- se", "sd", "stated", "max st", "IS/AC/PT", "evals", "max ev", "fit ev", "quad +-",
              "s/set");
  if (only != "ridge" && only != "bound" && only != "bimodal") {
    unsigned family = 0;
    for (const auto& model : sediment::model_examples()) {
      ++family;
      const std::string name = model->name();
      if (!only.empty() && (only.front() == '=' ? name != only.substr(1) : name.find(only) == std::string::npos)) continue;
      const std::string typical = sediment::typical_free_parameters(*model);
      const std::string free = typical.substr(0, typical.find(',', typical.find(',') + 1));
      Tally tally;
      for (int set = 1; set <= sets; ++set) {
        const auto seed = static_cast<unsigned>(set);
        const inversion::ObservationSet data =
            inversion::synthetic_observations(*model, inversion::FitParameters(model->parameters()), design(seed));
        // The sampler's seed differs between families: on near-Gaussian posteriors the same seed
        // would give every family the same importance-sampling errors.
        run_set(tally, *model, data, free_start(*model, free), {}, seed, seed + 1000u * family, n);
      }
      tally.print(name, free);
    }
  }
  if (only.empty() || only == "ridge") {
    const auto chain = sediment::make_sediment_model("lattice");
    Tally tally;
    for (int set = 1; set <= std::min(sets, 5); ++set) {
      inversion::ObservationSet data =
          inversion::synthetic_observations(*chain, inversion::FitParameters(chain->parameters()),
                                            {100.0, 300.0, 20, 0.05, 0.01, 100u + static_cast<unsigned>(set)});
      std::erase_if(data.observations, [](const inversion::Observation& o) { return o.quantity != inversion::Quantity::SoundSpeed; });
      const auto seed = 100u + static_cast<unsigned>(set);
      run_set(tally, *chain, data, free_start(*chain, "kappa,d"), {}, seed, seed, n, false, "ridge");
    }
    tally.print("ridge: lattice", "kappa,d (speeds only)");
  }
  if (only.empty() || only == "bound") {
    const auto edfm = sediment::make_sediment_model("edfm");
    Tally tally;
    for (int set = 1; set <= std::min(sets, 5); ++set) {
      const inversion::ObservationSet data =
          inversion::synthetic_observations(*edfm, inversion::FitParameters(edfm->parameters()), design(200u + set));
      const auto seed = 200u + static_cast<unsigned>(set);
      run_set(tally, *edfm, data, free_start(*edfm, "porosity,permeability"), {}, seed, seed, n, true, "bound");
    }
    tally.print("bound: edfm", "permeability cut at fit");
  }
  if (only.empty() || only == "bimodal") {
    const bench::BimodalCase bimodal;
    Tally tally;
    // Cheap (about 0.03 s a set by the cubature): every set asked for, not 5 at most.
    for (int set = 1; set <= sets; ++set) {
      const auto seed = 300u + static_cast<unsigned>(set);
      run_set(tally, *bimodal.model, bimodal.data(seed), bimodal.start, {}, seed, seed, n, false, "bimodal");
    }
    tally.print("bimodal: biot-stoll", "k at 200-210 Hz");
  }
  return 0;
}
