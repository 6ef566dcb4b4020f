// Timing quality of a log: scans arriving in bursts (odometry::internal::BurstTiming).
#include "pena/odometry/internal/burst_timing.hpp"

#include <gtest/gtest.h>

namespace pena::odometry::internal {
namespace {

TEST(BurstTiming, RegularStampsAreNeverPoor) {
  BurstTiming timing(0.02, 0.05, 0);
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(timing.Add(100.0 + 0.1 * i)) << "scan " << i;
  EXPECT_DOUBLE_EQ(timing.fraction(), 0.0);
}

TEST(BurstTiming, ScansDeliveredInBurstsMakeTheTimingPoor) {
  // Like intel: every third scan arrives 5 ms after the previous one.
  BurstTiming timing(0.02, 0.05, 0);
  double stamp_s = 100.0;
  bool poor = false;
  for (int i = 0; i < 300; ++i) {
    stamp_s += (i % 3 == 2) ? 0.005 : 0.2;
    poor = timing.Add(stamp_s);
  }
  EXPECT_TRUE(poor);
  EXPECT_NEAR(timing.fraction(), 1.0 / 3.0, 0.01);
}

// The laser's period where the stamps are delivery times: the mean over all scans, also with a
// window and with the check off.
TEST(BurstTiming, MeanIntervalIsOverAllScansSoFar) {
  for (const int window_scans : {0, 10}) {
    for (const double gap_s : {0.02, 0.0}) {
      BurstTiming timing(gap_s, 0.05, window_scans);
      EXPECT_EQ(timing.mean_interval_s(), 0.0);
      double stamp_s = 100.0;
      timing.Add(stamp_s);
      EXPECT_EQ(timing.mean_interval_s(), 0.0);
      for (int i = 0; i < 300; ++i) timing.Add(stamp_s += (i % 3 == 2) ? 0.005 : 0.2);
      EXPECT_NEAR(timing.mean_interval_s(), (0.2 + 0.2 + 0.005) / 3.0, 1e-9);
    }
  }
}

TEST(BurstTiming, AWindowForgetsOldBursts) {
  BurstTiming timing(0.02, 0.05, 50);
  double stamp_s = 100.0;
  for (int i = 0; i < 50; ++i) timing.Add(stamp_s += 0.01);  // all in a burst
  EXPECT_TRUE(timing.Add(stamp_s += 0.1));
  bool poor = true;
  for (int i = 0; i < 50; ++i) poor = timing.Add(stamp_s += 0.1);  // regular again
  EXPECT_FALSE(poor);
  EXPECT_DOUBLE_EQ(timing.fraction(), 0.0);
}

TEST(BurstTiming, ZeroGapDisablesTheCheck) {
  BurstTiming timing(0.0, 0.05, 0);
  double stamp_s = 100.0;
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(timing.Add(stamp_s += 0.001));
}

}  // namespace
}  // namespace pena::odometry::internal
