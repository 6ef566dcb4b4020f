#include "carmen_line_parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "text_fields.hpp"

namespace pena::io::detail {
namespace {

using Fields = std::vector<std::string_view>;

// Field counts around the variable parts of each message (see docs/formats.md).
constexpr std::size_t kFlaserFixedFields = 11;   // type n [ranges] x y th ox oy oth ts host lts
constexpr std::size_t kOdomFields = 10;          // type x y th tv rv accel ts host lts
constexpr std::size_t kLaserHeaderFields = 9;    // type laser_type start fov res max acc rem n
constexpr std::size_t kRobotLaserTailFields = 14;  // 2 poses, tv rv fwd side turn, ts host lts
constexpr std::size_t kRawLaserTailFields = 3;     // ts host lts
constexpr std::int64_t kMaxBeams = 100000;

[[noreturn]] void Fail(const std::string& message) { throw CarmenLineError(message); }

std::string Quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// A finite number at `index`; the message names the field by position (from 1) and meaning.
double Number(const Fields& fields, std::size_t index, const char* name) {
  const std::optional<double> value = ParseDouble(fields[index]);
  const std::string where = "field " + std::to_string(index + 1) + " (" + name + ")";
  if (!value) Fail(where + " " + Quoted(fields[index]) + " is not a number");
  if (!std::isfinite(*value)) Fail(where + " is " + std::string(fields[index]) + ", not finite");
  return *value;
}

geometry::Pose2 Pose(const Fields& fields, std::size_t index, const char* x_name,
                     const char* y_name, const char* theta_name) {
  return {Number(fields, index, x_name), Number(fields, index + 1, y_name),
          Number(fields, index + 2, theta_name)};
}

// A non-negative count at `index`, at most `limit`.
std::size_t Count(const Fields& fields, std::size_t index, const char* name, std::int64_t limit) {
  const std::optional<std::int64_t> value = ParseInt64(fields[index]);
  if (!value || *value < 0 || *value > limit) {
    Fail(std::string(name) + " " + Quoted(fields[index]) + " is not an integer in 0.." +
         std::to_string(limit));
  }
  return static_cast<std::size_t>(*value);
}

// One range in metres; no-return codes (0, at or above max range, +inf) become kNoReturn.
float Range(std::string_view field, std::size_t beam, float max_range_m) {
  std::optional<float> value = ParseFloat(field);
  if (!value) {
    // from_chars refuses values beyond float's range; a huge positive range is still a no-return.
    const std::optional<double> wide = ParseDouble(field);
    if (!wide) Fail("range " + std::to_string(beam) + " " + Quoted(field) + " is not a number");
    value = *wide > 0.0 ? sensors::LaserScan::kNoReturn : -sensors::LaserScan::kNoReturn;
  }
  const float range_m = *value;
  if (std::isnan(range_m)) Fail("range " + std::to_string(beam) + " is NaN");
  if (range_m < 0.0f) {
    Fail("negative range " + std::string(field) + " at beam " + std::to_string(beam));
  }
  if (range_m == 0.0f || range_m >= max_range_m) return sensors::LaserScan::kNoReturn;
  return range_m;
}

std::vector<float> Ranges(const Fields& fields, std::size_t first, std::size_t count,
                          double max_range_m) {
  std::vector<float> ranges(count);
  const auto max_range = static_cast<float>(max_range_m);
  for (std::size_t i = 0; i < count; ++i) ranges[i] = Range(fields[first + i], i, max_range);
  return ranges;
}

// Checks that the line has exactly `expected` fields, `fixed` of them besides the ranges.
void RequireFieldCount(const Fields& fields, std::size_t expected, std::size_t beams,
                       std::size_t fixed) {
  if (fields.size() == expected) return;
  if (fields.size() >= fixed) {
    Fail("expected " + std::to_string(beams) + " ranges, found " +
         std::to_string(fields.size() - fixed));
  }
  Fail("expected " + std::to_string(expected) + " fields for " + std::to_string(beams) +
       " ranges, found " + std::to_string(fields.size()));
}

sensors::LaserScan ParseFlaser(const Fields& fields, const ReadOptions& options) {
  if (fields.size() < 2) Fail("FLASER line has no beam count");
  const std::size_t n = Count(fields, 1, "beam count", kMaxBeams);
  RequireFieldCount(fields, n + kFlaserFixedFields, n, kFlaserFixedFields);
  sensors::LaserScan scan;
  scan.geometry = FlaserGeometry(n, options);
  scan.ranges_m = Ranges(fields, 2, n, options.carmen_max_range_m);
  scan.logged_pose = Pose(fields, n + 2, "x", "y", "theta");
  scan.odometry_pose = Pose(fields, n + 5, "odom_x", "odom_y", "odom_theta");
  scan.stamp_s = Number(fields, n + 8, "ipc_timestamp");
  return scan;
}

sensors::WheelOdometry ParseOdom(const Fields& fields) {
  if (fields.size() != kOdomFields) {
    Fail("expected " + std::to_string(kOdomFields) + " fields in ODOM, found " +
         std::to_string(fields.size()));
  }
  sensors::WheelOdometry odometry;
  odometry.odom_pose = Pose(fields, 1, "x", "y", "theta");
  odometry.forward_velocity_m_s = Number(fields, 4, "tv");
  odometry.yaw_rate_rad_s = Number(fields, 5, "rv");
  Number(fields, 6, "accel");
  odometry.stamp_s = Number(fields, 7, "ipc_timestamp");
  return odometry;
}

// ROBOTLASER1 and RAWLASERn share the head: they state their own geometry and maximum range.
// `tail` is the number of fields after the remissions.
sensors::LaserScan ParseStatedLaser(const Fields& fields, std::size_t tail,
                                    const ReadOptions& options, std::size_t* tail_start) {
  if (fields.size() < kLaserHeaderFields) Fail("laser line too short for its header");
  for (std::size_t i = 1; i < 8; ++i) Number(fields, i, "laser header");
  sensors::LaserScan scan;
  scan.geometry.angle_min_rad = Number(fields, 2, "start_angle");
  scan.geometry.angle_increment_rad = Number(fields, 4, "angular_resolution");
  scan.geometry.max_range_m = Number(fields, 5, "maximum_range");
  scan.geometry.sweep_s = options.carmen_sweep_s;
  scan.geometry.interlace = CarmenInterlace(scan.geometry.angle_increment_rad, options);
  if (scan.geometry.max_range_m <= 0.0) {
    Fail("maximum_range " + std::string(fields[5]) + " m must be > 0 m");
  }
  const std::size_t n = Count(fields, 8, "beam count", kMaxBeams);
  if (fields.size() < kLaserHeaderFields + n + 1) {
    Fail("expected " + std::to_string(n) + " ranges and a remission count, found " +
         std::to_string(fields.size() - kLaserHeaderFields) + " fields after the beam count");
  }
  const std::size_t m = Count(fields, kLaserHeaderFields + n, "remission count", kMaxBeams);
  const std::size_t fixed = kLaserHeaderFields + 1 + m + tail;
  RequireFieldCount(fields, fixed + n, n, fixed);
  scan.ranges_m = Ranges(fields, kLaserHeaderFields, n, scan.geometry.max_range_m);
  for (std::size_t i = 0; i < m; ++i) Number(fields, kLaserHeaderFields + n + 1 + i, "remission");
  *tail_start = kLaserHeaderFields + n + 1 + m;
  return scan;
}

sensors::LaserScan ParseRobotLaser(const Fields& fields, const ReadOptions& options) {
  std::size_t tail = 0;
  sensors::LaserScan scan = ParseStatedLaser(fields, kRobotLaserTailFields, options, &tail);
  scan.logged_pose = Pose(fields, tail, "laser_x", "laser_y", "laser_theta");
  scan.odometry_pose = Pose(fields, tail + 3, "robot_x", "robot_y", "robot_theta");
  for (std::size_t i = tail + 6; i < tail + 11; ++i) Number(fields, i, "velocity or safety");
  scan.stamp_s = Number(fields, tail + 11, "ipc_timestamp");
  return scan;
}

sensors::LaserScan ParseRawLaser(const Fields& fields, const ReadOptions& options) {
  std::size_t tail = 0;
  sensors::LaserScan scan = ParseStatedLaser(fields, kRawLaserTailFields, options, &tail);
  scan.stamp_s = Number(fields, tail, "ipc_timestamp");
  return scan;
}

bool IsRawLaser(std::string_view type) {
  return type == "RAWLASER1" || type == "RAWLASER2" || type == "RAWLASER3" ||
         type == "RAWLASER4";
}

}  // namespace

sensors::LaserGeometry FlaserGeometry(std::size_t beam_count, const ReadOptions& options) {
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  constexpr double kOneDegree = std::numbers::pi / 180.0;
  sensors::LaserGeometry geometry;
  geometry.max_range_m = options.carmen_max_range_m;
  geometry.sweep_s = options.carmen_sweep_s;
  if (beam_count < 2) return geometry;  // a single beam looks straight ahead
  geometry.angle_min_rad = -kHalfPi;
  // 181 and 361 beams span -90..+90 deg at 1 and 0.5 deg; 180 beams are ambiguous (option).
  const bool one_degree_steps = beam_count == 180 && !options.carmen_180_beams_span_180_deg;
  geometry.angle_increment_rad =
      one_degree_steps ? kOneDegree : std::numbers::pi / static_cast<double>(beam_count - 1);
  geometry.interlace = CarmenInterlace(geometry.angle_increment_rad, options);
  return geometry;
}

int CarmenInterlace(double angle_increment_rad, const ReadOptions& options) {
  if (options.carmen_interlace > 0) return options.carmen_interlace;
  // A SICK LMS 2xx measures 1 deg steps per mirror turn; finer steps are turns interleaved.
  constexpr double kOneDegree = std::numbers::pi / 180.0;
  const double steps_per_degree = kOneDegree / std::abs(angle_increment_rad);
  if (!(steps_per_degree > 1.5)) return 1;  // 1 deg or coarser (or no increment: one beam)
  constexpr auto kMax = static_cast<double>(sensors::LaserGeometry::kMaxInterlace);
  return static_cast<int>(std::min(std::round(steps_per_degree), kMax));
}

std::optional<CarmenMessage> ParseCarmenLine(std::string_view line, const ReadOptions& options) {
  const Fields fields = SplitWhitespace(line);
  if (fields.empty() || fields[0].front() == '#') return std::nullopt;
  const std::string_view type = fields[0];
  if (type == "FLASER") return CarmenMessage{"FLASER", ParseFlaser(fields, options)};
  if (type == "ODOM") return CarmenMessage{"ODOM", ParseOdom(fields)};
  if (type == "ROBOTLASER1") return CarmenMessage{"ROBOTLASER1", ParseRobotLaser(fields, options)};
  if (IsRawLaser(type)) return CarmenMessage{std::string(type), ParseRawLaser(fields, options)};
  return std::nullopt;
}

}  // namespace pena::io::detail
