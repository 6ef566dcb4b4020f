// The CARMEN reader on well-formed synthetic logs: fields, geometry, no-returns, time rule.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "io_test_util.hpp"
#include "pena/io/carmen.hpp"

namespace pena::io {
namespace {

using sensors::LaserScan;
using sensors::WheelOdometry;
using testing::FlaserLine;
using testing::ReadAll;
using testing::WriteText;

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(CarmenReader, ReadsFlaserFieldsIntoScan) {
  std::string line = "FLASER 181";
  for (int i = 0; i < 181; ++i) line += " " + std::to_string(1.0 + 0.01 * i);
  line += " 1.5 -2 0.25 1.4 -2.1 0.2 976052857.337530 bag 976052857.337530\n";
  const auto path = WriteText("one.clf", line);
  const auto records = ReadAll(*OpenCarmenLog(path));
  ASSERT_EQ(records.size(), 1u);
  const auto& scan = std::get<LaserScan>(records[0]);
  ASSERT_EQ(scan.ranges_m.size(), 181u);
  EXPECT_FLOAT_EQ(scan.ranges_m[17], 1.17f);
  EXPECT_DOUBLE_EQ(scan.stamp_s, 976052857.337530);
  ASSERT_TRUE(scan.logged_pose && scan.odometry_pose);
  EXPECT_DOUBLE_EQ(scan.logged_pose->x_m, 1.5);
  EXPECT_DOUBLE_EQ(scan.logged_pose->theta_rad, 0.25);
  EXPECT_DOUBLE_EQ(scan.odometry_pose->y_m, -2.1);
  EXPECT_DOUBLE_EQ(scan.odometry_pose->theta_rad, 0.2);
  EXPECT_NEAR(scan.BeamAngle(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(scan.BeamAngle(90), 0.0, 1e-12);
  EXPECT_NEAR(scan.BeamAngle(180), 90 * kDeg, 1e-12);
}

TEST(CarmenReader, GivesFlaserBeamCountsTheirDocumentedGeometry) {
  const std::string log = FlaserLine(361, "2", "1") + FlaserLine(180, "2", "2") +
                          FlaserLine(91, "2", "3");
  const auto path = WriteText("geom.clf", log);
  ReadOptions one_degree;
  ReadOptions spread;
  spread.carmen_180_beams_span_180_deg = true;
  const auto a = ReadAll(*OpenCarmenLog(path, one_degree));
  const auto b = ReadAll(*OpenCarmenLog(path, spread));
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  const auto& s361 = std::get<LaserScan>(a[0]);
  EXPECT_NEAR(s361.geometry.angle_increment_rad, 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(s361.BeamAngle(360), 90 * kDeg, 1e-12);
  const auto& s180_steps = std::get<LaserScan>(a[1]);
  EXPECT_NEAR(s180_steps.BeamAngle(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(s180_steps.BeamAngle(179), 89 * kDeg, 1e-12);
  const auto& s180_spread = std::get<LaserScan>(b[1]);
  EXPECT_NEAR(s180_spread.BeamAngle(179), 90 * kDeg, 1e-12);
  const auto& s91 = std::get<LaserScan>(a[2]);
  EXPECT_NEAR(s91.geometry.angle_increment_rad, 2 * kDeg, 1e-12);
}

TEST(CarmenReader, MapsMaxRangeAndZeroToNoReturn) {
  std::string line = "FLASER 4 49.99 50 81.83 0 0 0 0 0 0 0 5.0 h 5.0\n";
  const auto path = WriteText("noreturn.clf", line);
  const auto records = ReadAll(*OpenCarmenLog(path));  // default max range
  const auto& scan = std::get<LaserScan>(records.at(0));
  EXPECT_FLOAT_EQ(scan.ranges_m[0], 49.99f);
  EXPECT_EQ(scan.ranges_m[1], LaserScan::kNoReturn);
  EXPECT_EQ(scan.ranges_m[2], LaserScan::kNoReturn);
  EXPECT_EQ(scan.ranges_m[3], LaserScan::kNoReturn);
  EXPECT_EQ(scan.CountReturns(), 1u);
  EXPECT_DOUBLE_EQ(scan.geometry.max_range_m, ReadOptions{}.carmen_max_range_m);

  ReadOptions far;
  far.carmen_max_range_m = 81.8;
  const auto far_scan = std::get<LaserScan>(ReadAll(*OpenCarmenLog(path, far)).at(0));
  EXPECT_FLOAT_EQ(far_scan.ranges_m[1], 50.0f);
  EXPECT_EQ(far_scan.ranges_m[2], LaserScan::kNoReturn);
}

TEST(CarmenReader, ReadsOdomAsWheelOdometry) {
  const auto path = WriteText("odom.clf", "ODOM 1 2 -1.5 0.3 -0.1 0 12.25 host 12.25\n");
  const auto records = ReadAll(*OpenCarmenLog(path));
  ASSERT_EQ(records.size(), 1u);
  const auto& odometry = std::get<WheelOdometry>(records[0]);
  EXPECT_DOUBLE_EQ(odometry.stamp_s, 12.25);
  EXPECT_DOUBLE_EQ(odometry.odom_pose.x_m, 1.0);
  EXPECT_DOUBLE_EQ(odometry.odom_pose.y_m, 2.0);
  EXPECT_DOUBLE_EQ(odometry.odom_pose.theta_rad, -1.5);
  EXPECT_DOUBLE_EQ(odometry.forward_velocity_m_s, 0.3);
  EXPECT_DOUBLE_EQ(odometry.yaw_rate_rad_s, -0.1);
}

// A SICK LMS 2xx measures 1 deg steps per mirror turn: a 0.5 deg scan is two turns interleaved,
// a 0.25 deg scan four (docs/odometry.md, "Interlaced scans"); the option overrides that.
TEST(CarmenReader, GivesScansFinerThanOneDegreeTheirInterlace) {
  const auto path = WriteText("interlace.clf", FlaserLine(181, "1", "1") +
                                                   FlaserLine(361, "2", "2") +
                                                   FlaserLine(721, "3", "3"));
  std::vector<int> found;
  for (const auto& record : ReadAll(*OpenCarmenLog(path, {}))) {
    found.push_back(std::get<LaserScan>(record).geometry.interlace);
  }
  EXPECT_EQ(found, (std::vector<int>{1, 2, 4}));
  ReadOptions one;
  one.carmen_interlace = 1;
  for (const auto& record : ReadAll(*OpenCarmenLog(path, one))) {
    EXPECT_EQ(std::get<LaserScan>(record).geometry.interlace, 1);
  }
  ReadOptions too_many;
  too_many.carmen_interlace = 17;
  try {
    OpenCarmenLog(path, too_many);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("carmen_interlace must be in [0, 16]"),
              std::string::npos)
        << error.what();
  }
}

// CARMEN does not say how long a scan takes: the reader gives every laser message the sweep of
// its options (a SICK LMS 2xx's 1/150 s by default; docs/odometry.md, "Scan deskew").
TEST(CarmenReader, GivesEveryLaserMessageTheSweepOfItsOptions) {
  const std::string robot =
      "ROBOTLASER1 0 -2.0 4.0 1.0 30 0.01 0 5 1 2 30 4 5 2 0.5 0.6 "
      "1 2 0.1 0.9 1.9 0.05 0.2 0 0.5 0.5 0.1 7.5 host 7.5\n";
  const std::string raw = "RAWLASER2 0 -1.0 2.0 0.5 10 0.01 0 5 1 2 3 10 11 0 8.0 host 8.0\n";
  const auto path = WriteText("sweep.clf", FlaserLine(361, "2", "1") + robot + raw);
  ReadOptions instantaneous;
  instantaneous.carmen_sweep_s = 0.0;
  for (const auto& [options, sweep_s] :
       {std::pair{ReadOptions{}, 1.0 / 150.0}, std::pair{instantaneous, 0.0}}) {
    const auto records = ReadAll(*OpenCarmenLog(path, options));
    ASSERT_EQ(records.size(), 3u);
    for (const auto& record : records) {
      EXPECT_EQ(std::get<LaserScan>(record).geometry.sweep_s, sweep_s);
    }
  }
  ReadOptions negative;
  negative.carmen_sweep_s = -0.001;
  EXPECT_THROW(
      {
        try {
          OpenCarmenLog(path, negative);
        } catch (const std::invalid_argument& error) {
          EXPECT_NE(std::string(error.what()).find("carmen_sweep_s must be in [0, 1] s"),
                    std::string::npos)
              << error.what();
          throw;
        }
      },
      std::invalid_argument);
}

TEST(CarmenReader, ReadsRobotLaserAndRawLaserWithTheirStatedGeometry) {
  // ROBOTLASER1 type start fov res max acc rem n [r] m [rem] laser_pose robot_pose tv rv f s t ts h lts
  const std::string robot =
      "ROBOTLASER1 0 -2.0 4.0 1.0 30 0.01 0 5 1 2 30 4 5 2 0.5 0.6 "
      "1 2 0.1 0.9 1.9 0.05 0.2 0 0.5 0.5 0.1 7.5 host 7.5\n";
  const std::string raw = "RAWLASER2 0 -1.0 2.0 0.5 10 0.01 0 5 1 2 3 10 11 0 8.0 host 8.0\n";
  const auto path = WriteText("stated.clf", robot + raw);
  const auto records = ReadAll(*OpenCarmenLog(path));
  ASSERT_EQ(records.size(), 2u);
  const auto& a = std::get<LaserScan>(records[0]);
  EXPECT_DOUBLE_EQ(a.geometry.angle_min_rad, -2.0);
  EXPECT_DOUBLE_EQ(a.geometry.angle_increment_rad, 1.0);
  EXPECT_DOUBLE_EQ(a.geometry.max_range_m, 30.0);
  EXPECT_EQ(a.ranges_m[2], LaserScan::kNoReturn);
  EXPECT_FLOAT_EQ(a.ranges_m[4], 5.0f);
  EXPECT_DOUBLE_EQ(a.logged_pose->x_m, 1.0);
  EXPECT_DOUBLE_EQ(a.odometry_pose->theta_rad, 0.05);
  EXPECT_DOUBLE_EQ(a.stamp_s, 7.5);
  const auto& b = std::get<LaserScan>(records[1]);
  EXPECT_DOUBLE_EQ(b.geometry.angle_increment_rad, 0.5);
  EXPECT_EQ(b.ranges_m[3], LaserScan::kNoReturn);
  EXPECT_FALSE(b.logged_pose.has_value());
  EXPECT_DOUBLE_EQ(b.stamp_s, 8.0);
}

TEST(CarmenReader, IgnoresCommentsAndUnknownMessages) {
  const std::string log = "# a comment\n\nPARAM robot_front_laser_max 50 nohost 0\n" +
                          FlaserLine(181, "3", "1.0") + "SYNC whatever\nNEFF 30\n" +
                          "TRUEPOS 1 2 3 4 5 6 1.1 host 1.1\n" + FlaserLine(181, "3", "1.1");
  const auto path = WriteText("mixed.clf", log);
  auto source = OpenCarmenLog(path);
  EXPECT_EQ(ReadAll(*source).size(), 2u);
  EXPECT_EQ(source->skipped(), 0u);
  EXPECT_EQ(source->description().format, "carmen");
}

TEST(CarmenReader, ReadsGzipLikePlainText) {
  const std::string log = FlaserLine(181, "3", "1.0") + "ODOM 0 0 0 0 0 0 1.05 h 1.05\n";
  const auto plain = ReadAll(*OpenCarmenLog(WriteText("log.clf", log)));
  const auto gzip = ReadAll(*OpenCarmenLog(testing::WriteGzip("log.clf.gz", log)));
  ASSERT_EQ(gzip.size(), 2u);
  EXPECT_EQ(plain.size(), gzip.size());
  EXPECT_EQ(std::get<LaserScan>(plain[0]).ranges_m, std::get<LaserScan>(gzip[0]).ranges_m);
}

TEST(CarmenReader, AcceptsEqualStampsAndDropsSlightlyEarlierScan) {
  const std::string log = FlaserLine(181, "3", "10.0") + FlaserLine(181, "3", "10.0") +
                          FlaserLine(181, "3", "9.2") + FlaserLine(181, "3", "10.5");
  const auto source = OpenCarmenLog(WriteText("jitter.clf", log));
  const auto records = ReadAll(*source);
  ASSERT_EQ(records.size(), 3u);  // the 9.2 s scan is dropped: consumers see time in order
  EXPECT_DOUBLE_EQ(sensors::StampOf(records[2]), 10.5);
  EXPECT_EQ(source->skipped(), 1u);
}

TEST(CarmenReader, DropsOdometryOlderThanTheLastReturned) {
  const std::string log =
      "ODOM 0 0 0 0 0 0 5.0 h 5.0\nODOM 1 0 0 0 0 0 0 h 0\nODOM 2 0 0 0 0 0 5.1 h 5.1\n";
  const auto records = ReadAll(*OpenCarmenLog(WriteText("odom_order.clf", log)));
  ASSERT_EQ(records.size(), 2u);
  EXPECT_DOUBLE_EQ(std::get<WheelOdometry>(records[1]).odom_pose.x_m, 2.0);
}

TEST(CarmenReader, ChecksTimeOrderPerMessageType) {
  // ODOM at 20 s does not make the FLASER at 10.5 s late: each type has its own clock check.
  const std::string log = FlaserLine(181, "3", "10.0") + "ODOM 0 0 0 0 0 0 20 h 20\n" +
                          FlaserLine(181, "3", "10.5");
  EXPECT_EQ(ReadAll(*OpenCarmenLog(WriteText("types.clf", log))).size(), 3u);
}

}  // namespace
}  // namespace pena::io
