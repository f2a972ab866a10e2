// A study in a dozen lines: two models set up with what is known of the site, fitted and ranked.
#include <cstdio>
#include <vector>

#include "sedwave/inversion/comparison.hpp"

int main(int argc, char** argv) {
  using namespace sedwave::inversion;
  const ObservationSet data = read_observation_csv(argc > 1 ? argv[1] : "data/field/zhou2009_regression.csv");
  ModelSetup setup;  // what the command line's --model, --fit, --set, --site and --prior say
  setup.site_file = argc > 2 ? argv[2] : "data/sites/medium_sand.toml";
  std::vector<Candidate> candidates;
  for (const char* model : {"biot-stoll", "edfm"}) {
    setup.model = model;
    candidates.push_back(make_candidate(setup));
  }
  const Ranking ranking = compare_models(data, candidates, {.threads = 2});
  for (const ComparedModel& m : ranking.models) {
    std::printf("%-10s chi2 %7.2f  ln Z %8.2f +- %.2f\n", m.model.c_str(), m.fit.chi2, m.evidence.log_evidence,
                m.evidence.uncertainty);
  }
  return ranking.best().model == "biot-stoll" ? 0 : 1;
}
