#include "sedwave/sediment/biot_stoll.hpp"

#include "sedwave/sediment/poroelastic_parameters.hpp"

namespace sedwave::sediment {

BiotStollModel::BiotStollModel()
    : parameters_(pore_space_parameters()) {
  parameters_.insert(parameters_.end(),
                 {{"K_b", "Pa", 4.4e7, 1.0e3, 1.0e11, true,
                   "drained frame bulk modulus; unconsolidated sand 1e7-1e8 (Stoll 1989, ch. 2)"},
                  {"mu", "Pa", 2.9e7, 1.0e2, 1.0e11, true,
                   "frame shear modulus; unconsolidated sand 1e7-1e8 (Stoll 1989, ch. 2)"},
                  {"delta_b", "1", 0.15, 1.0e-6, 2.0, false,
                   "logarithmic decrement of the frame bulk modulus, pi/Q; sands ~0.1-0.2 (Stoll 1989)"},
                  {"delta_s", "1", 0.15, 1.0e-6, 2.0, false,
                   "logarithmic decrement of the frame shear modulus, pi/Q; sands ~0.1-0.2 (Stoll 1989)"}});
}

std::string BiotStollModel::summary() const {
  return "Biot-Stoll: Biot's theory with a constant-decrement frame (Biot 1956; Stoll 1989; Stoll & Kan 1981) "
         "(docs/models/poroelastic.md)";
}

std::string BiotStollModel::shear_summary() const {
  return "Biot's shear wave of the frame shear modulus mu (1 - i delta_s/pi) with the pore fluid's inertia and drag "
         "(Stoll 1989)";
}

}  // namespace sedwave::sediment
