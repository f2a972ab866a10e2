// How often model comparison by evidence ranks first the model that generated the data, per band
// (50 Hz - 1 kHz, 2-8 kHz, 10-400 kHz, and their union) and per generating model, at field noise
// (7 % attenuation, 0.7 % sound speed; 15 log-spaced frequencies). Candidates: EDFM, Biot-Stoll, GS,
// VGS(lambda), each at its defaults as the truth and fitted with its typical free parameters under
// default (log-uniform) priors. A realisation counts as "indistinguishable" when the generator is not
// first but trails the first by less than max(1, twice the combined ln Z uncertainty). A last row
// ranks the same models on reflection data instead: bottom loss of each as a half-space under
// 1500 m/s water at 1, 2 and 4 kHz and grazing angles 5-85 deg every 10 deg, 1 dB Gaussian noise.
//
//   build/bin/bench_model_ranking [realisations=5] [steps=800] [temperatures=16] [rows=all|reflection]
#include <cmath>
#include <numbers>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/posterior.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace {

using namespace sedwave;

struct Band {
  const char* name;
  double lowest_hz, highest_hz;
  bool reflection = false;  ///< bottom-loss rows only (at 3 log-spaced frequencies), no attenuation or speed
};

/// The synthetic data of a band: attenuation and speed at 15 frequencies (field noise), or bottom loss.
inversion::SyntheticDesign design_of(const Band& band, unsigned seed) {
  inversion::SyntheticDesign design{band.lowest_hz, band.highest_hz, 15, 0.07, 0.007, seed};
  if (band.reflection) {
    design.points = 3;
    design.waves = false;
    for (double degrees = 5.0; degrees < 90.0; degrees += 10.0) design.grazing_angles.push_back(degrees * std::numbers::pi / 180.0);
    design.bottom_loss_sigma_db = 1.0;
  }
  return design;
}

inversion::ModelEvidence evidence_of(const std::string& spec, const inversion::ObservationSet& data,
                                     const inversion::EvidenceOptions& options) {
  const auto model = sediment::make_sediment_model(spec);
  inversion::FitParameters start(model->parameters());
  start.set_free_from_list(sediment::typical_free_parameters(*model));
  const inversion::FitOptions fit_options{.method = inversion::FitMethod::Global, .profile_likelihood = false};
  const inversion::FitResult best = inversion::fit(data, *model, start, fit_options);
  return inversion::model_evidence(data, *model, best, inversion::make_priors(best.fitted, {}), fit_options, options);
}

}  // namespace

int main(int argc, char** argv) {
  const int realisations = argc > 1 ? std::atoi(argv[1]) : 5;
  inversion::EvidenceOptions options;
  options.steps = argc > 2 ? std::atoi(argv[2]) : 800;
  options.temperatures = argc > 3 ? std::atoi(argv[3]) : 16;
  const std::vector<std::string> models{"edfm", "biot-stoll", "grain-shearing", "vgs-lambda"};
  std::vector<Band> bands{{"50 Hz-1 kHz", 50.0, 1e3}, {"2-8 kHz", 2e3, 8e3}, {"10-400 kHz", 1e4, 4e5},
                          {"50 Hz-400 kHz", 50.0, 4e5}, {"BL 1-4 kHz", 1e3, 4e3, true}};
  if (argc > 4 && std::string(argv[4]) == "reflection") bands.erase(bands.begin(), bands.end() - 1);
  std::printf("model ranking by evidence: %d realisations, %d steps x %d temperatures; per cell: ranked first / "
              "indistinguishable / wrong\n", realisations, options.steps, options.temperatures);
  std::printf("%-16s", "band \\ truth");
  for (const std::string& m : models) std::printf(" | %-16s", m.c_str());
  std::printf("\n");
  for (const Band& band : bands) {
    std::printf("%-16s", band.name);
    for (std::size_t g = 0; g < models.size(); ++g) {
      int first = 0, tie = 0, wrong = 0;
      for (int r = 0; r < realisations; ++r) {
        const auto generator = sediment::make_sediment_model(models[g]);
        const inversion::ObservationSet data = inversion::synthetic_observations(
            *generator, inversion::FitParameters(generator->parameters()),
            design_of(band, static_cast<unsigned>(1000 * g + r + 1)));
        std::vector<inversion::ModelEvidence> e;
        for (const std::string& m : models) e.push_back(evidence_of(m, data, options));
        std::size_t best = 0;
        for (std::size_t c = 1; c < e.size(); ++c) {
          if (e[c].log_evidence > e[best].log_evidence) best = c;
        }
        const double gap = e[best].log_evidence - e[g].log_evidence;
        const double noise = std::hypot(e[best].uncertainty, e[g].uncertainty);
        if (best == g) ++first;
        else if (gap < std::max(1.0, 2.0 * noise)) ++tie;
        else ++wrong;
      }
      std::printf(" | %4d / %3d / %3d ", first, tie, wrong);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
