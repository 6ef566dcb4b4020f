// The live sensor input without DDS: the conversions validate what a hostile publisher could
// send (NaN ranges, oversized scans, non-finite values, another schema), and the merger puts
// records of different topics back in stamp order inside its window and skips, counting, what
// comes too late.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sensor_from_dds.hpp"
#include "sensor_merger.hpp"
#include "sensor_to_dds.hpp"

namespace pena::services {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TopicRecord Gyro(double stamp_s, std::uint64_t seq) {
  return {SensorTopic::kGyro, seq, sensors::GyroSample{stamp_s, 0.1}};
}
TopicRecord Scan(double stamp_s, std::uint64_t seq) {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = {-1.0, 0.5, 10.0};
  scan.ranges_m = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  return {SensorTopic::kScan, seq, scan};
}
TopicRecord Stride(double stamp_s, std::uint64_t seq) {
  return {SensorTopic::kStride, seq, sensors::StrideSample{stamp_s, 0.7}};
}

std::size_t Index(SensorTopic topic) { return static_cast<std::size_t>(topic); }

pena_dds::LaserScanSample ScanSample(std::vector<float> ranges) {
  pena_dds::LaserScanSample sample;
  sample.entity_id("ff1");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  sample.seq(7);
  sample.stamp_s(12.5);
  sample.angle_min_rad(-1.0);
  sample.angle_increment_rad(0.01);
  sample.max_range_m(30.0);
  sample.ranges_m(std::move(ranges));
  return sample;
}

TEST(SensorMerger, ReordersTopicsThatArriveOutOfOrderInsideTheWindow) {
  SensorMerger merger({0.2});
  // The gyro is ahead of the scan and the stride on the wire.
  EXPECT_TRUE(merger.Add(Gyro(1.00, 2)));
  EXPECT_TRUE(merger.Add(Gyro(1.01, 3)));
  EXPECT_TRUE(merger.Add(Scan(0.95, 1)));
  EXPECT_FALSE(merger.PopReady().has_value());  // nothing is 0.2 s old yet
  EXPECT_TRUE(merger.Add(Stride(1.005, 4)));
  EXPECT_TRUE(merger.Add(Gyro(1.204, 5)));
  std::vector<double> stamps;
  std::vector<SensorTopic> order;
  while (auto record = merger.PopReady()) {
    stamps.push_back(sensors::StampOf(record->record));
    order.push_back(record->topic);
  }
  // 0.95 and 1.00 are at least 0.2 s older than 1.204; 1.005 is not.
  ASSERT_EQ(stamps, (std::vector<double>{0.95, 1.00}));
  EXPECT_EQ(order, (std::vector<SensorTopic>{SensorTopic::kScan, SensorTopic::kGyro}));
  EXPECT_EQ(merger.held(), 3u);
  while (auto record = merger.PopOldest()) stamps.push_back(sensors::StampOf(record->record));
  EXPECT_EQ(stamps, (std::vector<double>{0.95, 1.00, 1.005, 1.01, 1.204}));
  EXPECT_EQ(merger.counts().late, (std::array<std::size_t, kSensorTopicCount>{}));
}

TEST(SensorMerger, SkipsAndCountsARecordOlderThanWhatWasReleased) {
  SensorMerger merger({0.2});
  merger.Add(Gyro(1.00, 1));
  merger.Add(Gyro(1.30, 3));
  ASSERT_TRUE(merger.PopReady().has_value());  // 1.00 released
  // A stride of 0.9 s arriving now cannot go before the gyro already handed on.
  EXPECT_FALSE(merger.Add(Stride(0.90, 2)));
  EXPECT_EQ(merger.counts().late[Index(SensorTopic::kStride)], 1u);
  EXPECT_EQ(merger.counts().accepted[Index(SensorTopic::kStride)], 0u);
  EXPECT_EQ(merger.held(), 1u);
  // One later than the released one still goes in, in order.
  EXPECT_TRUE(merger.Add(Stride(1.10, 4)));
  EXPECT_DOUBLE_EQ(sensors::StampOf(merger.PopOldest()->record), 1.10);
  EXPECT_DOUBLE_EQ(sensors::StampOf(merger.PopOldest()->record), 1.30);
  EXPECT_EQ(*merger.released_stamp_s(), 1.30);
}

TEST(SensorMerger, KeepsThePublishersOrderForEqualStamps) {
  SensorMerger merger({0.0});
  merger.Add(Scan(2.0, 9));
  merger.Add(Gyro(2.0, 8));
  // Window 0: released as soon as offered, but both are held here until popped.
  EXPECT_EQ(merger.PopReady()->seq, 8u);
  EXPECT_EQ(merger.PopReady()->seq, 9u);
  // Equal stamp, lower seq than the released one: would go out of order, so it is late.
  EXPECT_FALSE(merger.Add(Stride(2.0, 7)));
  EXPECT_TRUE(merger.Add(Stride(2.0, 10)));
}

TEST(SensorMerger, ReleasesTheOldestWhenMoreThanMaxHeldWaitWhateverTheWindow) {
  // A publisher whose clock stands still: no record is ever reorder_window_s old.
  SensorMerger merger({0.2, 3});
  for (std::uint64_t seq = 1; seq <= 3; ++seq) EXPECT_TRUE(merger.Add(Gyro(5.0, seq)));
  EXPECT_FALSE(merger.PopReady().has_value());  // three held: within the bound
  EXPECT_TRUE(merger.Add(Gyro(5.0, 4)));
  const std::optional<TopicRecord> forced = merger.PopReady();
  ASSERT_TRUE(forced.has_value());
  EXPECT_EQ(forced->seq, 1u);  // the oldest, in the publisher's order
  EXPECT_EQ(merger.held(), 3u);
  EXPECT_FALSE(merger.PopReady().has_value());
  EXPECT_THROW(SensorMerger({0.2, 0}), std::invalid_argument);
}

TEST(SensorMerger, RefusesAWindowThatIsNegativeOrNotFinite) {
  EXPECT_THROW(SensorMerger({-0.1}), std::invalid_argument);
  EXPECT_THROW(SensorMerger({std::nan("")}), std::invalid_argument);
}

TEST(SensorValidation, NanAndNegativeRangesBecomeNoReturns) {
  const SensorCheck check = FromDds(ScanSample({1.0f, kNaN, -2.0f, kInf, 2.5f, 0.0f}));
  ASSERT_TRUE(check.record.has_value()) << check.error;
  EXPECT_EQ(check.bad_ranges, 2u);
  const auto& scan = std::get<sensors::LaserScan>(*check.record);
  ASSERT_EQ(scan.ranges_m.size(), 6u);
  EXPECT_EQ(scan.ranges_m[1], sensors::LaserScan::kNoReturn);
  EXPECT_EQ(scan.ranges_m[2], sensors::LaserScan::kNoReturn);
  EXPECT_EQ(scan.CountReturns(), 2u);  // 1.0 and 2.5; +inf and 0 were no-returns already
  EXPECT_DOUBLE_EQ(scan.stamp_s, 12.5);
}

TEST(SensorValidation, RefusesAScanOverTheBeamBoundNamingTheCount) {
  const SensorCheck over =
      FromDds(ScanSample(std::vector<float>(pena_dds::SCAN_MAX_BEAMS + 1, 1.0f)));
  EXPECT_FALSE(over.record.has_value());
  EXPECT_NE(over.error.find(std::to_string(pena_dds::SCAN_MAX_BEAMS + 1)), std::string::npos)
      << over.error;
  // A reader may bound it tighter (a 361-beam laser).
  EXPECT_FALSE(FromDds(ScanSample(std::vector<float>(362, 1.0f)), 361).record.has_value());
  EXPECT_TRUE(FromDds(ScanSample(std::vector<float>(361, 1.0f)), 361).record.has_value());
  EXPECT_FALSE(FromDds(ScanSample({})).record.has_value());
}

TEST(SensorValidation, RefusesNonFiniteValuesAndOtherSchemasNamingTheField) {
  pena_dds::LaserScanSample scan = ScanSample({1.0f});
  scan.max_range_m(std::numeric_limits<double>::infinity());
  EXPECT_NE(FromDds(scan).error.find("max_range_m"), std::string::npos);
  scan = ScanSample({1.0f});
  scan.has_odometry_pose(true);
  scan.odometry_pose().theta_rad(std::nan(""));
  EXPECT_NE(FromDds(scan).error.find("odometry_pose.theta_rad"), std::string::npos);
  pena_dds::GyroSample gyro;
  gyro.schema_version(pena_dds::SCHEMA_VERSION);
  gyro.stamp_s(1.0);
  gyro.yaw_rate_rad_s(std::nan(""));
  EXPECT_NE(FromDds(gyro).error.find("yaw_rate_rad_s"), std::string::npos);
  gyro.yaw_rate_rad_s(0.1);
  gyro.stamp_s(std::numeric_limits<double>::infinity());
  EXPECT_NE(FromDds(gyro).error.find("stamp_s"), std::string::npos);
  gyro.stamp_s(1.0);
  gyro.schema_version(pena_dds::SCHEMA_VERSION + 1);
  EXPECT_NE(FromDds(gyro).error.find("schema_version"), std::string::npos);
  pena_dds::StrideSample stride;
  stride.schema_version(pena_dds::SCHEMA_VERSION);
  stride.length_m(-0.5);
  EXPECT_NE(FromDds(stride).error.find("length_m"), std::string::npos);
}

// What pena-sensor-replay publishes converts back to the very record it read.
TEST(SensorValidation, EveryRecordRoundTripsExactly) {
  sensors::LaserScan scan = std::get<sensors::LaserScan>(Scan(3.25, 1).record);
  scan.odometry_pose = geometry::Pose2{1.5, -2.0, 0.3};
  sensors::WheelOdometry wheel{4.0, {1.0, 2.0, -0.5}, 0.8, 0.05};
  const std::vector<sensors::SensorRecord> records = {
      scan, sensors::GyroSample{1.0, -0.02}, sensors::CompassSample{1.1, 2.9},
      sensors::StrideSample{1.2, 0.71}, wheel};
  for (const sensors::SensorRecord& record : records) {
    const SensorSample sample = ToDdsSensorSample(record, "ff1", 42);
    const SensorCheck back = std::visit(
        [](const auto& s) -> SensorCheck {
          if constexpr (std::is_same_v<std::decay_t<decltype(s)>, std::monostate>) {
            return {};
          } else {
            EXPECT_EQ(s.seq(), 42u);
            EXPECT_EQ(s.entity_id().to_string(), "ff1");
            return FromDds(s);
          }
        },
        sample);
    ASSERT_TRUE(back.record.has_value()) << back.error;
    ASSERT_EQ(back.record->index(), record.index());
    EXPECT_EQ(sensors::StampOf(*back.record), sensors::StampOf(record));
  }
  const SensorCheck scan_check =
      FromDds(std::get<pena_dds::LaserScanSample>(ToDdsSensorSample(scan, "ff1", 1)));
  const auto& scan_back = std::get<sensors::LaserScan>(*scan_check.record);
  EXPECT_EQ(scan_back.ranges_m, scan.ranges_m);
  EXPECT_EQ(scan_back.odometry_pose->theta_rad, 0.3);
  EXPECT_FALSE(scan_back.logged_pose.has_value());
  const SensorCheck wheel_check =
      FromDds(std::get<pena_dds::WheelOdometrySample>(ToDdsSensorSample(wheel, "r", 1)));
  const auto& wheel_back = std::get<sensors::WheelOdometry>(*wheel_check.record);
  EXPECT_EQ(wheel_back.odom_pose.theta_rad, -0.5);
  EXPECT_EQ(wheel_back.yaw_rate_rad_s, 0.05);
  // Ground truth has no topic.
  EXPECT_TRUE(std::holds_alternative<std::monostate>(
      ToDdsSensorSample(sensors::GroundTruth{}, "ff1", 1)));
}

}  // namespace
}  // namespace pena::services
