#pragma once
// CLI11 validators that refuse what CLI::PositiveNumber lets through: NaN and infinity compare false
// with everything, so "nan" passes a plain `x <= 0` test.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sedwave/inversion/observations.hpp"
#include "usable_cores.hpp"

namespace sedwave::app {

/// "a, b, c": names listed in a help text or a message.
inline std::string comma_separated(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// A finite number in [lower, upper] (both inclusive).
inline CLI::Validator finite_in(double lower, double upper = std::numeric_limits<double>::max()) {
  return CLI::Validator(
      [lower, upper](std::string& text) -> std::string {
        double x = 0.0;
        try {
          size_t used = 0;
          x = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!std::isfinite(x)) return "'" + text + "' is not a finite number";
        if (x < lower || x > upper) {
          return text + " is outside the accepted range [" + CLI::detail::to_string(lower) + ", " +
                 (upper == std::numeric_limits<double>::max() ? std::string("inf") : CLI::detail::to_string(upper)) +
                 "]";
        }
        return {};
      },
      "FINITE");
}

/// The water above a seabed (reflection): its sound speed [m/s], from fresh water near freezing to
/// hot brine, and its density [kg/m^3] (the range an observation file may declare).
inline CLI::Validator water_speed_range() { return finite_in(1300.0, 1800.0); }
inline CLI::Validator water_density_range() {
  return finite_in(inversion::kLowestWaterDensity, inversion::kHighestWaterDensity);
}

/// A non-empty list: `--fit ''` names no parameter, which is not the same as leaving --fit out.
inline CLI::Validator non_empty_list() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "an empty list names no parameter (leave the option out for the default)" : "";
      },
      "LIST");
}

/// An output path: not empty (`--csv ''` names nothing) and not an option (`--out --quiet` would
/// write a file named "--quiet"; write ./--quiet for that).
inline CLI::Validator output_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty()) return "an empty path names no file (leave the option out for the default)";
        if (text.front() == '-')
          return "'" + text + "' looks like an option, not a path (write ./" + text + " for a file of that name)";
        return "";
      },
      "PATH");
}

/// A finite number > 0.
inline CLI::Validator finite_positive() {
  return finite_in(std::numeric_limits<double>::denorm_min());
}

/// The samplers' --threads: 0 means every usable core (usable_cores.hpp). The samples do not
/// depend on it.
inline void add_threads_option(CLI::App& cmd, int& threads, const std::string& what) {
  cmd.add_option("--threads", threads, what + " (0: every usable core: OMP_NUM_THREADS, else the CPU affinity); "
                                       "the results do not depend on it")
      ->capture_default_str()->check(CLI::Range(0, 1024));
}

inline int threads_to_use(int requested) { return requested > 0 ? requested : usable_cores(); }

}  // namespace sedwave::app
