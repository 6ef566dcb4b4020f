#include "from_dds.hpp"

#include <stdexcept>

namespace pena::services {
namespace {

std::vector<line_map::LineSegment> FromDdsSegments(const std::vector<pena_dds::Segment>& segments) {
  std::vector<line_map::LineSegment> out;
  out.reserve(segments.size());
  for (const pena_dds::Segment& segment : segments) {
    out.push_back(pena::services::FromDds(segment));
  }
  return out;
}

template <class Delta>
line_map::MapDelta DeltaFrom(const Delta& delta, const char* type_name) {
  CheckSchemaVersion(delta.schema_version(), type_name);
  line_map::MapDelta out;
  out.from_version = delta.from_version();
  out.to_version = delta.to_version();
  out.added = FromDdsSegments(delta.added());
  out.changed = FromDdsSegments(delta.changed());
  out.removed.assign(delta.removed().begin(), delta.removed().end());
  return out;
}

template <class Snapshot>
line_map::MapSnapshot SnapshotFrom(const Snapshot& snapshot, const char* type_name) {
  CheckSchemaVersion(snapshot.schema_version(), type_name);
  line_map::MapSnapshot out;
  out.version = snapshot.version();
  out.next_id = snapshot.next_id();
  out.segments = FromDdsSegments(snapshot.segments());
  return out;
}

}  // namespace

void CheckSchemaVersion(std::uint32_t version, const char* type_name) {
  if (version != pena_dds::SCHEMA_VERSION) {
    throw std::invalid_argument(std::string(type_name) + " has schema_version " +
                                std::to_string(version) + ", this build reads " +
                                std::to_string(pena_dds::SCHEMA_VERSION));
  }
}

geometry::Pose2 FromDds(const pena_dds::Pose2& pose) {
  return {pose.x_m(), pose.y_m(), pose.theta_rad()};
}

line_map::LineSegment FromDds(const pena_dds::Segment& segment) {
  using line_map::FromQuanta;
  using line_map::kCoordinateQuantumM;
  line_map::LineSegment out;
  out.id = segment.id();
  out.segment.start_m = {FromQuanta(segment.start_x_mm(), kCoordinateQuantumM),
                         FromQuanta(segment.start_y_mm(), kCoordinateQuantumM)};
  out.segment.end_m = {FromQuanta(segment.end_x_mm(), kCoordinateQuantumM),
                       FromQuanta(segment.end_y_mm(), kCoordinateQuantumM)};
  out.support_cells = static_cast<double>(segment.support_cells());
  out.observations = static_cast<double>(segment.observations());
  out.rms_error_m = FromQuanta(segment.rms_error_100um(), line_map::kRmsQuantumM);
  out.provenance.reserve(segment.provenance().size());
  for (const auto& entry : segment.provenance()) out.provenance.push_back(entry.to_string());
  out.seen_by_entities = segment.seen_by_entities();
  out.error_sd_m = FromQuanta(segment.error_sd_cm(), line_map::kErrorSdQuantumM);
  return out;
}

line_map::MapDelta FromDds(const pena_dds::LineMapDelta& delta) {
  return DeltaFrom(delta, "LineMapDelta");
}

line_map::MapSnapshot FromDds(const pena_dds::LineMapSnapshot& snapshot) {
  return SnapshotFrom(snapshot, "LineMapSnapshot");
}

line_map::MapDelta FromDds(const pena_dds::GlobalMapDelta& delta) {
  return DeltaFrom(delta, "GlobalMapDelta");
}

line_map::MapSnapshot FromDds(const pena_dds::GlobalMapSnapshot& snapshot) {
  return SnapshotFrom(snapshot, "GlobalMapSnapshot");
}

pipeline::Correction FromDds(const pena_dds::Correction& correction) {
  CheckSchemaVersion(correction.schema_version(), "Correction");
  pipeline::Correction out;
  out.kind = correction.kind() == pena_dds::CORRECTION_MAP_FROM_ODOM
                 ? pipeline::Correction::Kind::kMapFromOdom
                 : pipeline::Correction::Kind::kPose;
  out.map_from_odom = FromDds(correction.map_from_odom());
  out.stamp_s = correction.stamp_s();
  out.world_from_body = FromDds(correction.world_from_body());
  out.confidence = correction.confidence();
  return out;
}

sensors::LaserScan FromDds(const pena_dds::ReferenceScan& scan) {
  CheckSchemaVersion(scan.schema_version(), "ReferenceScan");
  sensors::LaserScan out;
  out.stamp_s = scan.stamp_s();
  out.geometry = {scan.angle_min_rad(), scan.angle_increment_rad(), scan.max_range_m()};
  out.ranges_m.reserve(scan.ranges().size());
  for (const std::uint16_t quanta : scan.ranges()) {
    out.ranges_m.push_back(quanta == 0 ? sensors::LaserScan::kNoReturn
                                       : static_cast<float>(quanta) * scan.range_quantum_m());
  }
  return out;
}

}  // namespace pena::services
