#include "sedwave/forward/linear/newton_stage.hpp"

#include "sedwave/forward/linear/static_equilibrium.hpp"

namespace sedwave::forward::linear {

channel::NewtonRelaxation newton_stage() {
  return [](std::vector<dem::Grain>& grains, const dem::Box& box, const dem::ContactSpec& contact, int rigid_bodies,
            double residual_force_tolerance, int max_iterations) {
    StaticEquilibriumSettings settings;
    settings.residual_force_tolerance = residual_force_tolerance;
    settings.max_iterations = max_iterations;
    return relax_to_equilibrium(grains, box, contact, rigid_bodies, nullptr, settings).iterations;
  };
}

}  // namespace sedwave::forward::linear
