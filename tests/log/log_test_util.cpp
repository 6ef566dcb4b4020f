#include "log_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <sstream>
#include <variant>

#include "scoped_temp_dir.hpp"

namespace pena::io::testing {

std::filesystem::path TempPath(const std::string& name) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = pena::testing::ProcessTempDir() /
                                    (std::string(test->test_suite_name()) + "." + test->name());
  std::filesystem::create_directories(dir);
  return dir / name;
}

MissionLogHeader MakeHeader() {
  MissionLogHeader header;
  header.mission = "office";
  header.entity_id = "ff1";
  header.kind = sensors::EntityKind::kHuman;
  header.laser = {-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  header.laser_height_m = 1.35;
  header.producer = "log_test --seed 7";
  return header;
}

sensors::LaserScan MakeScan(double stamp_s, const sensors::LaserGeometry& geometry) {
  sensors::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.geometry = geometry;
  for (std::size_t i = 0; i < 361; ++i) {
    const double angle = scan.BeamAngle(i);
    // Distance to the walls of a 4 m x 6 m room from its centre, plus a stamp-dependent wiggle so
    // scans differ and ranges are not round millimetres.
    const double to_x = 3.0 / std::max(std::abs(std::cos(angle)), 1e-9);
    const double to_y = 2.0 / std::max(std::abs(std::sin(angle)), 1e-9);
    const double range = std::min(to_x, to_y) + 0.0003 * std::sin(7.0 * stamp_s + 0.37 * double(i));
    scan.ranges_m.push_back(static_cast<float>(range));
  }
  scan.ranges_m[10] = sensors::LaserScan::kNoReturn;
  scan.ranges_m[11] = std::numeric_limits<float>::quiet_NaN();
  scan.ranges_m[12] = 0.0f;
  scan.ranges_m[13] = static_cast<float>(geometry.max_range_m + 5.0);
  scan.ranges_m[14] = static_cast<float>(geometry.max_range_m);  // at max range: no-return too
  scan.ranges_m[15] = static_cast<float>(geometry.max_range_m - 0.0002);  // just a return
  scan.ranges_m[16] = 0.0002f;  // a return below a millimetre stays a return
  return scan;
}

std::vector<sensors::SensorRecord> MakeOneOfEach(double stamp_s) {
  const MissionLogHeader header = MakeHeader();
  sensors::LaserScan with_poses = MakeScan(stamp_s, header.laser);
  with_poses.odometry_pose = geometry::Pose2{1.25, -3.5, 0.75};
  with_poses.logged_pose = geometry::Pose2{1.2, -3.4, 0.7};
  // A scan whose geometry differs from the header's (e.g. a second laser setting).
  sensors::LaserScan other_geometry = MakeScan(stamp_s + 0.01, {-2.0, 0.01, 8.0});
  other_geometry.ranges_m.resize(200);
  return {
      with_poses,
      other_geometry,
      sensors::GyroSample{stamp_s + 0.02, -0.123456789},
      sensors::CompassSample{stamp_s + 0.03, 2.9},
      sensors::StrideSample{stamp_s + 0.04, 0.71},
      sensors::WheelOdometry{stamp_s + 0.05, {10.5, 2.25, -3.0}, 0.4, 0.05},
      sensors::GroundTruth{stamp_s + 0.06, {3.0, 4.0, 1.0}, 1.3, 0.087, -0.01},
  };
}

void WriteLog(const std::filesystem::path& path, const MissionLogHeader& header,
              const std::vector<sensors::SensorRecord>& records) {
  MissionLogWriter writer(path, header);
  for (const auto& record : records) writer.Write(record);
  writer.Close();
}

std::vector<sensors::SensorRecord> ReadAll(MissionLogReader& reader, std::string* error) {
  std::vector<sensors::SensorRecord> records;
  try {
    while (auto record = reader.Next()) records.push_back(std::move(*record));
  } catch (const InputError& e) {
    if (error == nullptr) throw;
    *error = e.what();
  }
  return records;
}

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  // A new file, not a truncated one: ext4 flushes truncated-and-rewritten files on close, which
  // makes the byte-by-byte corruption tests crawl.
  std::filesystem::remove(path);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

namespace {

void ExpectSamePose(const geometry::Pose2& expected, const geometry::Pose2& actual) {
  EXPECT_EQ(expected.x_m, actual.x_m);
  EXPECT_EQ(expected.y_m, actual.y_m);
  EXPECT_EQ(expected.theta_rad, actual.theta_rad);
}

void ExpectSameScan(const sensors::LaserScan& expected, const sensors::LaserScan& actual) {
  EXPECT_EQ(expected.geometry.angle_min_rad, actual.geometry.angle_min_rad);
  EXPECT_EQ(expected.geometry.angle_increment_rad, actual.geometry.angle_increment_rad);
  EXPECT_EQ(expected.geometry.max_range_m, actual.geometry.max_range_m);
  EXPECT_EQ(expected.geometry.sweep_s, actual.geometry.sweep_s);
  EXPECT_EQ(expected.geometry.interlace, actual.geometry.interlace);
  ASSERT_EQ(expected.ranges_m.size(), actual.ranges_m.size());
  for (std::size_t i = 0; i < expected.ranges_m.size(); ++i) {
    ASSERT_EQ(expected.IsReturn(i), actual.IsReturn(i)) << "beam " << i;
    if (expected.IsReturn(i)) {
      EXPECT_NEAR(expected.ranges_m[i], actual.ranges_m[i], 0.001) << "beam " << i;
    } else {
      EXPECT_EQ(actual.ranges_m[i], sensors::LaserScan::kNoReturn) << "beam " << i;
    }
  }
  ASSERT_EQ(expected.odometry_pose.has_value(), actual.odometry_pose.has_value());
  if (expected.odometry_pose) ExpectSamePose(*expected.odometry_pose, *actual.odometry_pose);
  ASSERT_EQ(expected.logged_pose.has_value(), actual.logged_pose.has_value());
  if (expected.logged_pose) ExpectSamePose(*expected.logged_pose, *actual.logged_pose);
}

}  // namespace

void ExpectSameRecord(const sensors::SensorRecord& expected, const sensors::SensorRecord& actual) {
  ASSERT_EQ(expected.index(), actual.index());
  EXPECT_EQ(sensors::StampOf(expected), sensors::StampOf(actual));  // exact
  if (const auto* scan = std::get_if<sensors::LaserScan>(&expected)) {
    ExpectSameScan(*scan, std::get<sensors::LaserScan>(actual));
  } else if (const auto* gyro = std::get_if<sensors::GyroSample>(&expected)) {
    EXPECT_EQ(gyro->yaw_rate_rad_s, std::get<sensors::GyroSample>(actual).yaw_rate_rad_s);
  } else if (const auto* compass = std::get_if<sensors::CompassSample>(&expected)) {
    EXPECT_EQ(compass->heading_rad, std::get<sensors::CompassSample>(actual).heading_rad);
  } else if (const auto* stride = std::get_if<sensors::StrideSample>(&expected)) {
    EXPECT_EQ(stride->length_m, std::get<sensors::StrideSample>(actual).length_m);
  } else if (const auto* odometry = std::get_if<sensors::WheelOdometry>(&expected)) {
    const auto& got = std::get<sensors::WheelOdometry>(actual);
    ExpectSamePose(odometry->odom_pose, got.odom_pose);
    EXPECT_EQ(odometry->forward_velocity_m_s, got.forward_velocity_m_s);
    EXPECT_EQ(odometry->yaw_rate_rad_s, got.yaw_rate_rad_s);
  } else {
    const auto& truth = std::get<sensors::GroundTruth>(expected);
    const auto& got = std::get<sensors::GroundTruth>(actual);
    ExpectSamePose(truth.world_from_body, got.world_from_body);
    EXPECT_EQ(truth.laser_height_m, got.laser_height_m);
    EXPECT_EQ(truth.pitch_rad, got.pitch_rad);
    EXPECT_EQ(truth.roll_rad, got.roll_rad);
  }
}

}  // namespace pena::io::testing
