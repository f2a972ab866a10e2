// How a driven run's measurement becomes a table point: ok only when the attenuation is
// significantly positive; otherwise unresolved with a reason, never noise stored as a value.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sedwave/forward/experiment/time_domain_points.hpp"

namespace sedwave::forward::experiment {
namespace {

using table::log_spaced;
using table::PointResult;
using table::PointStatus;

channel::AcousticResult measured(double alpha, double sigma_alpha, double c, double sigma_c) {
  channel::AcousticResult r;
  r.fit.alpha = alpha;
  r.fit.sigma_alpha = sigma_alpha;
  r.fit.c = c;
  r.fit.sigma_c = sigma_c;
  r.wall_seconds = 3.5;
  return r;
}

TEST(PointFromAcoustic, SignificantAttenuationIsOk) {
  const PointResult p = point_from_acoustic(measured(0.02, 0.001, 0.9, 0.01));
  EXPECT_EQ(p.status, PointStatus::ok);
  EXPECT_EQ(p.alpha_hat, 0.02);
  EXPECT_EQ(p.sigma_alpha_hat, 0.001);
  EXPECT_EQ(p.c_hat, 0.9);
  EXPECT_EQ(p.sigma_c_hat, 0.01);
  EXPECT_EQ(p.wall_seconds, 3.5);
  EXPECT_TRUE(p.reason.empty());
}

TEST(PointFromAcoustic, AttenuationBelowTwoSigmaIsUnresolved) {
  for (double alpha : {0.0015, -0.001, 0.0}) {
    const PointResult p = point_from_acoustic(measured(alpha, 0.001, 0.9, 0.01));
    EXPECT_EQ(p.status, PointStatus::unresolved) << alpha;
    EXPECT_TRUE(std::isnan(p.alpha_hat));
    EXPECT_NE(p.reason.find("not significantly positive"), std::string::npos) << p.reason;
  }
}

TEST(PointFromAcoustic, RunProblemIsUnresolvedWithItsReason) {
  channel::AcousticResult r = measured(0.02, 0.001, 0.9, 0.01);
  r.problem = "fewer than 3 layers have a steady window";
  const PointResult p = point_from_acoustic(r);
  EXPECT_EQ(p.status, PointStatus::unresolved);
  EXPECT_EQ(p.reason, r.problem);
  EXPECT_TRUE(std::isnan(p.c_hat));
}

TEST(PointFromAcoustic, WindowsStillNotSteadyAreUnresolved) {
  channel::AcousticResult r = measured(0.02, 0.001, 0.9, 0.01);
  r.warning = "not steady: the first and last halves of the lock-in windows give alpha_hat 0.03 and 0.02";
  r.extensions = 2;
  const PointResult p = point_from_acoustic(r);
  EXPECT_EQ(p.status, PointStatus::unresolved);
  EXPECT_EQ(p.reason, "not steady after 2 extension(s) of the run: the first and last halves of the lock-in "
                      "windows give alpha_hat 0.03 and 0.02");
  EXPECT_TRUE(std::isnan(p.alpha_hat));
}

TEST(PointFromAcoustic, NonFiniteFitIsUnresolved) {
  const PointResult p = point_from_acoustic(measured(0.02, NAN, 0.9, 0.01));
  EXPECT_EQ(p.status, PointStatus::unresolved);
}

TEST(PulseBands, CutTheGridIntoBandsOneGaussianPulseCovers) {
  const std::vector<std::vector<double>> bands = pulse_bands(log_spaced(1e-3, 1.0, 10));
  ASSERT_FALSE(bands.empty());
  std::size_t total = 0;
  double previous = 0.0;
  for (const auto& band : bands) {
    EXPECT_LE(band.back() / band.front(), kPulseBandRatio * (1.0 + 1e-12));
    EXPECT_GT(band.front(), previous);  // consecutive, nothing repeated
    previous = band.back();
    total += band.size();
  }
  EXPECT_EQ(total, 10u);
  EXPECT_EQ(bands.size(), 4u);  // 3 decades in bands of at most a factor 8: 4 bands
  EXPECT_EQ(pulse_bands({0.5}).size(), 1u);
}

}  // namespace
}  // namespace sedwave::forward::experiment
