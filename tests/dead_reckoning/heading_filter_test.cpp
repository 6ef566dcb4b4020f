#include "pena/dead_reckoning/heading_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pena/geometry/pose2.hpp"

namespace pena::dead_reckoning {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Feeds `seconds` of a constant true turn rate: gyro at 100 Hz with bias and noise, compass at
// 10 Hz with noise plus `compass_offset_rad`; returns the true heading at the end.
double Simulate(HeadingFilter& filter, double& t, double true_heading, double rate, double seconds,
           double bias, double compass_offset_rad, std::mt19937& rng) {
  std::normal_distribution<double> gyro_noise(0.0, 0.005);
  std::normal_distribution<double> compass_noise(0.0, 2.0 * kDeg);
  const int steps = static_cast<int>(std::lround(seconds * 100.0));
  for (int i = 1; i <= steps; ++i) {
    t += 0.01;
    true_heading += rate * 0.01;
    filter.Predict({t, rate + bias + gyro_noise(rng)});
    if (i % 10 == 0) {
      filter.Update({t, true_heading + compass_offset_rad + compass_noise(rng)});
    }
  }
  return true_heading;
}

TEST(HeadingFilter, RecoversHeadingAfterTurnAndLearnsBias) {
  std::mt19937 rng(7);
  HeadingFilter filter({}, 0.0, 0.0);
  double t = 0.0;
  double heading = Simulate(filter, t, 0.0, 0.0, 20.0, 0.03, 0.0, rng);
  heading = Simulate(filter, t, heading, 200.0 * kDeg, 0.45, 0.03, 0.0, rng);  // fast 90 deg turn
  heading = Simulate(filter, t, heading, 0.0, 10.0, 0.03, 0.0, rng);
  EXPECT_NEAR(geometry::NormalizeAngle(filter.heading_rad() - heading), 0.0, 1.5 * kDeg);
  EXPECT_NEAR(filter.bias_rad_s(), 0.03, 0.01);
}

TEST(HeadingFilter, RejectsCompassDuringMagneticDisturbance) {
  std::mt19937 rng(11);
  HeadingFilter filter({}, 0.0, 0.0);
  double t = 0.0;
  double heading = Simulate(filter, t, 0.0, 0.0, 30.0, 0.01, 0.0, rng);
  heading = Simulate(filter, t, heading, 0.0, 5.0, 0.01, 40.0 * kDeg, rng);  // near a steel door
  EXPECT_NEAR(geometry::NormalizeAngle(filter.heading_rad() - heading), 0.0, 2.0 * kDeg);
  // The gate really rejects: one disturbed reading straight after is reported as such.
  EXPECT_EQ(filter.Update({t, heading + 40.0 * kDeg}), HeadingEvent::kCompassRejected);
}

TEST(HeadingFilter, GyroGapInflatesUncertaintyAndCompassRecovers) {
  HeadingFilter filter({}, 0.0, 0.0);
  filter.Predict({0.01, 0.0});
  const double sigma_before = filter.heading_sigma_rad();
  EXPECT_EQ(filter.Predict({5.01, 0.0}), HeadingEvent::kGyroGap);
  EXPECT_GT(filter.heading_sigma_rad(), 10.0 * sigma_before);
  // The person turned 60 deg during the gap: with the inflated variance the compass is accepted.
  EXPECT_EQ(filter.Update({5.02, 60.0 * kDeg}), HeadingEvent::kNone);
  EXPECT_NEAR(filter.heading_rad(), 60.0 * kDeg, 3.0 * kDeg);
}

TEST(HeadingFilter, OutOfOrderGyroIsReportedAndIgnored) {
  HeadingFilter filter({}, 0.5, 10.0);
  EXPECT_EQ(filter.Predict({9.0, 1.0}), HeadingEvent::kOutOfOrder);
  EXPECT_DOUBLE_EQ(filter.heading_rad(), 0.5);
}

TEST(HeadingFilter, InvalidOptionNamesFieldAndUnit) {
  HeadingFilterOptions options;
  options.compass_noise_rad = -1.0;
  try {
    HeadingFilter filter(options, 0.0, 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("compass_noise_rad must be > 0 rad"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::dead_reckoning
