#pragma once
// CLI11 validators that refuse what CLI::PositiveNumber lets through: NaN and infinity compare false
// with everything, so "nan" passes a plain `x <= 0` test.
#include <CLI/CLI.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace sedwave::app {

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

/// A finite number > 0.
inline CLI::Validator finite_positive() {
  return finite_in(std::numeric_limits<double>::denorm_min());
}

}  // namespace sedwave::app
