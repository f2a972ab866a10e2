#pragma once
// A posterior with two modes from a shipped model: Biot-Stoll's porosity and permeability from
// attenuation and sound speed at 4 frequencies over 200-210 Hz (5 % attenuation, 1 % speed noise),
// generated at its defaults but a permeability of 1e-9 m^2. At a fixed frequency Biot's viscous loss
// peaks where the frequency meets Biot's relaxation frequency f_c ~ eta phi / (2 pi alpha_inf rho_f k)
// (k about 1.6e-10 m^2 here): the attenuation of the data (0.006 Np/m) is met by k near 1e-9 m^2
// (above the peak) and near 3e-11 m^2 (below it, where a lower porosity gives the same sound speed),
// and so narrow a band cannot tell them apart by the frequency dependence. Priors (the search
// bounds): log-uniform permeability over 1e-13 - 1e-7 m^2, log-uniform porosity over 0.2 - 0.7.
// Shared by bench/evidence_accuracy.cpp and tests/inversion/test_coverage.cpp.
#include <memory>

#include "sedwave/inversion/parameters.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::bench {

struct BimodalCase {
  std::shared_ptr<const sediment::SedimentModel> model = sediment::make_sediment_model("biot-stoll");
  inversion::FitParameters start{model->parameters()};  ///< porosity and permeability free, narrowed bounds

  BimodalCase() {
    start.set_free_from_list("porosity,permeability");
    auto& k = start.spec[static_cast<std::size_t>(start.index_of("permeability"))];
    k.lower = 1e-13, k.upper = 1e-7;
    auto& phi = start.spec[static_cast<std::size_t>(start.index_of("porosity"))];
    phi.lower = 0.2, phi.upper = 0.7;
  }
  /// The observations of noise realisation `seed`.
  [[nodiscard]] inversion::ObservationSet data(unsigned seed) const {
    inversion::FitParameters truth(model->parameters());
    truth.spec[static_cast<std::size_t>(truth.index_of("permeability"))].value = 1e-9;
    return inversion::synthetic_observations(*model, truth, {200.0, 210.0, 4, 0.05, 0.01, seed});
  }
};

}  // namespace sedwave::bench
