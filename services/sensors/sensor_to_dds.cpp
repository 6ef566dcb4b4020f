#include "sensor_to_dds.hpp"

#include <stdexcept>

#include "to_dds.hpp"

namespace pena::services {
namespace {

// Sets the fields every sensor sample starts with.
template <class Sample>
Sample Header(const std::string& entity_id, std::uint64_t seq, double stamp_s) {
  Sample sample;
  SetBounded(sample.entity_id(), entity_id, "entity_id");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  sample.seq(seq);
  sample.stamp_s(stamp_s);
  return sample;
}

struct Converter {
  const std::string& entity_id;
  std::uint64_t seq;

  SensorSample operator()(const sensors::LaserScan& scan) const {
    if (scan.ranges_m.size() > pena_dds::SCAN_MAX_BEAMS) {
      throw std::length_error("ranges_m holds at most " + std::to_string(pena_dds::SCAN_MAX_BEAMS) +
                              " beams, got " + std::to_string(scan.ranges_m.size()));
    }
    auto out = Header<pena_dds::LaserScanSample>(entity_id, seq, scan.stamp_s);
    out.angle_min_rad(scan.geometry.angle_min_rad);
    out.angle_increment_rad(scan.geometry.angle_increment_rad);
    out.max_range_m(scan.geometry.max_range_m);
    out.ranges_m(scan.ranges_m);
    out.has_odometry_pose(scan.odometry_pose.has_value());
    if (scan.odometry_pose) out.odometry_pose(ToDds(*scan.odometry_pose));
    out.has_logged_pose(scan.logged_pose.has_value());
    if (scan.logged_pose) out.logged_pose(ToDds(*scan.logged_pose));
    return out;
  }
  SensorSample operator()(const sensors::GyroSample& gyro) const {
    auto out = Header<pena_dds::GyroSample>(entity_id, seq, gyro.stamp_s);
    out.yaw_rate_rad_s(gyro.yaw_rate_rad_s);
    return out;
  }
  SensorSample operator()(const sensors::CompassSample& compass) const {
    auto out = Header<pena_dds::CompassSample>(entity_id, seq, compass.stamp_s);
    out.heading_rad(compass.heading_rad);
    return out;
  }
  SensorSample operator()(const sensors::StrideSample& stride) const {
    auto out = Header<pena_dds::StrideSample>(entity_id, seq, stride.stamp_s);
    out.length_m(stride.length_m);
    return out;
  }
  SensorSample operator()(const sensors::WheelOdometry& odometry) const {
    auto out = Header<pena_dds::WheelOdometrySample>(entity_id, seq, odometry.stamp_s);
    out.odom_pose(ToDds(odometry.odom_pose));
    out.forward_velocity_m_s(odometry.forward_velocity_m_s);
    out.yaw_rate_rad_s(odometry.yaw_rate_rad_s);
    return out;
  }
  // Ground truth exists only in simulation: no sensor publishes it.
  SensorSample operator()(const sensors::GroundTruth&) const { return std::monostate{}; }
};

}  // namespace

SensorSample ToDdsSensorSample(const sensors::SensorRecord& record, const std::string& entity_id,
                               std::uint64_t seq) {
  return std::visit(Converter{entity_id, seq}, record);
}

}  // namespace pena::services
