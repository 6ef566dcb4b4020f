#include "to_dds.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pena::services {
namespace {

// `value_m` in whole quanta as an IDL long; throws if it is not whole or does not fit.
std::int32_t Quanta32(double value_m, double quantum_m, const char* field) {
  const std::int64_t quanta = line_map::ToQuanta(value_m, quantum_m);
  if (line_map::FromQuanta(quanta, quantum_m) != value_m ||
      quanta < std::numeric_limits<std::int32_t>::min() ||
      quanta > std::numeric_limits<std::int32_t>::max()) {
    throw std::invalid_argument(std::string(field) + " " + std::to_string(value_m) +
                                " m is not a whole number of quanta that fits 32 bits");
  }
  return static_cast<std::int32_t>(quanta);
}

void CheckCount(std::size_t count, std::size_t bound, const char* field) {
  if (count > bound) {
    throw std::length_error(std::string(field) + " holds at most " + std::to_string(bound) +
                            " items, got " + std::to_string(count));
  }
}

std::vector<pena_dds::Segment> ToDdsSegments(const std::vector<line_map::LineSegment>& segments,
                                             std::size_t bound, const char* field) {
  CheckCount(segments.size(), bound, field);
  std::vector<pena_dds::Segment> out;
  out.reserve(segments.size());
  for (const line_map::LineSegment& segment : segments) {
    out.push_back(pena::services::ToDds(segment));
  }
  return out;
}

std::vector<std::int64_t> Removed(const std::vector<std::int64_t>& ids, std::size_t bound,
                                  const char* field) {
  CheckCount(ids.size(), bound, field);
  return ids;
}

std::array<double, 9> RowMajor(const Eigen::Matrix3d& covariance) {
  std::array<double, 9> out{};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out[static_cast<std::size_t>(3 * row + col)] = covariance(row, col);
  }
  return out;
}

// The fields LineMapDelta and GlobalMapDelta share.
template <class Delta>
Delta FillDelta(const line_map::MapDelta& delta, double stamp_s, std::size_t bound) {
  Delta out;
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.stamp_s(stamp_s);
  out.from_version(delta.from_version);
  out.to_version(delta.to_version);
  out.added(ToDdsSegments(delta.added, bound, "delta.added"));
  out.changed(ToDdsSegments(delta.changed, bound, "delta.changed"));
  out.removed(Removed(delta.removed, bound, "delta.removed"));
  return out;
}

template <class Snapshot>
Snapshot FillSnapshot(const line_map::MapSnapshot& snapshot, double stamp_s, std::size_t bound) {
  Snapshot out;
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.stamp_s(stamp_s);
  out.version(snapshot.version);
  out.next_id(snapshot.next_id);
  out.segments(ToDdsSegments(snapshot.segments, bound, "snapshot.segments"));
  return out;
}

}  // namespace

pena_dds::Pose2 ToDds(const geometry::Pose2& pose) {
  pena_dds::Pose2 out;
  out.x_m(pose.x_m);
  out.y_m(pose.y_m);
  out.theta_rad(pose.theta_rad);
  return out;
}

pena_dds::EntityKind ToDds(sensors::EntityKind kind) {
  return kind == sensors::EntityKind::kHuman ? pena_dds::ENTITY_HUMAN : pena_dds::ENTITY_ROBOT;
}

pena_dds::PoseStatus ToDds(odometry::MatchStatus status) {
  switch (status) {
    case odometry::MatchStatus::kFirst: return pena_dds::POSE_FIRST;
    case odometry::MatchStatus::kMatched: return pena_dds::POSE_MATCHED;
    case odometry::MatchStatus::kDegenerate: return pena_dds::POSE_DEGENERATE;
    case odometry::MatchStatus::kFailed: return pena_dds::POSE_FAILED;
    case odometry::MatchStatus::kNoPoints: return pena_dds::POSE_NO_POINTS;
    case odometry::MatchStatus::kPriorOnly: return pena_dds::POSE_PRIOR_ONLY;
  }
  return pena_dds::POSE_FAILED;
}

pena_dds::Segment ToDds(const line_map::LineSegment& segment) {
  using line_map::kCoordinateQuantumM;
  pena_dds::Segment out;
  out.id(segment.id);
  out.start_x_mm(Quanta32(segment.segment.start_m.x(), kCoordinateQuantumM, "segment.start_x"));
  out.start_y_mm(Quanta32(segment.segment.start_m.y(), kCoordinateQuantumM, "segment.start_y"));
  out.end_x_mm(Quanta32(segment.segment.end_m.x(), kCoordinateQuantumM, "segment.end_x"));
  out.end_y_mm(Quanta32(segment.segment.end_m.y(), kCoordinateQuantumM, "segment.end_y"));
  out.support_cells(static_cast<std::uint64_t>(std::llround(segment.support_cells)));
  out.observations(static_cast<std::uint64_t>(std::llround(segment.observations)));
  out.rms_error_100um(static_cast<std::uint32_t>(
      Quanta32(segment.rms_error_m, line_map::kRmsQuantumM, "segment.rms_error")));
  CheckCount(segment.provenance.size(), pena_dds::PROVENANCE_MAX, "segment.provenance");
  out.provenance().resize(segment.provenance.size());
  for (std::size_t i = 0; i < segment.provenance.size(); ++i) {
    SetBounded(out.provenance()[i], segment.provenance[i], "segment.provenance entry");
  }
  if (segment.seen_by_entities > std::numeric_limits<std::uint16_t>::max()) {
    throw std::invalid_argument("segment.seen_by_entities must be <= 65535, got " +
                                std::to_string(segment.seen_by_entities));
  }
  out.seen_by_entities(static_cast<std::uint16_t>(segment.seen_by_entities));
  const std::int32_t sd_cm = Quanta32(segment.error_sd_m, line_map::kErrorSdQuantumM,
                                      "segment.error_sd");
  if (sd_cm < 0 || sd_cm > std::numeric_limits<std::uint16_t>::max()) {
    throw std::invalid_argument("segment.error_sd_m must be in [0, 655.35] m, got " +
                                std::to_string(segment.error_sd_m));
  }
  out.error_sd_cm(static_cast<std::uint16_t>(sd_cm));
  return out;
}

pena_dds::LineMapDelta ToDdsLineMapDelta(const line_map::MapDelta& delta,
                                         const std::string& entity_id, double stamp_s) {
  auto out = FillDelta<pena_dds::LineMapDelta>(delta, stamp_s, pena_dds::DELTA_MAX_SEGMENTS);
  SetBounded(out.entity_id(), entity_id, "entity_id");
  return out;
}

pena_dds::LineMapSnapshot ToDdsLineMapSnapshot(const line_map::MapSnapshot& snapshot,
                                               const std::string& entity_id, double stamp_s) {
  auto out = FillSnapshot<pena_dds::LineMapSnapshot>(snapshot, stamp_s,
                                                     pena_dds::SNAPSHOT_MAX_SEGMENTS);
  SetBounded(out.entity_id(), entity_id, "entity_id");
  return out;
}

pena_dds::GlobalMapDelta ToDdsGlobalMapDelta(const line_map::MapDelta& delta,
                                             const std::string& map_id, double stamp_s) {
  auto out =
      FillDelta<pena_dds::GlobalMapDelta>(delta, stamp_s, pena_dds::GLOBAL_DELTA_MAX_SEGMENTS);
  SetBounded(out.map_id(), map_id, "map_id");
  return out;
}

pena_dds::GlobalMapSnapshot ToDdsGlobalMapSnapshot(const line_map::MapSnapshot& snapshot,
                                                   const std::string& map_id, double stamp_s) {
  auto out = FillSnapshot<pena_dds::GlobalMapSnapshot>(snapshot, stamp_s,
                                                       pena_dds::GLOBAL_SNAPSHOT_MAX_SEGMENTS);
  SetBounded(out.map_id(), map_id, "map_id");
  return out;
}

pena_dds::EntityPose ToDdsPose(const pipeline::ScanStep& step, const std::string& entity_id,
                               std::uint64_t seq, std::uint64_t local_map_version,
                               std::uint64_t correction_seq) {
  pena_dds::EntityPose out;
  SetBounded(out.entity_id(), entity_id, "entity_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.stamp_s(step.odometry.stamp_s);
  out.world_from_body(ToDds(step.world_from_body));
  out.odom_from_body(ToDds(step.odometry.world_from_body));
  out.covariance(RowMajor(step.covariance));
  out.status(ToDds(step.odometry.status));
  out.match_score(static_cast<float>(step.odometry.score));
  out.reference_changed(step.odometry.reference_changed);
  out.local_map_version(local_map_version);
  out.correction_seq(correction_seq);
  return out;
}

pena_dds::ReferenceScan ToDdsReferenceScan(const sensors::LaserScan& scan,
                                           const pipeline::ScanStep& step,
                                           const std::string& entity_id, std::uint64_t seq,
                                           std::uint64_t local_map_version,
                                           double range_quantum_m) {
  if (!(range_quantum_m > 0.0)) {
    throw std::invalid_argument("range_quantum_m must be > 0 m, got " +
                                std::to_string(range_quantum_m));
  }
  CheckCount(scan.ranges_m.size(), pena_dds::SCAN_MAX_BEAMS, "reference_scan.ranges");
  pena_dds::ReferenceScan out;
  SetBounded(out.entity_id(), entity_id, "entity_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.stamp_s(scan.stamp_s);
  out.odom_from_body(ToDds(step.odometry.world_from_body));
  out.world_from_body(ToDds(step.world_from_body));
  out.covariance(RowMajor(step.covariance));
  out.local_map_version(local_map_version);
  out.angle_min_rad(static_cast<float>(scan.geometry.angle_min_rad));
  out.angle_increment_rad(static_cast<float>(scan.geometry.angle_increment_rad));
  out.max_range_m(static_cast<float>(scan.geometry.max_range_m));
  out.range_quantum_m(static_cast<float>(range_quantum_m));
  out.ranges().reserve(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double quanta = scan.IsReturn(i) ? std::round(scan.ranges_m[i] / range_quantum_m) : 0.0;
    out.ranges().push_back(quanta >= 1.0 && quanta <= 65535.0 ? static_cast<std::uint16_t>(quanta)
                                                              : std::uint16_t{0});
  }
  return out;
}

pena_dds::Correction ToDdsCorrection(const pipeline::Correction& correction,
                                     const std::string& entity_id, std::uint64_t seq,
                                     std::uint64_t for_version, std::uint64_t reference_seq) {
  pena_dds::Correction out;
  SetBounded(out.entity_id(), entity_id, "entity_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.kind(correction.kind == pipeline::Correction::Kind::kMapFromOdom
               ? pena_dds::CORRECTION_MAP_FROM_ODOM
               : pena_dds::CORRECTION_POSE);
  out.map_from_odom(ToDds(correction.map_from_odom));
  out.stamp_s(correction.stamp_s);
  out.world_from_body(ToDds(correction.world_from_body));
  out.confidence(static_cast<float>(correction.confidence));
  out.for_version(for_version);
  out.reference_seq(reference_seq);
  return out;
}

}  // namespace pena::services
