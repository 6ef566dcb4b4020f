#include "pena/io/log_summary.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "log_test_util.hpp"

namespace pena::io {
namespace {

// A log of a firefighter: 10 Hz scans, 100 Hz gyro, 1 Hz compass, strides, 10 Hz ground truth.
std::vector<sensors::SensorRecord> FirefighterRecords() {
  const sensors::LaserGeometry laser = testing::MakeHeader().laser;
  std::vector<sensors::SensorRecord> records;
  for (int i = 0; i <= 1000; ++i) {
    const double t = 100.0 + 0.01 * i;  // 10 s from t = 100 s
    records.push_back(sensors::GyroSample{t, 0.01});
    if (i % 10 == 0) records.push_back(testing::MakeScan(t, laser));
    if (i % 10 == 5) records.push_back(sensors::GroundTruth{t, {0.1 * i, 0.0, 0.0}, 1.3, 0.0, 0.0});
    if (i % 100 == 0) records.push_back(sensors::CompassSample{t, 0.3});
    if (i % 60 == 30) records.push_back(sensors::StrideSample{t, 0.7});
  }
  return records;
}

TEST(LogSummary, CountsEachSensorWithItsTimeRange) {
  const auto path = testing::TempPath("ff.penalog");
  testing::WriteLog(path, testing::MakeHeader(), FirefighterRecords());
  MissionLogReader reader(path);
  const LogSummary summary = SummarizeLog(reader);

  EXPECT_EQ(summary.description.format, "pena-log");
  EXPECT_EQ(summary.description.entity_id, "ff1");
  EXPECT_EQ(summary.description.kind, sensors::EntityKind::kHuman);
  EXPECT_EQ(summary.description.mission, "office");
  const auto& laser = summary.sensors[0];
  EXPECT_EQ(laser.count, 101u);
  EXPECT_NEAR(laser.first_stamp_s, 100.0, 1e-9);
  EXPECT_NEAR(laser.duration_s(), 10.0, 1e-9);
  EXPECT_EQ(summary.sensors[1].count, 1001u);  // gyro
  EXPECT_EQ(summary.sensors[2].count, 11u);    // compass
  EXPECT_EQ(summary.sensors[3].count, 17u);    // stride: i = 30, 90, ..., 990
  EXPECT_NEAR(summary.sensors[3].first_stamp_s, 100.3, 1e-9);
  EXPECT_NEAR(summary.sensors[3].last_stamp_s, 109.9, 1e-9);
  EXPECT_EQ(summary.sensors[4].count, 0u);    // no wheel odometry on a firefighter
  EXPECT_EQ(summary.sensors[5].count, 100u);  // ground truth
  EXPECT_EQ(summary.overall.count, 101u + 1001u + 11u + 17u + 100u);
  EXPECT_NEAR(summary.overall.first_stamp_s, 100.0, 1e-9);
  EXPECT_NEAR(summary.overall.last_stamp_s, 110.0, 1e-9);
  EXPECT_EQ(summary.skipped_lines, 0u);
}

TEST(LogSummary, DescribesTheBeams) {
  const auto path = testing::TempPath("beams.penalog");
  const sensors::LaserGeometry wide = testing::MakeHeader().laser;
  sensors::LaserScan narrow = testing::MakeScan(2.0, {-1.0, 0.01, 8.0});
  narrow.ranges_m.resize(100);
  testing::WriteLog(path, testing::MakeHeader(), {testing::MakeScan(1.0, wide), narrow});
  MissionLogReader reader(path);
  const LogSummary summary = SummarizeLog(reader);

  EXPECT_EQ(summary.laser.min_beams, 100u);
  EXPECT_EQ(summary.laser.max_beams, 361u);
  EXPECT_NEAR(summary.laser.angle_min_rad, -std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(summary.laser.angle_max_rad, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(summary.laser.max_range_m, 30.0);
  // MakeScan puts a return just below the 30 m max range in beam 15 (1 mm quantisation).
  EXPECT_NEAR(summary.laser.longest_return_m, 30.0 - 0.0002, 0.001);
  // MakeScan puts 5 no-returns in beams 10..14 of each scan.
  EXPECT_EQ(summary.laser.beams, 461u);
  EXPECT_EQ(summary.laser.no_returns, 10u);
  EXPECT_NEAR(summary.laser.no_return_fraction(), 10.0 / 461.0, 1e-12);
}

// A source that says it skipped lines, as a lenient text reader would.
class SkippingSource : public LogSource {
 public:
  std::optional<sensors::SensorRecord> Next() override {
    if (left_ == 0) return std::nullopt;
    --left_;
    return sensors::GyroSample{static_cast<double>(3 - left_), 0.0};
  }
  const LogDescription& description() const override { return description_; }
  std::size_t skipped() const override { return 4; }

 private:
  int left_ = 3;
  LogDescription description_{"robot.clf", "carmen", "", std::nullopt, ""};
};

TEST(LogSummary, ReportsSkippedLinesAndUnknownFields) {
  SkippingSource source;
  const LogSummary summary = SummarizeLog(source);
  EXPECT_EQ(summary.skipped_lines, 4u);
  EXPECT_EQ(summary.sensors[1].count, 3u);
  const std::string text = FormatSummary(summary);
  EXPECT_NE(text.find("malformed lines skipped: 4"), std::string::npos) << text;
  EXPECT_NE(text.find("Entity:        - (kind unknown)"), std::string::npos) << text;
  EXPECT_EQ(text.find("Laser:"), std::string::npos) << "no scans, no laser line";
}

TEST(LogSummary, EmptyLogSaysNoRecordsAndNoTimes) {
  const auto path = testing::TempPath("empty.penalog");
  testing::WriteLog(path, testing::MakeHeader(), {});
  MissionLogReader reader(path);
  const LogSummary summary = SummarizeLog(reader);
  EXPECT_EQ(summary.overall.count, 0u);
  const std::string text = FormatSummary(summary);
  EXPECT_NE(text.find("Records:       0 "), std::string::npos) << text;
  EXPECT_EQ(text.find("Duration:"), std::string::npos) << text;
  EXPECT_EQ(text.find("Sensors:"), std::string::npos) << text;
}

TEST(LogSummary, FormatNamesEntityStreamsAndBeams) {
  const auto path = testing::TempPath("ff.penalog");
  testing::WriteLog(path, testing::MakeHeader(), FirefighterRecords());
  MissionLogReader reader(path);
  const std::string text = FormatSummary(SummarizeLog(reader));
  EXPECT_NE(text.find("Format:        pena-log"), std::string::npos) << text;
  EXPECT_NE(text.find("Entity:        ff1 (human)"), std::string::npos) << text;
  EXPECT_NE(text.find("Duration:      10.000 s"), std::string::npos) << text;
  EXPECT_NE(text.find("gyro"), std::string::npos) << text;
  EXPECT_NE(text.find("1001"), std::string::npos) << text;
  EXPECT_EQ(text.find("wheel_odometry"), std::string::npos) << "empty streams are left out";
  EXPECT_NE(text.find("361 beams per scan, span -90.00 .. 90.00 deg"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace
}  // namespace pena::io
