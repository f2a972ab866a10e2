#pragma once
// Choosing a forward model by name, as the command line and scene files do.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sedwave/forward/dispersion.hpp"

namespace sedwave::forward {

/// "continuum" or "lattice" (the 1D chain theories), or "table:FILE.h5[?extrapolate=theory|long-wavelength]" (a
/// precomputed table, docs/tables.md). Throws std::invalid_argument naming the accepted
/// specifications for anything else.
[[nodiscard]] std::unique_ptr<DispersionModel> make_dispersion_model(const std::string& spec);

/// The file a specification reads ("table:FILE.h5?..." gives FILE.h5), or nothing for a closed
/// form: commands check that no output would overwrite it.
[[nodiscard]] std::optional<std::string> dispersion_model_file(const std::string& spec);

/// The specifications make_dispersion_model accepts, for help texts.
[[nodiscard]] std::vector<std::string> dispersion_model_names();

}  // namespace sedwave::forward
