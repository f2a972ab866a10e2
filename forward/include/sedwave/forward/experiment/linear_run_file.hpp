#pragma once
// The run file of the linear engine (HDF5, units as attributes): scene text, per ensemble member the
// packing statistics, the layer-averaged complex field and its fits, the contact state changes; the
// ensemble's alpha_hat and c_hat. Layout: docs/linear.md. Serial; written atomically.
#include <filesystem>
#include <vector>

#include "sedwave/forward/experiment/scene.hpp"
#include "sedwave/forward/linear/ensemble.hpp"

namespace sedwave::forward::experiment {

void write_linear_run_file(const std::filesystem::path& path, const ChannelScene& scene,
                           const std::vector<channel::PreparationReport>& preparations,
                           const linear::EnsembleResult& result);

}  // namespace sedwave::forward::experiment
