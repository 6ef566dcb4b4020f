#include "pena/dead_reckoning/stride_interpolator.hpp"

#include "pena/dead_reckoning/human_dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace pena::dead_reckoning {
namespace {

sensors::LaserScan Scan(double stamp_s) {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  return scan;
}

sensors::SensorRecord Gyro(double stamp_s) { return sensors::GyroSample{stamp_s, 0.0}; }
sensors::SensorRecord Stride(double stamp_s, double length_m) {
  return sensors::StrideSample{stamp_s, length_m};
}

StrideInterpolationOptions On() {
  StrideInterpolationOptions options;
  options.enabled = true;
  return options;
}

std::vector<sensors::SensorRecord> Drain(StrideInterpolator& spread) {
  std::vector<sensors::SensorRecord> out;
  while (auto record = spread.Pop()) out.push_back(std::move(*record));
  return out;
}

// (stamp, length) of every stride in the stream, in order.
std::vector<std::pair<double, double>> Strides(const std::vector<sensors::SensorRecord>& records) {
  std::vector<std::pair<double, double>> strides;
  for (const auto& record : records) {
    if (const auto* s = std::get_if<sensors::StrideSample>(&record)) {
      strides.emplace_back(s->stamp_s, s->length_m);
    }
  }
  return strides;
}

TEST(StrideInterpolator, CutsAStrideAtTheScansInsideItInProportionToTime) {
  StrideInterpolator spread(On());
  spread.Push(Stride(10.0, 0.5));  // the previous report: the stride below spans 10.0 -> 10.5
  spread.Push(Gyro(10.1));
  spread.Push(Scan(10.1));
  spread.Push(Gyro(10.35));
  spread.Push(Scan(10.35));
  EXPECT_EQ(Strides(Drain(spread)).size(), 1u)
      << "records wait for the report that ends their stride";
  spread.Push(Stride(10.5, 0.6));
  const std::vector<sensors::SensorRecord> out = Drain(spread);
  const auto strides = Strides(out);
  ASSERT_EQ(strides.size(), 3u);
  EXPECT_DOUBLE_EQ(strides[0].first, 10.1);
  EXPECT_NEAR(strides[0].second, 0.6 * 0.1 / 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(strides[1].first, 10.35);
  EXPECT_NEAR(strides[1].second, 0.6 * 0.25 / 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(strides[2].first, 10.5);
  EXPECT_NEAR(strides[0].second + strides[1].second + strides[2].second, 0.6, 1e-12);
  // Each piece comes right before its scan; the other records keep their order.
  ASSERT_EQ(out.size(), 7u);
  EXPECT_TRUE(std::holds_alternative<sensors::GyroSample>(out[0]));
  EXPECT_TRUE(std::holds_alternative<sensors::StrideSample>(out[1]));
  EXPECT_TRUE(std::holds_alternative<sensors::LaserScan>(out[2]));
  EXPECT_TRUE(std::holds_alternative<sensors::StrideSample>(out[4]));
  EXPECT_TRUE(std::holds_alternative<sensors::LaserScan>(out[5]));
}

TEST(StrideInterpolator, AStrideAfterStandingSpansOnePeriodBeforeItsReport) {
  StrideInterpolationOptions options = On();
  options.max_hold_s = 10.0;
  StrideInterpolator spread(options);
  spread.Push(Stride(1.0, 0.5));
  spread.Push(Stride(1.5, 0.5));  // a 0.5 s period
  spread.Push(Scan(4.0));         // standing: no piece
  spread.Push(Scan(4.9));         // 0.4 s into the 0.5 s stride ending at 5.0
  spread.Push(Stride(5.0, 0.5));
  const auto strides = Strides(Drain(spread));
  ASSERT_EQ(strides.size(), 4u);
  EXPECT_DOUBLE_EQ(strides[2].first, 4.9);
  EXPECT_NEAR(strides[2].second, 0.4, 1e-12);
  EXPECT_NEAR(strides[3].second, 0.1, 1e-12);
}

TEST(StrideInterpolator, AStoppedWalkerDelaysRecordsByAtMostTheHold) {
  StrideInterpolator spread(On());  // max_hold_s 1
  spread.Push(Stride(0.0, 0.5));
  spread.Push(Scan(0.25));
  spread.Push(Gyro(1.0));
  EXPECT_TRUE(Drain(spread).size() == 1u) << "only the report: the scan is 0.75 s old";
  spread.Push(Gyro(1.3));
  const auto out = Drain(spread);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<sensors::LaserScan>(out[0]));
  // The report after the stop cannot move the released scan: its stride starts after it, so the
  // scan still held gets its share of 0.25 -> 1.5 s, not of 0 -> 1.5 s.
  spread.Push(Scan(1.35));
  spread.Push(Stride(1.5, 0.5));
  const auto strides = Strides(Drain(spread));
  ASSERT_EQ(strides.size(), 2u);
  EXPECT_NEAR(strides[0].second, 0.5 * 1.1 / 1.25, 1e-12);
  EXPECT_NEAR(strides[0].second + strides[1].second, 0.5, 1e-12);
  EXPECT_EQ(spread.counts().released_unspread, 1u);
}

TEST(StrideInterpolator, AFaultyStrideIsPassedOnWholeForTheDeadReckoningToReject) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  spread.Push(Scan(0.25));
  spread.Push(Stride(0.5, 40.0));
  spread.Push(Scan(0.75));
  spread.Push(Stride(1.0, std::numeric_limits<double>::quiet_NaN()));
  spread.Finish();
  const auto out = Drain(spread);
  const auto strides = Strides(out);
  ASSERT_EQ(strides.size(), 3u);
  EXPECT_DOUBLE_EQ(strides[1].second, 40.0);
  EXPECT_TRUE(std::isnan(strides[2].second));
  EXPECT_EQ(out.size(), 5u) << "nothing dropped";
}

TEST(StrideInterpolator, FinishReleasesEverythingHeldInOrder) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  for (int i = 1; i <= 3; ++i) spread.Push(Scan(0.1 * i));
  spread.Push(sensors::GroundTruth{0.35, {}});
  spread.Finish();
  const auto out = Drain(spread);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_TRUE(std::holds_alternative<sensors::GroundTruth>(out.back()));
}

TEST(StrideInterpolator, HoldsAtMostMaxHeldRecordsWhenStampsStandStill) {
  StrideInterpolationOptions options = On();
  options.max_held_records = 10;
  StrideInterpolator spread(options);
  for (int i = 0; i < 100; ++i) spread.Push(Gyro(5.0));
  EXPECT_EQ(Drain(spread).size(), 90u);
}

// The dead reckoning fed through the interpolator follows a steady walker between reports
// (0.6 m strides every 0.5 s, scans every 0.25 s): at reports only it lags by half a stride at
// every mid-stride scan.
TEST(StrideInterpolator, TheDeadReckoningFollowsASteadyWalkerAtEveryScan) {
  std::vector<sensors::SensorRecord> walk;
  for (int tick = 1; tick <= 400; ++tick) {
    const double t = tick * 0.01;
    walk.push_back(sensors::GyroSample{t, 0.0});
    if (tick % 25 == 12) walk.push_back(Scan(t));
    if (tick % 50 == 0) walk.push_back(Stride(t, 0.6));
  }
  const auto run = [](const std::vector<sensors::SensorRecord>& records) {
    HumanDeadReckoning dead_reckoning(HumanDeadReckoningOptions{}, PosePrior{});
    double worst_m = 0.0;
    for (const auto& record : records) {
      if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
        const double true_x_m = 1.2 * scan->stamp_s;
        const double x_m = dead_reckoning.PriorAt(scan->stamp_s).world_from_body.x_m;
        worst_m = std::max(worst_m, std::abs(x_m - true_x_m));
      }
      dead_reckoning.Add(record);
    }
    return worst_m;
  };
  EXPECT_NEAR(run(walk), 1.2 * 0.37, 1e-9);
  // Exact but for the first stride, taken to span the default period (0.55 s, not 0.5 s).
  EXPECT_LT(run(SpreadStrides(walk, On())), 0.045);
}

TEST(StrideInterpolator, AScanAtTheReportsStampComesAfterTheWholeStride) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  spread.Push(Scan(0.5));
  spread.Push(Stride(0.5, 0.5));
  const auto out = Drain(spread);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<sensors::StrideSample>(out[1]));
  EXPECT_TRUE(std::holds_alternative<sensors::LaserScan>(out[2]));
}

TEST(StrideInterpolator, ARecordStampedFarAheadDoesNotStopTheSpreading) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  spread.Push(sensors::CompassSample{1e9, 0.0});  // a glitch
  spread.Push(Scan(0.3));
  spread.Push(Stride(0.5, 0.5));
  spread.Push(Scan(0.75));
  spread.Push(Stride(1.0, 0.5));
  const auto strides = Strides(Drain(spread));
  ASSERT_EQ(strides.size(), 5u) << "both scans get their piece";
  EXPECT_NEAR(strides[1].second, 0.5 * 0.3 / 0.5, 1e-12);
  EXPECT_NEAR(strides[3].second, 0.25, 1e-12);
}

TEST(StrideInterpolator, RecordsStampedAfterTheReportWaitForTheNextStride) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  spread.Push(Scan(0.6));  // came before the report that ends the stride it is not in
  spread.Push(Stride(0.5, 0.5));
  EXPECT_EQ(Strides(Drain(spread)).size(), 2u);
  spread.Push(Stride(1.0, 0.5));
  const auto out = Drain(spread);
  const auto strides = Strides(out);
  ASSERT_EQ(strides.size(), 2u);
  EXPECT_NEAR(strides[0].second, 0.1, 1e-12);
  EXPECT_TRUE(std::holds_alternative<sensors::LaserScan>(out[1]));
}

TEST(StrideInterpolator, AFaultyReportStillEndsAStride) {
  StrideInterpolator spread(On());
  spread.Push(Stride(0.0, 0.5));
  spread.Push(Stride(0.5, 40.0));  // passed on whole; the step ended at 0.5 s all the same
  spread.Push(Scan(0.75));
  spread.Push(Stride(1.0, 0.5));
  const auto strides = Strides(Drain(spread));
  ASSERT_EQ(strides.size(), 4u);
  EXPECT_NEAR(strides[2].second, 0.25, 1e-12);
}

TEST(StrideInterpolationOptions, RejectsBadValues) {
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    StrideInterpolationOptions options = On();
    options.max_hold_s = bad;
    EXPECT_THROW(StrideInterpolator{options}, std::invalid_argument);
    options = On();
    options.default_stride_period_s = bad;
    EXPECT_THROW(StrideInterpolator{options}, std::invalid_argument);
  }
}

}  // namespace
}  // namespace pena::dead_reckoning
