#include "fusion_fields.hpp"

#include <limits>

// Field layouts of the fusion codec (docs/formats.md): fixed-width little-endian numbers, doubles
// by their bits, lists as a u64 count and items.

namespace pena::fusion::detail {
namespace {

constexpr std::size_t kMinSegmentBytes = 8 + 7 * 8 + 8;

}  // namespace

void Put(ByteWriter& w, const geometry::Pose2& pose) {
  w.F64(pose.x_m);
  w.F64(pose.y_m);
  w.F64(pose.theta_rad);
}
geometry::Pose2 GetPose(ByteReader& r) {
  geometry::Pose2 pose;
  pose.x_m = r.F64();
  pose.y_m = r.F64();
  pose.theta_rad = r.F64();
  return pose;
}
void Put(ByteWriter& w, const std::optional<geometry::Pose2>& pose) {
  w.U8(pose ? 1 : 0);
  if (pose) Put(w, *pose);
}
std::optional<geometry::Pose2> GetOptionalPose(ByteReader& r) {
  const std::uint8_t flag = r.U8();
  if (flag > 1) r.Fail("optional flag " + std::to_string(flag));
  if (flag == 0) return std::nullopt;
  return GetPose(r);
}

void Put(ByteWriter& w, const line_map::LineSegment& s) {
  w.I64(s.id);
  for (const double v : {s.segment.start_m.x(), s.segment.start_m.y(), s.segment.end_m.x(),
                         s.segment.end_m.y(), s.support_cells, s.observations, s.rms_error_m}) {
    w.F64(v);
  }
  w.U64(s.provenance.size());
  for (const std::string& entry : s.provenance) w.Text(entry);
  // A global wall's support (version 4): one byte when there is none (an entity's walls).
  const bool supported = s.seen_by_entities != 0 || s.error_sd_m != 0.0;
  w.U8(supported ? 1 : 0);
  if (supported) {
    w.U64(s.seen_by_entities);
    w.F64(s.error_sd_m);
  }
}
line_map::LineSegment GetSegment(ByteReader& r) {
  line_map::LineSegment s;
  s.id = r.I64();
  s.segment.start_m.x() = r.F64();
  s.segment.start_m.y() = r.F64();
  s.segment.end_m.x() = r.F64();
  s.segment.end_m.y() = r.F64();
  s.support_cells = r.F64();
  s.observations = r.F64();
  s.rms_error_m = r.F64();
  s.provenance.resize(r.Count(8));
  for (std::string& entry : s.provenance) entry = r.Text();
  if (r.version() >= 4) {  // before it, no wall carried its support
    const std::uint8_t supported = r.U8();
    if (supported > 1) r.Fail("support flag " + std::to_string(supported));
    if (supported == 1) {
      const std::uint64_t seen_by = r.U64();
      if (seen_by > std::numeric_limits<std::uint32_t>::max()) r.Fail("seen_by_entities " + std::to_string(seen_by));
      s.seen_by_entities = static_cast<std::uint32_t>(seen_by);
      s.error_sd_m = r.F64();
    }
  }
  return s;
}
void Put(ByteWriter& w, const std::vector<line_map::LineSegment>& list) {
  w.U64(list.size());
  for (const line_map::LineSegment& s : list) Put(w, s);
}
std::vector<line_map::LineSegment> GetSegments(ByteReader& r) {
  std::vector<line_map::LineSegment> list(r.Count(kMinSegmentBytes));
  for (line_map::LineSegment& s : list) s = GetSegment(r);
  return list;
}

void Put(ByteWriter& w, const line_map::MapDelta& d) {
  w.U64(d.from_version);
  w.U64(d.to_version);
  Put(w, d.added);
  Put(w, d.changed);
  w.U64(d.removed.size());
  for (const std::int64_t id : d.removed) w.I64(id);
}
line_map::MapDelta GetDelta(ByteReader& r) {
  line_map::MapDelta d;
  d.from_version = r.U64();
  d.to_version = r.U64();
  d.added = GetSegments(r);
  d.changed = GetSegments(r);
  d.removed.resize(r.Count(8));
  for (std::int64_t& id : d.removed) id = r.I64();
  return d;
}

void Put(ByteWriter& w, const line_map::MapSnapshot& s) {
  w.U64(s.version);
  w.I64(s.next_id);
  Put(w, s.segments);
}
line_map::MapSnapshot GetSnapshot(ByteReader& r) {
  line_map::MapSnapshot s;
  s.version = r.U64();
  s.next_id = r.I64();
  s.segments = GetSegments(r);
  return s;
}

void Put(ByteWriter& w, const Annotation& a) {
  w.I64(a.id);
  w.U8(static_cast<std::uint8_t>(a.kind));
  w.F64(a.position_m.x());
  w.F64(a.position_m.y());
  w.F64(a.radius_m);
  w.Text(a.text);
  w.Text(a.author);
  w.F64(a.stamp_s);
  w.U64(a.outline_m.size());
  for (const Eigen::Vector2d& corner : a.outline_m) {
    w.F64(corner.x());
    w.F64(corner.y());
  }
}
Annotation GetAnnotation(ByteReader& r) {
  Annotation a;
  a.id = r.I64();
  const std::uint8_t kind = r.U8();
  if (kind > static_cast<std::uint8_t>(AnnotationKind::kNote)) {
    r.Fail("unknown annotation kind " + std::to_string(kind));
  }
  a.kind = static_cast<AnnotationKind>(kind);
  a.position_m.x() = r.F64();
  a.position_m.y() = r.F64();
  a.radius_m = r.F64();
  a.text = r.Text();
  a.author = r.Text();
  a.stamp_s = r.F64();
  if (r.version() >= 2) {  // version 1 kept no outline
    a.outline_m.resize(r.Count(2 * 8));
    for (Eigen::Vector2d& corner : a.outline_m) {
      corner.x() = r.F64();
      corner.y() = r.F64();
    }
  }
  return a;
}

}  // namespace pena::fusion::detail
