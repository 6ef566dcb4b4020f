#include "mission_log_codec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <variant>

#include "pena/io/log_summary.hpp"

namespace pena::io::detail {
namespace {

constexpr double kMaxRangeLimitM = 1.0e6;  // keeps millimetre deltas within sint32
constexpr double kMinRangeLimitM = 0.01;
constexpr double kMaxSweepS = 1.0;  // a scan that takes longer is not one scan
constexpr int kMaxInterlace = sensors::LaserGeometry::kMaxInterlace;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Spelled out for compilers without C++20's aggregate deduction (clang before 17).
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::string Number(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.9g", value);
  return text.data();
}

bool SameGeometry(const sensors::LaserGeometry& a, const sensors::LaserGeometry& b) {
  return a.angle_min_rad == b.angle_min_rad && a.angle_increment_rad == b.angle_increment_rad &&
         a.max_range_m == b.max_range_m && a.sweep_s == b.sweep_s &&
         a.interlace == b.interlace;
}

// Strings in a proto3 message must be UTF-8 or the reader's parse fails.
bool IsUtf8(const std::string& text) {
  std::size_t follow = 0;
  for (const unsigned char c : text) {
    if (follow > 0) {
      if ((c & 0xC0u) != 0x80u) return false;
      --follow;
    } else if (c >= 0xF0u && c <= 0xF4u) {
      follow = 3;
    } else if (c >= 0xE0u) {
      if (c > 0xEFu) return false;
      follow = 2;
    } else if (c >= 0xC2u) {
      follow = 1;
    } else if (c >= 0x80u) {
      return false;
    }
  }
  return follow == 0;
}

// --- Conversions between libpena types and the schema (the only place that knows both). ---

void ToProto(const geometry::Pose2& pose, log::Pose2* out) {
  out->set_x_m(pose.x_m);
  out->set_y_m(pose.y_m);
  out->set_theta_rad(pose.theta_rad);
}

geometry::Pose2 FromProto(const log::Pose2& pose) {
  return {pose.x_m(), pose.y_m(), pose.theta_rad()};
}

void ToProto(const sensors::LaserGeometry& laser, log::LaserGeometry* out) {
  out->set_angle_min_rad(laser.angle_min_rad);
  out->set_angle_increment_rad(laser.angle_increment_rad);
  out->set_max_range_m(laser.max_range_m);
  out->set_sweep_s(laser.sweep_s);
  out->set_interlace(static_cast<std::uint32_t>(laser.interlace));
}

sensors::LaserGeometry FromProto(const log::LaserGeometry& laser) {
  // Logs before minor version 2 have no interlace field: 0, a single sweep. A value too large
  // for int is clamped so that CheckGeometry names it.
  const std::uint32_t interlace = laser.interlace();
  return {laser.angle_min_rad(), laser.angle_increment_rad(), laser.max_range_m(), laser.sweep_s(),
          interlace == 0 ? 1 : static_cast<int>(std::min<std::uint32_t>(interlace, 1u << 20))};
}

// A return rounded to millimetres, kept at >= 1 mm and below max range so that decoding gives the
// same return / no-return split as LaserScan::IsReturn on the original.
std::int64_t QuantiseReturn(float range_m, double max_range_m) {
  std::int64_t mm = std::max<std::int64_t>(1, std::llround(static_cast<double>(range_m) * 1000.0));
  while (mm > 1 && !(static_cast<float>(static_cast<double>(mm) / 1000.0) <
                     static_cast<float>(max_range_m))) {
    --mm;
  }
  return mm;
}

void EncodeScan(const sensors::LaserScan& scan, const sensors::LaserGeometry& header_laser,
                log::LaserScan* out) {
  out->set_stamp_s(scan.stamp_s);
  if (!SameGeometry(scan.geometry, header_laser)) ToProto(scan.geometry, out->mutable_geometry());
  if (scan.odometry_pose) ToProto(*scan.odometry_pose, out->mutable_odometry_pose());
  if (scan.logged_pose) ToProto(*scan.logged_pose, out->mutable_logged_pose());
  // Neighbouring beams see nearby surfaces: deltas need about a third fewer bytes than absolute
  // millimetres (measured in docs/mission-log.md).
  auto* deltas = out->mutable_range_delta_mm();
  deltas->Reserve(static_cast<int>(scan.ranges_m.size()));
  std::int64_t previous_mm = 0;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const std::int64_t mm =
        scan.IsReturn(i) ? QuantiseReturn(scan.ranges_m[i], scan.geometry.max_range_m) : 0;
    deltas->Add(static_cast<std::int32_t>(mm - previous_mm));
    previous_mm = mm;
  }
}

sensors::LaserScan DecodeScan(const log::LaserScan& in,
                              const sensors::LaserGeometry& header_laser) {
  sensors::LaserScan scan;
  scan.stamp_s = in.stamp_s();
  scan.geometry = in.has_geometry() ? FromProto(in.geometry()) : header_laser;
  if (const std::string problem = CheckGeometry(scan.geometry, "scan.geometry"); !problem.empty()) {
    throw FormatError(in.has_geometry() ? problem
                                        : "laser scan without geometry, and the header has none");
  }
  if (in.has_odometry_pose()) scan.odometry_pose = FromProto(in.odometry_pose());
  if (in.has_logged_pose()) scan.logged_pose = FromProto(in.logged_pose());
  scan.ranges_m.reserve(static_cast<std::size_t>(in.range_delta_mm_size()));
  std::int64_t mm = 0;
  for (const std::int32_t delta : in.range_delta_mm()) {
    mm += delta;
    if (mm < 0) throw FormatError("laser scan: negative range " + std::to_string(mm) + " mm");
    scan.ranges_m.push_back(mm == 0 ? sensors::LaserScan::kNoReturn
                                    : static_cast<float>(static_cast<double>(mm) / 1000.0));
  }
  return scan;
}

}  // namespace

std::string CheckGeometry(const sensors::LaserGeometry& laser, const std::string& name) {
  if (!std::isfinite(laser.angle_min_rad) || !std::isfinite(laser.angle_increment_rad)) {
    return name + ".angle_min_rad and " + name + ".angle_increment_rad must be finite";
  }
  if (!(laser.max_range_m >= kMinRangeLimitM && laser.max_range_m <= kMaxRangeLimitM)) {
    return name + ".max_range_m must be in [" + Number(kMinRangeLimitM) + ", " +
           Number(kMaxRangeLimitM) + "] m, got " + Number(laser.max_range_m);
  }
  if (!(laser.sweep_s >= 0.0 && laser.sweep_s <= kMaxSweepS)) {
    return name + ".sweep_s must be in [0, " + Number(kMaxSweepS) + "] s, got " +
           Number(laser.sweep_s);
  }
  if (!(laser.interlace >= 1 && laser.interlace <= kMaxInterlace)) {
    return name + ".interlace must be in [1, " + std::to_string(kMaxInterlace) + "], got " +
           std::to_string(laser.interlace);
  }
  return {};
}

bool IsUnsetGeometry(const sensors::LaserGeometry& laser) {
  return laser.angle_min_rad == 0.0 && laser.angle_increment_rad == 0.0 && laser.max_range_m == 0.0;
}

std::string CheckHeader(const MissionLogHeader& header) {
  if (header.format_version != kMissionLogFormatVersion) {
    return "header.format_version must be " + std::to_string(kMissionLogFormatVersion) + ", got " +
           std::to_string(header.format_version);
  }
  if (!IsUnsetGeometry(header.laser)) {
    if (const std::string problem = CheckGeometry(header.laser, "header.laser"); !problem.empty()) {
      return problem;
    }
  }
  if (!IsUtf8(header.mission) || !IsUtf8(header.entity_id) || !IsUtf8(header.producer)) {
    return "header mission, entity_id and producer must be UTF-8";
  }
  return {};
}

// Empty if `stamp_s` may follow `previous_s` in one sensor's stream, else what is wrong.
std::string CheckStamp(std::size_t sensor, double stamp_s, double previous_s) {
  const std::string name(SensorName(sensor));
  if (!std::isfinite(stamp_s)) return name + " stamp_s is not finite";
  if (stamp_s < previous_s) {
    return name + " stamp " + Number(stamp_s) + " s goes back in time (previous " + name +
           " stamp " + Number(previous_s) + " s)";
  }
  return {};
}

log::Record ToProto(const sensors::SensorRecord& record,
                    const sensors::LaserGeometry& header_laser) {
  log::Record out;
  std::visit(Overloaded{[&](const sensors::LaserScan& s) {
                          EncodeScan(s, header_laser, out.mutable_laser_scan());
                        },
                        [&](const sensors::GyroSample& s) {
                          out.mutable_gyro()->set_stamp_s(s.stamp_s);
                          out.mutable_gyro()->set_yaw_rate_rad_s(s.yaw_rate_rad_s);
                        },
                        [&](const sensors::CompassSample& s) {
                          out.mutable_compass()->set_stamp_s(s.stamp_s);
                          out.mutable_compass()->set_heading_rad(s.heading_rad);
                        },
                        [&](const sensors::StrideSample& s) {
                          out.mutable_stride()->set_stamp_s(s.stamp_s);
                          out.mutable_stride()->set_length_m(s.length_m);
                        },
                        [&](const sensors::WheelOdometry& s) {
                          auto* o = out.mutable_wheel_odometry();
                          o->set_stamp_s(s.stamp_s);
                          ToProto(s.odom_pose, o->mutable_odom_pose());
                          o->set_forward_velocity_m_s(s.forward_velocity_m_s);
                          o->set_yaw_rate_rad_s(s.yaw_rate_rad_s);
                        },
                        [&](const sensors::GroundTruth& s) {
                          auto* o = out.mutable_ground_truth();
                          o->set_stamp_s(s.stamp_s);
                          ToProto(s.world_from_body, o->mutable_world_from_body());
                          o->set_laser_height_m(s.laser_height_m);
                          o->set_pitch_rad(s.pitch_rad);
                          o->set_roll_rad(s.roll_rad);
                        }},
             record);
  return out;
}

// nullopt for a payload this reader does not know (a record type added in a later minor version).
std::optional<sensors::SensorRecord> FromProto(const log::Record& in,
                                               const sensors::LaserGeometry& header_laser) {
  switch (in.payload_case()) {
    case log::Record::kLaserScan:
      return DecodeScan(in.laser_scan(), header_laser);
    case log::Record::kGyro:
      return sensors::GyroSample{in.gyro().stamp_s(), in.gyro().yaw_rate_rad_s()};
    case log::Record::kCompass:
      return sensors::CompassSample{in.compass().stamp_s(), in.compass().heading_rad()};
    case log::Record::kStride:
      return sensors::StrideSample{in.stride().stamp_s(), in.stride().length_m()};
    case log::Record::kWheelOdometry: {
      const auto& o = in.wheel_odometry();
      return sensors::WheelOdometry{o.stamp_s(), FromProto(o.odom_pose()), o.forward_velocity_m_s(),
                                    o.yaw_rate_rad_s()};
    }
    case log::Record::kGroundTruth: {
      const auto& o = in.ground_truth();
      return sensors::GroundTruth{o.stamp_s(), FromProto(o.world_from_body()), o.laser_height_m(),
                                  o.pitch_rad(), o.roll_rad()};
    }
    case log::Record::PAYLOAD_NOT_SET:
      break;
  }
  return std::nullopt;
}

log::MissionLogHeader ToProto(const MissionLogHeader& header) {
  log::MissionLogHeader out;
  out.set_mission(header.mission);
  out.set_entity_id(header.entity_id);
  out.set_kind(header.kind == sensors::EntityKind::kHuman ? log::ENTITY_KIND_HUMAN
                                                          : log::ENTITY_KIND_ROBOT);
  if (!IsUnsetGeometry(header.laser)) ToProto(header.laser, out.mutable_laser());
  out.set_laser_height_m(header.laser_height_m);
  out.set_producer(header.producer);
  return out;
}

MissionLogHeader FromProto(const log::MissionLogHeader& in) {
  MissionLogHeader header;
  header.mission = in.mission();
  header.entity_id = in.entity_id();
  if (in.kind() == log::ENTITY_KIND_HUMAN) {
    header.kind = sensors::EntityKind::kHuman;
  } else if (in.kind() == log::ENTITY_KIND_ROBOT) {
    header.kind = sensors::EntityKind::kRobot;
  } else {
    throw FormatError("header: unknown entity kind " + std::to_string(in.kind()));
  }
  if (in.has_laser()) {
    header.laser = FromProto(in.laser());
    if (const std::string problem = CheckGeometry(header.laser, "header.laser"); !problem.empty()) {
      throw FormatError(problem);
    }
  }
  header.laser_height_m = in.laser_height_m();
  header.producer = in.producer();
  return header;
}

}  // namespace pena::io::detail
