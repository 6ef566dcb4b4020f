#include "pena/gateway/link_codec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "pena/line_map/map_packing.hpp"

namespace pena::gateway {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

std::int32_t ClampInt32(double value) {
  const double limit = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(std::llround(std::clamp(value, -limit, limit)));
}

std::int64_t ClampInt64(double value) {
  constexpr double kLimit = 9.0e18;
  if (!std::isfinite(value)) return 0;
  return static_cast<std::int64_t>(std::llround(std::clamp(value, -kLimit, kLimit)));
}

std::int32_t StampOffset(double stamp_s, std::uint64_t base_ms) {
  return ClampInt32(static_cast<double>(StampMs(stamp_s)) - static_cast<double>(base_ms));
}

double StampFrom(std::int32_t offset_ms, std::uint64_t base_ms) {
  return (static_cast<double>(base_ms) + offset_ms) / 1000.0;
}

// Heading in [0, 3600) tenths of a degree.
std::uint32_t HeadingDdeg(double theta_rad) {
  const long long ddeg = std::llround(geometry::NormalizeAngle(theta_rad) * kRadToDeg * 10.0);
  return static_cast<std::uint32_t>(((ddeg % 3600) + 3600) % 3600);
}

// A standard deviation in `quantum` units, rounded up so the far side is never more certain;
// unknown (0, negative or not finite) stays 0, and a huge one is capped.
std::uint32_t SdQuanta(double sd, double quantum) {
  constexpr double kMaxQuanta = 1e9;
  if (!(sd > 0.0)) return 0;
  return static_cast<std::uint32_t>(std::min(std::ceil(sd / quantum), kMaxQuanta));
}

void PutPose(const PoseUpdate& pose, std::uint64_t base_ms, link::Pose* out) {
  out->set_entity(pose.entity);
  out->set_x_cm(ClampInt32(pose.world_from_body.x_m * 100.0));
  out->set_y_cm(ClampInt32(pose.world_from_body.y_m * 100.0));
  out->set_heading_ddeg(HeadingDdeg(pose.world_from_body.theta_rad));
  out->set_stamp_offset_ms(StampOffset(pose.stamp_s, base_ms));
  out->set_position_sd_cm(SdQuanta(pose.position_sd_m, 0.01));
  out->set_heading_sd_ddeg(SdQuanta(pose.heading_sd_rad, 0.1 / kRadToDeg));
  if (pose.mission_stamp_s) out->set_mission_stamp_ms(ClampInt64(*pose.mission_stamp_s * 1e3));
}

void PutAnnotation(const Annotation& a, std::uint64_t base_ms, link::Annotation* out) {
  out->set_alarm(a.alarm);
  out->set_entity(a.entity);
  out->set_id(a.id);
  out->set_x_cm(ClampInt32(a.x_m * 100.0));
  out->set_y_cm(ClampInt32(a.y_m * 100.0));
  out->set_stamp_offset_ms(StampOffset(a.stamp_s, base_ms));
  out->set_text(a.text);
  if (a.mission_stamp_s) out->set_mission_stamp_ms(ClampInt64(*a.mission_stamp_s * 1e3));
  out->set_radius_cm(static_cast<std::uint32_t>(std::clamp(std::ceil(a.radius_m * 100.0), 0.0, 1e9)));
  for (const auto& [x, y] : a.outline_m) {
    out->add_outline_cm(ClampInt32(x * 100.0));
    out->add_outline_cm(ClampInt32(y * 100.0));
  }
}

std::int32_t Mm(double metres) { return ClampInt32(metres * 1000.0); }

void PutOperatorCorrection(const OperatorCorrection& c, std::uint64_t base_ms,
                           link::OperatorCorrection* out) {
  out->set_correction_id(c.correction_id);
  out->set_operator_id(c.operator_id);
  out->set_kind(c.kind);
  out->set_entity(c.entity);
  out->set_mission_stamp_us(ClampInt64(c.mission_stamp_s * 1e6));
  out->set_origin_x_mm(Mm(c.origin_x_m));
  out->set_origin_y_mm(Mm(c.origin_y_m));
  out->set_wrong_x_mm(Mm(c.wrong_x_m));
  out->set_wrong_y_mm(Mm(c.wrong_y_m));
  out->set_correct_x_mm(Mm(c.correct_x_m));
  out->set_correct_y_mm(Mm(c.correct_y_m));
  out->set_pose_x_mm(Mm(c.world_from_body.x_m));
  out->set_pose_y_mm(Mm(c.world_from_body.y_m));
  out->set_pose_heading_cdeg(
      ClampInt32(geometry::NormalizeAngle(c.world_from_body.theta_rad) * kRadToDeg * 100.0));
  out->set_console_seq(c.console_seq);
  out->set_segment_id(c.segment_id);
  out->set_segment_x0_mm(Mm(c.segment_x0_m));
  out->set_segment_y0_mm(Mm(c.segment_y0_m));
  out->set_segment_x1_mm(Mm(c.segment_x1_m));
  out->set_segment_y1_mm(Mm(c.segment_y1_m));
  out->set_applied(c.applied);
  out->set_refusal(c.refusal);
  out->set_stamp_offset_ms(StampOffset(c.stamp_s, base_ms));
  out->set_undoes_id(c.undoes_id);
}

void PutCorrection(const Correction& c, std::uint64_t base_ms, link::Correction* out) {
  out->set_entity(c.entity);
  out->set_x_mm(ClampInt32(c.world_from_local.x_m * 1000.0));
  out->set_y_mm(ClampInt32(c.world_from_local.y_m * 1000.0));
  out->set_heading_cdeg(ClampInt32(geometry::NormalizeAngle(c.world_from_local.theta_rad) *
                                   kRadToDeg * 100.0));
  out->set_version(c.version);
  out->set_stamp_offset_ms(StampOffset(c.stamp_s, base_ms));
  out->set_operator_id(c.operator_id);
}

void PutMap(const MapChange& change, link::MapUpdate* out) {
  out->set_map_id(change.map_id);
  if (const auto* delta = std::get_if<line_map::MapDelta>(&change.change)) {
    out->set_from_version(delta->from_version);
    out->set_to_version(delta->to_version);
    out->set_packed(line_map::PackDelta(*delta));
    return;
  }
  const auto& snapshot = std::get<line_map::MapSnapshot>(change.change);
  out->set_to_version(snapshot.version);
  out->set_snapshot(true);
  out->set_reset(change.reset);
  out->set_packed(line_map::PackSnapshot(snapshot));
}

std::optional<DomainItem> Fail(std::string* error, const std::string& what) {
  if (error != nullptr) *error = what;
  return std::nullopt;
}

// The highest OperatorCorrectionKind (OPERATOR_UNDO).
constexpr std::uint32_t kMaxOperatorKind = 5;

std::optional<DomainItem> GetOperatorCorrection(const link::OperatorCorrection& c,
                                                std::uint64_t base_ms, std::string* error) {
  if (c.correction_id().empty()) return Fail(error, "operator correction: empty correction_id");
  if (c.kind() > kMaxOperatorKind) {
    return Fail(error, "operator correction " + c.correction_id() + ": kind " +
                           std::to_string(c.kind()) + " out of range");
  }
  if (c.pose_heading_cdeg() > 18000 || c.pose_heading_cdeg() < -18000) {
    return Fail(error, "operator correction " + c.correction_id() +
                           ": pose_heading_cdeg out of [-18000, 18000]");
  }
  OperatorCorrection out;
  out.correction_id = c.correction_id();
  out.operator_id = c.operator_id();
  out.kind = c.kind();
  out.entity = c.entity();
  out.mission_stamp_s = static_cast<double>(c.mission_stamp_us()) / 1e6;
  out.origin_x_m = c.origin_x_mm() / 1000.0;
  out.origin_y_m = c.origin_y_mm() / 1000.0;
  out.wrong_x_m = c.wrong_x_mm() / 1000.0;
  out.wrong_y_m = c.wrong_y_mm() / 1000.0;
  out.correct_x_m = c.correct_x_mm() / 1000.0;
  out.correct_y_m = c.correct_y_mm() / 1000.0;
  out.world_from_body = {c.pose_x_mm() / 1000.0, c.pose_y_mm() / 1000.0,
                         geometry::NormalizeAngle(c.pose_heading_cdeg() / 100.0 / kRadToDeg)};
  out.console_seq = c.console_seq();
  out.segment_id = c.segment_id();
  out.segment_x0_m = c.segment_x0_mm() / 1000.0;
  out.segment_y0_m = c.segment_y0_mm() / 1000.0;
  out.segment_x1_m = c.segment_x1_mm() / 1000.0;
  out.segment_y1_m = c.segment_y1_mm() / 1000.0;
  out.applied = c.applied();
  out.refusal = c.refusal();
  out.stamp_s = StampFrom(c.stamp_offset_ms(), base_ms);
  out.undoes_id = c.undoes_id();
  return out;
}

std::optional<DomainItem> GetMap(const link::MapUpdate& m, std::string* error) {
  std::string why;
  MapChange change{m.map_id(), line_map::MapDelta{}, m.reset()};
  if (m.map_id().empty()) return Fail(error, "map update: empty map_id");
  if (m.snapshot()) {
    std::optional<line_map::MapSnapshot> snapshot = line_map::UnpackSnapshot(m.packed(), &why);
    if (!snapshot) return Fail(error, "map update " + m.map_id() + ": snapshot " + why);
    snapshot->version = m.to_version();
    std::int64_t previous = 0;
    for (const auto& segment : snapshot->segments) {
      if (segment.id <= previous) return Fail(error, "map snapshot " + m.map_id() + ": ids not increasing");
      previous = segment.id;
    }
    change.change = std::move(*snapshot);
    return change;
  }
  if (m.reset() || m.to_version() != m.from_version() + 1) {
    return Fail(error, "map update " + m.map_id() + ": delta " + std::to_string(m.from_version()) +
                           " -> " + std::to_string(m.to_version()) + " is not one step");
  }
  std::optional<line_map::MapDelta> delta = line_map::UnpackDelta(m.packed(), &why);
  if (!delta) return Fail(error, "map update " + m.map_id() + ": delta " + why);
  delta->from_version = m.from_version();
  delta->to_version = m.to_version();
  change.change = std::move(*delta);
  return change;
}

}  // namespace

std::uint64_t StampMs(double stamp_s) {
  if (!(stamp_s > 0.0)) return 0;
  return static_cast<std::uint64_t>(std::llround(std::min(stamp_s, 1e15) * 1000.0));
}

void ToProto(const DomainItem& item, std::uint64_t base_stamp_ms, link::Item* out) {
  if (const auto* pose = std::get_if<PoseUpdate>(&item)) {
    PutPose(*pose, base_stamp_ms, out->mutable_pose());
  } else if (const auto* annotation = std::get_if<Annotation>(&item)) {
    PutAnnotation(*annotation, base_stamp_ms, out->mutable_annotation());
  } else if (const auto* correction = std::get_if<Correction>(&item)) {
    PutCorrection(*correction, base_stamp_ms, out->mutable_correction());
  } else if (const auto* op = std::get_if<OperatorCorrection>(&item)) {
    PutOperatorCorrection(*op, base_stamp_ms, out->mutable_operator_correction());
  } else {
    PutMap(std::get<MapChange>(item), out->mutable_map());
  }
}

std::optional<DomainItem> FromProto(const link::Item& item, std::uint64_t base_ms,
                                    std::string* error) {
  switch (item.body_case()) {
    case link::Item::kPose: {
      const link::Pose& p = item.pose();
      if (p.heading_ddeg() >= 3600) return Fail(error, "pose: heading_ddeg >= 3600");
      const double theta = geometry::NormalizeAngle(p.heading_ddeg() / 10.0 / kRadToDeg);
      PoseUpdate pose{p.entity(), {p.x_cm() / 100.0, p.y_cm() / 100.0, theta},
                      StampFrom(p.stamp_offset_ms(), base_ms), p.position_sd_cm() / 100.0,
                      p.heading_sd_ddeg() / 10.0 / kRadToDeg, std::nullopt};
      if (p.has_mission_stamp_ms()) pose.mission_stamp_s = static_cast<double>(p.mission_stamp_ms()) / 1e3;
      return pose;
    }
    case link::Item::kAnnotation: {
      const link::Annotation& a = item.annotation();
      if (a.outline_cm_size() % 2 != 0 || a.outline_cm_size() > 2 * static_cast<int>(kMaxOutlinePoints)) {
        return Fail(error, "annotation: outline_cm holds " + std::to_string(a.outline_cm_size()) +
                               " values (an even count, at most " +
                               std::to_string(2 * kMaxOutlinePoints) + ")");
      }
      Annotation out{a.alarm(), a.entity(), a.id(), a.x_cm() / 100.0, a.y_cm() / 100.0,
                     StampFrom(a.stamp_offset_ms(), base_ms), a.text(), std::nullopt,
                     a.radius_cm() / 100.0, {}};
      if (a.has_mission_stamp_ms()) out.mission_stamp_s = static_cast<double>(a.mission_stamp_ms()) / 1e3;
      for (int i = 0; i + 1 < a.outline_cm_size(); i += 2) {
        out.outline_m.emplace_back(a.outline_cm(i) / 100.0, a.outline_cm(i + 1) / 100.0);
      }
      return out;
    }
    case link::Item::kCorrection: {
      const link::Correction& c = item.correction();
      if (c.heading_cdeg() > 18000 || c.heading_cdeg() < -18000) {
        return Fail(error, "correction: heading_cdeg out of [-18000, 18000]");
      }
      const double theta = geometry::NormalizeAngle(c.heading_cdeg() / 100.0 / kRadToDeg);
      return Correction{c.entity(), {c.x_mm() / 1000.0, c.y_mm() / 1000.0, theta}, c.version(),
                        StampFrom(c.stamp_offset_ms(), base_ms), c.operator_id()};
    }
    case link::Item::kMap:
      return GetMap(item.map(), error);
    case link::Item::kOperatorCorrection:
      return GetOperatorCorrection(item.operator_correction(), base_ms, error);
    default:
      return Fail(error, "item without a domain body");
  }
}

}  // namespace pena::gateway
