#pragma once
// A number as the inversion's messages and notes print it: four significant digits ("%.4g").
#include <cstdio>
#include <string>

namespace sedwave::inversion {

inline std::string short_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

}  // namespace sedwave::inversion
