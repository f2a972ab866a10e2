// The inversion without MPI: this program links only the inversion library (and what it brings),
// refuses to compile where MPI's header is on its include path, finds no MPI symbol at run time,
// and sets up and fits a model from a site file. A dependency that brought MPI back into the
// inversion's interface would fail its build or its run.
#include <dlfcn.h>

#include <cstdio>
#include <string>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/setup.hpp"

#if __has_include(<mpi.h>)
#error "MPI's header is on the include path of a program linked only against the inversion"
#endif

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: without_mpi SOURCE_DIR\n");
    return 2;
  }
  if (dlsym(RTLD_DEFAULT, "MPI_Init") != nullptr) {
    std::fprintf(stderr, "FAILED: an MPI library is linked into a program that uses only the inversion\n");
    return 1;
  }
  using namespace sedwave::inversion;
  const std::string source = argv[1];
  const ObservationSet data = read_observation_csv(source + "/data/field/zhou2009_regression.csv");
  ModelSetup setup;
  setup.model = "biot-stoll";
  setup.free = "porosity,permeability";
  setup.site_file = source + "/data/sites/medium_sand.toml";
  const Candidate candidate = make_candidate(setup);
  FitOptions options;
  options.profile_likelihood = false;
  const FitResult result = fit(data, *candidate.model, candidate.parameters, options);
  std::printf("biot-stoll from a site file, without MPI: chi2 %.4g for %d dof (%zu site notes)\n", result.chi2,
              result.dof, candidate.notes.size());
  return result.converged && !candidate.notes.empty() ? 0 : 1;
}
