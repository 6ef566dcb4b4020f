#include "sensor_from_dds.hpp"

#include <cmath>
#include <sstream>

namespace pena::services {
namespace {

SensorCheck Refuse(const std::string& why) { return {std::nullopt, why, 0}; }

// What every sample must satisfy: our schema and a finite stamp; empty if fine.
template <class Sample>
std::string CheckHeader(const Sample& sample) {
  if (sample.schema_version() != pena_dds::SCHEMA_VERSION) {
    return "schema_version " + std::to_string(sample.schema_version()) + ", this reader knows " +
           std::to_string(pena_dds::SCHEMA_VERSION);
  }
  if (!std::isfinite(sample.stamp_s())) return "stamp_s is not finite";
  return {};
}

// Empty if every named value is finite, else the first offender's name.
std::string FirstNonFinite(std::initializer_list<std::pair<const char*, double>> values) {
  for (const auto& [name, value] : values) {
    if (!std::isfinite(value)) {
      std::ostringstream out;
      out << name << " is not finite (" << value << ")";
      return out.str();
    }
  }
  return {};
}

geometry::Pose2 PoseFrom(const pena_dds::Pose2& pose) {
  return {pose.x_m(), pose.y_m(), pose.theta_rad()};
}

std::string CheckPose(const char* name, const pena_dds::Pose2& pose) {
  const std::string bad = FirstNonFinite({{"x_m", pose.x_m()}, {"y_m", pose.y_m()},
                                          {"theta_rad", pose.theta_rad()}});
  return bad.empty() ? bad : std::string(name) + "." + bad;
}

}  // namespace

SensorCheck FromDds(const pena_dds::LaserScanSample& sample, std::size_t max_beams) {
  if (std::string bad = CheckHeader(sample); !bad.empty()) return Refuse(bad);
  const std::size_t beams = sample.ranges_m().size();
  const std::size_t bound = std::min<std::size_t>(max_beams, pena_dds::SCAN_MAX_BEAMS);
  if (beams == 0 || beams > bound) {
    return Refuse("ranges_m holds " + std::to_string(beams) + " beams, allowed 1.." +
                  std::to_string(bound));
  }
  if (std::string bad = FirstNonFinite({{"angle_min_rad", sample.angle_min_rad()},
                                        {"angle_increment_rad", sample.angle_increment_rad()},
                                        {"max_range_m", sample.max_range_m()}});
      !bad.empty()) {
    return Refuse(bad);
  }
  if (sample.max_range_m() <= 0.0) return Refuse("max_range_m must be > 0");
  if (sample.angle_increment_rad() == 0.0) return Refuse("angle_increment_rad must not be 0");
  if (sample.has_odometry_pose()) {
    if (std::string bad = CheckPose("odometry_pose", sample.odometry_pose()); !bad.empty()) {
      return Refuse(bad);
    }
  }
  if (sample.has_logged_pose()) {
    if (std::string bad = CheckPose("logged_pose", sample.logged_pose()); !bad.empty()) {
      return Refuse(bad);
    }
  }
  sensors::LaserScan scan;
  scan.stamp_s = sample.stamp_s();
  scan.geometry = {sample.angle_min_rad(), sample.angle_increment_rad(), sample.max_range_m()};
  scan.ranges_m = sample.ranges_m();
  SensorCheck out;
  // A NaN compares false with everything, so the chain's IsReturn() would already skip it, but
  // one explicit no-return code keeps every consumer (grid, reference scans) on one rule.
  for (float& range : scan.ranges_m) {
    if (std::isnan(range) || range < 0.0f) {
      range = sensors::LaserScan::kNoReturn;
      ++out.bad_ranges;
    }
  }
  if (sample.has_odometry_pose()) scan.odometry_pose = PoseFrom(sample.odometry_pose());
  if (sample.has_logged_pose()) scan.logged_pose = PoseFrom(sample.logged_pose());
  out.record = std::move(scan);
  return out;
}

SensorCheck FromDds(const pena_dds::GyroSample& sample) {
  if (std::string bad = CheckHeader(sample); !bad.empty()) return Refuse(bad);
  if (std::string bad = FirstNonFinite({{"yaw_rate_rad_s", sample.yaw_rate_rad_s()}});
      !bad.empty()) {
    return Refuse(bad);
  }
  return {sensors::GyroSample{sample.stamp_s(), sample.yaw_rate_rad_s()}, {}, 0};
}

SensorCheck FromDds(const pena_dds::CompassSample& sample) {
  if (std::string bad = CheckHeader(sample); !bad.empty()) return Refuse(bad);
  if (std::string bad = FirstNonFinite({{"heading_rad", sample.heading_rad()}}); !bad.empty()) {
    return Refuse(bad);
  }
  return {sensors::CompassSample{sample.stamp_s(), sample.heading_rad()}, {}, 0};
}

SensorCheck FromDds(const pena_dds::StrideSample& sample) {
  if (std::string bad = CheckHeader(sample); !bad.empty()) return Refuse(bad);
  if (std::string bad = FirstNonFinite({{"length_m", sample.length_m()}}); !bad.empty()) {
    return Refuse(bad);
  }
  if (sample.length_m() < 0.0) return Refuse("length_m must be >= 0");
  return {sensors::StrideSample{sample.stamp_s(), sample.length_m()}, {}, 0};
}

SensorCheck FromDds(const pena_dds::WheelOdometrySample& sample) {
  if (std::string bad = CheckHeader(sample); !bad.empty()) return Refuse(bad);
  if (std::string bad = CheckPose("odom_pose", sample.odom_pose()); !bad.empty()) {
    return Refuse(bad);
  }
  if (std::string bad = FirstNonFinite({{"forward_velocity_m_s", sample.forward_velocity_m_s()},
                                        {"yaw_rate_rad_s", sample.yaw_rate_rad_s()}});
      !bad.empty()) {
    return Refuse(bad);
  }
  sensors::WheelOdometry odometry;
  odometry.stamp_s = sample.stamp_s();
  odometry.odom_pose = PoseFrom(sample.odom_pose());
  odometry.forward_velocity_m_s = sample.forward_velocity_m_s();
  odometry.yaw_rate_rad_s = sample.yaw_rate_rad_s();
  return {std::move(odometry), {}, 0};
}

}  // namespace pena::services
