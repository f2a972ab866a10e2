#pragma once
// The values a quantity accepts — a scene key, a contact law's constant, a command-line option, a
// site file's entry — as one type, so a key has the same bounds, and the same words in a message,
// wherever it is read. A literal type: contact laws declare their keys' ranges at compile time.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace sedwave::io {

/// Shortest text that reads back as the same double ("0.1", not "0.10000000000000001"; whole
/// numbers without an exponent: "1000000", not "1e+06").
inline std::string shortest(double x) {
  if (std::trunc(x) == x && std::abs(x) < 1e16) return std::to_string(static_cast<std::int64_t>(x));
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

/// The values a key accepts, with their unit, as a message shows them: "(0, 1] (of the column)".
/// Open ends exclude the bound; infinite ends are open. `unit` names text that outlives the range
/// (a literal, or a string the caller keeps while it uses the range).
struct Range {
  double low = -INFINITY;
  double high = INFINITY;
  bool low_open = false;
  bool high_open = false;
  std::string_view unit = {};

  static constexpr Range positive(std::string_view unit = "") { return {0.0, INFINITY, true, true, unit}; }
  static constexpr Range non_negative(std::string_view unit = "") { return {0.0, INFINITY, false, true, unit}; }
  /// [low, high]
  static constexpr Range closed(double low, double high, std::string_view unit = "") {
    return {low, high, false, false, unit};
  }
  /// (low, high)
  static constexpr Range open(double low, double high, std::string_view unit = "") {
    return {low, high, true, true, unit};
  }
  /// (low, high]
  static constexpr Range above(double low, double high, std::string_view unit = "") {
    return {low, high, true, false, unit};
  }

  [[nodiscard]] constexpr bool contains(double x) const {
    return (low_open ? x > low : x >= low) && (high_open ? x < high : x <= high);
  }
  /// "(0, 1]", "[0, inf) m"
  [[nodiscard]] std::string describe() const {
    const auto bound = [](double x) { return std::isinf(x) ? std::string(x < 0 ? "-inf" : "inf") : shortest(x); };
    std::string text = std::string(low_open || std::isinf(low) ? "(" : "[") + bound(low) + ", " + bound(high) +
                       (high_open || std::isinf(high) ? ")" : "]");
    return unit.empty() ? text : text + " " + std::string(unit);
  }
};

}  // namespace sedwave::io
