#pragma once
// Shared helpers of the sediment-model tests.
#include <gtest/gtest.h>

#include <initializer_list>
#include <memory>
#include <numbers>
#include <vector>

#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment::testing {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// The dimensionless chain theory of the given name ("lattice", "continuum"), as a frame model takes it.
inline std::shared_ptr<const forward::DispersionModel> chain(const char* name) {
  return forward::make_dispersion_model(name);
}

/// A value computed outside sedwave (tests/sediment/independent_reference.py, 40 digits).
struct IndependentValue {
  double frequency;    ///< [Hz]
  double attenuation;  ///< [Np/m]
  double speed;        ///< [m/s]
};

/// The model at `values` agrees with each independent value to `relative_tolerance`.
inline void expect_independent_values(const SedimentModel& model, const std::vector<double>& values,
                                      std::initializer_list<IndependentValue> reference,
                                      double relative_tolerance) {
  for (const IndependentValue& r : reference) {
    const Wave w = model.evaluate(values, r.frequency, false);
    EXPECT_NEAR(w.attenuation / r.attenuation, 1.0, relative_tolerance) << r.frequency << " Hz";
    EXPECT_NEAR(w.speed / r.speed, 1.0, relative_tolerance) << r.frequency << " Hz";
  }
}

}  // namespace sedwave::sediment::testing
