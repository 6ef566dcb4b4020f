// CarmenWriter and CsmJsonWriter: what is written reads back as the same data.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io_test_util.hpp"
#include "pena/io/carmen.hpp"

namespace pena::io {
namespace {

using sensors::LaserScan;
using sensors::WheelOdometry;
using testing::ReadAll;

// A scan with returns, a no-return and a beyond-max range, in FLASER's 181-beam geometry.
LaserScan MakeScan(double stamp_s, double max_range_m) {
  LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = {-std::numbers::pi / 2, std::numbers::pi / 180, max_range_m};
  for (int i = 0; i < 181; ++i) scan.ranges_m.push_back(0.2f + 0.137f * static_cast<float>(i % 50));
  scan.ranges_m[5] = LaserScan::kNoReturn;
  scan.ranges_m[6] = static_cast<float>(max_range_m) + 3.0f;
  scan.logged_pose = geometry::Pose2{1.25, -3.5, 0.3};
  scan.odometry_pose = geometry::Pose2{1.2, -3.4, 0.31};
  return scan;
}

void ExpectSameScan(const LaserScan& read, const LaserScan& written) {
  EXPECT_DOUBLE_EQ(read.stamp_s, written.stamp_s);
  EXPECT_NEAR(read.geometry.angle_min_rad, written.geometry.angle_min_rad, 1e-12);
  EXPECT_NEAR(read.geometry.angle_increment_rad, written.geometry.angle_increment_rad, 1e-12);
  EXPECT_DOUBLE_EQ(read.geometry.max_range_m, written.geometry.max_range_m);
  ASSERT_EQ(read.ranges_m.size(), written.ranges_m.size());
  for (std::size_t i = 0; i < read.ranges_m.size(); ++i) {
    if (written.IsReturn(i)) {
      EXPECT_EQ(read.ranges_m[i], written.ranges_m[i]) << "beam " << i;
    } else {
      EXPECT_EQ(read.ranges_m[i], LaserScan::kNoReturn) << "beam " << i;
    }
  }
  ASSERT_TRUE(read.logged_pose && read.odometry_pose);
  EXPECT_DOUBLE_EQ(read.logged_pose->x_m, written.logged_pose->x_m);
  EXPECT_DOUBLE_EQ(read.logged_pose->theta_rad, written.logged_pose->theta_rad);
  EXPECT_DOUBLE_EQ(read.odometry_pose->y_m, written.odometry_pose->y_m);
  EXPECT_DOUBLE_EQ(read.odometry_pose->theta_rad, written.odometry_pose->theta_rad);
}

TEST(CarmenWriter, FlaserAndOdomRoundTripExactly) {
  const auto path = testing::TempPath("round.clf");
  const LaserScan first = MakeScan(976052857.337530, 50.0);
  const LaserScan second = MakeScan(976052857.537531, 50.0);
  const WheelOdometry odometry{976052857.4, {0.5, -0.25, 3.0}, 0.4, -0.2};
  {
    CarmenWriter writer(path);
    writer.Write(first);
    writer.Write(odometry);
    writer.Write(second);
  }
  ReadOptions options;
  options.carmen_max_range_m = 50.0;
  const auto records = ReadAll(*OpenCarmenLog(path, options));
  ASSERT_EQ(records.size(), 3u);
  ExpectSameScan(std::get<LaserScan>(records[0]), first);
  ExpectSameScan(std::get<LaserScan>(records[2]), second);
  const auto& odom = std::get<WheelOdometry>(records[1]);
  EXPECT_DOUBLE_EQ(odom.stamp_s, odometry.stamp_s);
  EXPECT_DOUBLE_EQ(odom.odom_pose.x_m, 0.5);
  EXPECT_DOUBLE_EQ(odom.odom_pose.theta_rad, 3.0);
  EXPECT_DOUBLE_EQ(odom.forward_velocity_m_s, 0.4);
  EXPECT_DOUBLE_EQ(odom.yaw_rate_rad_s, -0.2);
}

TEST(CarmenWriter, WritesOtherBeamGeometriesAsRobotLaserThatRoundTrips) {
  LaserScan scan = MakeScan(12.5, 30.0);
  scan.geometry.angle_min_rad = -2.0;
  scan.geometry.angle_increment_rad = 4.0 / 180.0;  // a 240-ish degree laser
  const auto path = testing::TempPath("wide.clf");
  { CarmenWriter(path).Write(scan); }
  const auto records = ReadAll(*OpenCarmenLog(path));
  ASSERT_EQ(records.size(), 1u);
  ExpectSameScan(std::get<LaserScan>(records[0]), scan);
}

TEST(CarmenWriter, RefusesScanWithoutAnyPose) {
  LaserScan scan = MakeScan(1.0, 50.0);
  scan.logged_pose.reset();
  scan.odometry_pose.reset();
  CarmenWriter writer(testing::TempPath("nopose.clf"));
  EXPECT_THROW(writer.Write(scan), std::invalid_argument);
}

TEST(CarmenWriter, RefusesUnwritablePath) {
  EXPECT_THROW(CarmenWriter(testing::TempPath("no_dir") / "x.clf"), std::runtime_error);
}

// The text between the brackets of "key": [ ... ] split at commas.
std::vector<std::string> JsonArray(const std::string& json, const std::string& key) {
  const std::size_t start = json.find("\"" + key + "\": [");
  EXPECT_NE(start, std::string::npos) << key;
  if (start == std::string::npos) return {};
  const std::size_t open = json.find('[', start);
  const std::size_t close = json.find(']', open);
  std::vector<std::string> items;
  std::stringstream stream(json.substr(open + 1, close - open - 1));
  for (std::string item; std::getline(stream, item, ',');) {
    items.push_back(item.substr(item.find_first_not_of(' ')));
  }
  return items;
}

TEST(CsmJsonWriter, WritesOneLaserDataObjectPerLineInCsmSchema) {
  const LaserScan scan = MakeScan(976052857.337530, 50.0);
  LaserScan no_odometry = MakeScan(976052858.0, 50.0);
  no_odometry.odometry_pose.reset();
  const auto path = testing::TempPath("scans.json");
  {
    CsmJsonWriter writer(path);
    writer.Write(scan);
    writer.Write(no_odometry);
  }
  std::ifstream in(path);
  std::string json;
  std::getline(in, json);
  std::string second;
  std::getline(in, second);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  EXPECT_NE(json.find("\"nrays\": 181,"), std::string::npos);

  const auto theta = JsonArray(json, "theta");
  const auto readings = JsonArray(json, "readings");
  const auto valid = JsonArray(json, "valid");
  ASSERT_EQ(theta.size(), 181u);
  ASSERT_EQ(readings.size(), 181u);
  ASSERT_EQ(valid.size(), 181u);
  for (std::size_t i = 0; i < 181; ++i) {
    EXPECT_NEAR(std::stod(theta[i]), scan.BeamAngle(i), 1e-12);
    // Doubles need a '.' for CSM's json-c to read them as doubles; no-returns are null, valid 0.
    EXPECT_NE(theta[i].find('.'), std::string::npos);
    if (scan.IsReturn(i)) {
      EXPECT_EQ(valid[i], "1");
      EXPECT_EQ(std::stof(readings[i]), scan.ranges_m[i]);
    } else {
      EXPECT_EQ(valid[i], "0");
      EXPECT_EQ(readings[i], "null");
    }
  }
  const auto odometry = JsonArray(json, "odometry");
  ASSERT_EQ(odometry.size(), 3u);
  EXPECT_DOUBLE_EQ(std::stod(odometry[2]), 0.31);
  EXPECT_DOUBLE_EQ(std::stod(JsonArray(json, "estimate")[0]), 1.25);
  EXPECT_EQ(JsonArray(json, "true_pose"), (std::vector<std::string>{"null", "null", "null"}));
  EXPECT_EQ(JsonArray(json, "timestamp"), (std::vector<std::string>{"976052857", "337530"}));
  EXPECT_NEAR(std::stod(json.substr(json.find("\"min_theta\": ") + 13)), -std::numbers::pi / 2,
              1e-15);
  // Without odometry, CSM's initial guess falls back to the logged pose.
  EXPECT_DOUBLE_EQ(std::stod(JsonArray(second, "odometry")[0]), 1.25);
}

}  // namespace
}  // namespace pena::io
