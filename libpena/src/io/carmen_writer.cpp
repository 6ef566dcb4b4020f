// CARMEN FLASER and ODOM lines, written so that the reader gives back exactly what was written.
#include <cmath>
#include <stdexcept>
#include <string>

#include "carmen_line_parser.hpp"
#include "pena/io/carmen.hpp"
#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

// The host field of every line: CARMEN readers expect a word there.
constexpr const char* kHost = "pena";

void AppendNumber(std::string& line, double value) {
  line += ' ';
  line += detail::FormatExact(value);
}

void AppendPose(std::string& line, const geometry::Pose2& pose) {
  AppendNumber(line, pose.x_m);
  AppendNumber(line, pose.y_m);
  AppendNumber(line, pose.theta_rad);
}

// "ipc_timestamp host logger_timestamp": we have one clock, so both stamps are the same.
void AppendStamps(std::string& line, double stamp_s) {
  AppendNumber(line, stamp_s);
  line += ' ';
  line += kHost;
  AppendNumber(line, stamp_s);
  line += '\n';
}

// Ranges that are not returns (no-return, 0, at or above max) become the max range, the code
// FLASER readers (ours included) take as "nothing seen".
std::string FormatRange(const sensors::LaserScan& scan, std::size_t index) {
  if (scan.IsReturn(index)) return detail::FormatExact(scan.ranges_m[index]);
  return detail::FormatExact(scan.geometry.max_range_m);
}

// True when the reader would give this scan its own geometry back from a FLASER line.
bool HasFlaserGeometry(const sensors::LaserScan& scan) {
  const sensors::LaserGeometry expected = detail::FlaserGeometry(scan.ranges_m.size(), ReadOptions{});
  return std::abs(scan.geometry.angle_min_rad - expected.angle_min_rad) < 1e-9 &&
         std::abs(scan.geometry.angle_increment_rad - expected.angle_increment_rad) < 1e-12;
}

std::string RangesText(const sensors::LaserScan& scan) {
  std::string text = std::to_string(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    text += ' ';
    text += FormatRange(scan, i);
  }
  return text;
}

// ROBOTLASER1 states start angle, resolution and max range: used for any other beam geometry.
// Layout: type start fov res max accuracy remission_mode n ranges m remissions laser_pose
// robot_pose tv rv forward_safety side_safety turn_axis stamps.
std::string RobotLaserLine(const sensors::LaserScan& scan, const geometry::Pose2& laser,
                           const geometry::Pose2& robot) {
  const sensors::LaserGeometry& g = scan.geometry;
  const double fov_rad =
      g.angle_increment_rad * static_cast<double>(scan.ranges_m.empty() ? 0 : scan.ranges_m.size() - 1);
  std::string line = "ROBOTLASER1 0";
  for (double value : {g.angle_min_rad, fov_rad, g.angle_increment_rad, g.max_range_m, 0.0, 0.0}) {
    AppendNumber(line, value);
  }
  line += ' ' + RangesText(scan) + " 0";
  AppendPose(line, laser);
  AppendPose(line, robot);
  line += " 0 0 0 0 0";
  AppendStamps(line, scan.stamp_s);
  return line;
}

}  // namespace

struct CarmenWriter::Impl {
  explicit Impl(const std::filesystem::path& path) : out(path) {}
  detail::TextWriter out;
};

CarmenWriter::CarmenWriter(const std::filesystem::path& path)
    : impl_(std::make_unique<Impl>(path)) {}

CarmenWriter::~CarmenWriter() = default;

void CarmenWriter::Write(const sensors::LaserScan& scan) {
  const std::optional<geometry::Pose2>& logged =
      scan.logged_pose ? scan.logged_pose : scan.odometry_pose;
  const std::optional<geometry::Pose2>& odometry =
      scan.odometry_pose ? scan.odometry_pose : scan.logged_pose;
  if (!logged || !odometry) {
    throw std::invalid_argument(impl_->out.path().string() + ": scan at " +
                                detail::FormatExact(scan.stamp_s) +
                                " s has neither odometry_pose nor logged_pose for FLASER");
  }
  if (!(scan.geometry.max_range_m > 0.0)) {
    throw std::invalid_argument(impl_->out.path().string() +
                                ": scan geometry.max_range_m must be > 0 m to write no-returns");
  }
  if (!HasFlaserGeometry(scan)) {
    impl_->out.Put(RobotLaserLine(scan, *logged, *odometry));
    return;
  }
  std::string line = "FLASER " + RangesText(scan);
  AppendPose(line, *logged);
  AppendPose(line, *odometry);
  AppendStamps(line, scan.stamp_s);
  impl_->out.Put(line);
}

void CarmenWriter::Write(const sensors::WheelOdometry& odometry) {
  std::string line = "ODOM";
  AppendPose(line, odometry.odom_pose);
  AppendNumber(line, odometry.forward_velocity_m_s);
  AppendNumber(line, odometry.yaw_rate_rad_s);
  AppendNumber(line, 0.0);  // acceleration: not measured
  AppendStamps(line, odometry.stamp_s);
  impl_->out.Put(line);
}

}  // namespace pena::io
