#pragma once
// What the fusion service is told: every input is one of these plain structs, stamped
// with the fusion's own receive time so that replaying the journal reproduces the state exactly.
// Frames: an entity's local map is in its own frame ("entity"); the global map and annotations
// are in the map frame; map_from_entity maps the former into the latter.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/line_segment.hpp"
#include "pena/line_map/map_delta.hpp"

namespace pena::fusion {

// The a priori plan (map frame, metres); replaces any earlier plan.
struct SetPlan {
  double stamp_s = 0.0;
  std::vector<line_map::LineSegment> segments;  // ids > 0 become provenance "plan:<id>"
};

// An entity announces itself. A known start gives its alignment; without one the fusion places
// it by matching its local map to the global map (see placement.hpp).
struct EntityJoin {
  double stamp_s = 0.0;
  std::string entity_id;
  std::optional<geometry::Pose2> map_from_entity;
};

// An entity says goodbye; its walls stay in the global map.
struct EntityLeave {
  double stamp_s = 0.0;
  std::string entity_id;
};

// Liveliness without data (a heartbeat or a pose).
struct EntityHeartbeat {
  double stamp_s = 0.0;
  std::string entity_id;
};

// One versioned change of an entity's local line map (entity frame).
struct LocalDelta {
  double stamp_s = 0.0;
  std::string entity_id;
  line_map::MapDelta delta;
};

// An entity's whole local map (after a gap, or at join).
struct LocalSnapshot {
  double stamp_s = 0.0;
  std::string entity_id;
  line_map::MapSnapshot snapshot;
};

// A new alignment of an entity (from virtual-scan matching, see correction.hpp): its local map
// moves to map_from_entity.
struct AlignmentCorrection {
  double stamp_s = 0.0;
  std::string entity_id;
  geometry::Pose2 map_from_entity;
  double confidence = 1.0;  // in [0, 1]
};

// An operator's correction of an entity (paper section 4.1): its contributions are moved by the
// rigid transform corrected_from_wrong (map frame), i.e. map_from_entity <- T * map_from_entity.
struct OperatorCorrection {
  double stamp_s = 0.0;
  std::string entity_id;
  geometry::Pose2 corrected_from_wrong;
  std::string author;
};

// An operator's correction of an entity with a known start (paper section 4.1: its data "from
// the origin onwards" moves): only the listed segments of its local map, the walls it mapped in
// the wrong frame from the correction's origin time until it applied the correction, move by
// corrected_from_wrong (map frame) in the global map; its earlier walls stay, its later ones
// arrive corrected. A segment moved twice composes both; one the entity removes forgets it.
struct MoveEntityWalls {
  double stamp_s = 0.0;
  std::string entity_id;
  geometry::Pose2 corrected_from_wrong;
  std::vector<std::int64_t> segment_ids;  // ids in the entity's local map
  std::string author;
};

// What an operator annotation marks (the paper's "dangerous area", "victim found", landmarks).
enum class AnnotationKind : std::uint8_t {
  kDangerousArea = 0,
  kVictimFound = 1,
  kCorridorCrossing = 2,
  kElevator = 3,
  kLandmark = 4,  // any other landmark, described by text
  kNote = 5,      // free text
};

// An operator annotation in the map frame.
struct Annotation {
  std::int64_t id = 0;  // assigned by the fusion (> 0); 0 in an AddAnnotation asks for a new one
  AnnotationKind kind = AnnotationKind::kNote;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;  // extent of an area, metres; 0 for a point
  std::vector<Eigen::Vector2d> outline_m;  // corners of an area's polygon, map frame; may be empty
  std::string text;
  std::string author;
  double stamp_s = 0.0;  // when the operator made it
};

// Adds an annotation (id 0) or replaces the one with that id.
struct PutAnnotation {
  double stamp_s = 0.0;
  Annotation annotation;
};

// Deletes an annotation.
struct RemoveAnnotation {
  double stamp_s = 0.0;
  std::int64_t annotation_id = 0;
  std::string author;
};

// Time passes: entities without data for FusionOptions::silent_after_s are marked lost.
struct Tick {
  double stamp_s = 0.0;
};

// Time to publish: with FusionOptions::rebuild_on_publish, the global map is rebuilt here (once for
// all changes since the last one) instead of after every change.
struct Publish {
  double stamp_s = 0.0;
};

// Any input; the journal stores them in this order.
using FusionInput = std::variant<SetPlan, EntityJoin, EntityLeave, EntityHeartbeat, LocalDelta,
                                 LocalSnapshot, AlignmentCorrection, OperatorCorrection,
                                 PutAnnotation, RemoveAnnotation, Tick, Publish, MoveEntityWalls>;

// The receive stamp of any input, seconds.
double StampOf(const FusionInput& input);

// "dangerous_area", "victim_found", "corridor_crossing", "elevator", "landmark", "note".
const char* ToString(AnnotationKind kind);

}  // namespace pena::fusion
