// EDFM and Biot-Stoll: limits and asymptotes against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sedwave/sediment/biot_stoll.hpp"
#include "sedwave/sediment/edfm.hpp"

namespace sedwave::sediment {
namespace {

TEST(Edfm, PlaceholderBuilds) {
  const EffectiveDensityFluidModel e;
  const BiotStollModel b;
  EXPECT_GT(e.evaluate(e.default_values(), 1e3, false).speed, 1500.0);
  EXPECT_GT(b.evaluate(b.default_values(), 1e3, false).speed, 1500.0);
}

}  // namespace
}  // namespace sedwave::sediment
