#include "sedwave/inversion/plausibility.hpp"

#include <array>

namespace sedwave::inversion {

const PlausibleRange* plausible_range(const std::string& quantity) {
  static const std::array<std::pair<const char*, PlausibleRange>, 4> kRanges{{
      {"d",
       {1e-6, 6.4e-2, "clay (1 um) to pebble gravel (64 mm)",
        "a grain size below clay: the fit slid along a direction the data do not see (d trades with kappa and "
        "gamma), or the frequencies are in the wrong unit",
        "a grain size above gravel: the frequencies or attenuations may be in the wrong unit"}},
      {"e_n", {1e-6, 1.0, "restitution of a binary collision, (0, 1]", "", ""}},
      {"sound_speed",
       {100.0, 2.0e4, "any seabed sediment at any frequency: gassy muds (about 100 m/s) to the P-wave speed of dense "
                      "rock-forming minerals (below 2e4 m/s)",
        "slower than any sediment: a sound speed in the wrong unit (km/s, or a ratio read as m/s)?",
        "faster than any mineral: parameters in the wrong unit (a kappa or d off by powers of ten?), or the model "
        "evaluated far beyond its range"}},
      {"porosity",
       {0.25, 0.9, "marine sediments, from poorly sorted sands to clays (Hamilton 1980: sands 0.37-0.47, clays to 0.85)",
        "denser than any unconsolidated sediment: the model puts too much stiffness or mass in the mixture",
        "looser than a clay: the model lowers the mixture's modulus through porosity to match a slow speed or to "
        "free the attenuation; check the water sound speed and the model"}},
  }};
  for (const auto& [name, range] : kRanges) {
    if (quantity == name) return &range;
  }
  return nullptr;
}

}  // namespace sedwave::inversion
