#pragma once
// The central fusion as a pure state machine: inputs (fusion_input.hpp) in, outputs
// (global-map deltas, snapshot requests, lifecycle and annotation changes, placement) out. It
// keeps each entity's local map, aligns it by map_from_entity and merges all of them with the a
// priori plan into one GlobalMap. Same inputs in the same order give bit-identical state, which
// is what the journal's crash recovery relies on (fusion_store.hpp). Not thread-safe.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pena/fusion/fusion_input.hpp"
#include "pena/fusion/global_map.hpp"
#include "pena/fusion/placement.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::fusion {

// Options of the fusion; validated by FusionState's constructor.
struct FusionOptions {
  GlobalMapOptions global;         // merging, and which lone walls are published
  double silent_after_s = 5.0;     // no data (or heartbeat) for this long: marked lost. Seconds, > 0
  PlacementOptions placement;
  double placement_every_m = 2.0;  // local wall growth between placement attempts. Metres, >= 0
  // false: every change rebuilds the global map at once (one global delta per change). true: a
  // change only marks it stale and the next Publish input rebuilds it once (many entities).
  bool rebuild_on_publish = false;
};

// Throws std::invalid_argument naming the field and its unit.
void ValidateFusionOptions(const FusionOptions& options);

// Where an entity is in its life.
enum class EntityLifecycle : std::uint8_t {
  kJoined = 0,  // announced, no data yet
  kActive = 1,  // data within silent_after_s
  kLost = 2,    // silent: no data for silent_after_s; its walls stay
  kLeft = 3,    // said goodbye; its walls stay
};

// "joined", "active", "lost", "left".
const char* ToString(EntityLifecycle lifecycle);

// What the fusion knows of one entity (besides its local map).
struct EntityStatus {
  std::string entity_id;
  EntityLifecycle lifecycle = EntityLifecycle::kJoined;
  std::optional<geometry::Pose2> map_from_entity;  // nullopt: not placed yet
  double last_data_s = 0.0;         // receive stamp of its last data or heartbeat
  bool awaiting_snapshot = false;   // a delta did not follow its local map: snapshot asked
  PlacementResult placement;        // last placement attempt (unplaced entities)
  double placement_length_m = 0.0;  // local wall length at that attempt
  // Operator moves of single local segments (MoveEntityWalls), by segment id: the segment is at
  // moved_walls[id] * map_from_entity * local in the global map.
  std::map<std::int64_t, geometry::Pose2> moved_walls;
};

// A lifecycle transition.
struct LifecycleChange {
  std::string entity_id;
  EntityLifecycle from = EntityLifecycle::kJoined;
  EntityLifecycle to = EntityLifecycle::kJoined;
  bool appeared = false;  // the entity was not known before (from == to == kJoined)
};

// A versioned change of the annotation set.
struct AnnotationChange {
  std::uint64_t version = 0;  // annotation-set version after the change
  Annotation annotation;      // full value (for a removal: the removed one)
  bool removed = false;
};

// What one input caused. `problem` non-empty: the input was refused and changed nothing.
struct FusionOutput {
  std::string problem;
  std::optional<line_map::MapDelta> global_delta;  // set when the global map changed
  std::optional<std::string> snapshot_request;     // entity whose local map needs a snapshot
  std::vector<LifecycleChange> lifecycle;
  std::optional<AnnotationChange> annotation;
  std::optional<PlacementResult> placement;  // set when a placement attempt ran
  bool changed = false;                      // the state changed (anything above, or a local map)
};

// Everything FusionState holds, as plain data (the periodic snapshot of the journal).
struct FusionCheckpoint {
  std::vector<line_map::LineSegment> plan;
  line_map::MapSnapshot global;
  struct Entity {
    EntityStatus status;
    line_map::MapSnapshot local;
  };
  std::vector<Entity> entities;  // sorted by id
  std::vector<Annotation> annotations;  // sorted by id
  std::uint64_t annotation_version = 0;
  std::int64_t next_annotation_id = 1;
  bool rebuild_pending = false;  // changes not yet in the global map (rebuild_on_publish)
};

// The fusion.
class FusionState {
 public:
  explicit FusionState(FusionOptions options = {});
  // Resumes from a checkpoint; throws std::invalid_argument for an inconsistent one.
  static FusionState FromCheckpoint(const FusionCheckpoint& checkpoint, FusionOptions options = {});

  // Applies one input (see fusion_input.hpp for each kind's meaning).
  FusionOutput Handle(const FusionInput& input);

  // The global map as a late joiner gets it: apply later global deltas on top.
  line_map::MapSnapshot GlobalSnapshot() const { return global_.Snapshot(); }
  std::uint64_t global_version() const { return global_.version(); }
  // Who saw each global wall and its estimated error, by id (GlobalMap::support()).
  const std::map<std::int64_t, WallSupport>& GlobalSupport() const { return global_.support(); }
  // Status of one entity, nullptr if unknown.
  const EntityStatus* entity(const std::string& entity_id) const;
  // Ids of all known entities, sorted.
  std::vector<std::string> entity_ids() const;
  // An entity's local map (entity frame); throws std::out_of_range if unknown.
  const line_map::LineMap& local_map(const std::string& entity_id) const;
  // Annotations sorted by id, and the version of that set.
  std::vector<Annotation> annotations() const;
  std::uint64_t annotation_version() const { return annotation_version_; }
  // The global walls a correction of `entity_id` may use: those supported by some other source
  // (plan or entity), so an entity is not corrected against its own drift. Map frame.
  std::vector<geometry::Segment2> CorrectionMap(const std::string& entity_id) const;
  // The whole state as plain data.
  FusionCheckpoint Checkpoint() const;
  const FusionOptions& options() const { return options_; }

 private:
  struct Entity {
    EntityStatus status;
    line_map::LineMap local;
  };
  FusionOutput OnPlan(const SetPlan& input);
  FusionOutput OnJoin(const EntityJoin& input);
  FusionOutput OnLeave(const EntityLeave& input);
  FusionOutput OnHeartbeat(const EntityHeartbeat& input);
  FusionOutput OnDelta(const LocalDelta& input);
  FusionOutput OnSnapshot(const LocalSnapshot& input);
  FusionOutput OnAlignment(const AlignmentCorrection& input);
  FusionOutput OnOperator(const OperatorCorrection& input);
  FusionOutput OnMoveWalls(const MoveEntityWalls& input);
  FusionOutput OnPut(const PutAnnotation& input);
  FusionOutput OnRemove(const RemoveAnnotation& input);
  FusionOutput OnTick(const Tick& input);
  FusionOutput OnPublish(const Publish& input);
  // A new entity (unplaced, joined, no data yet).
  Entity& Create(const std::string& entity_id, double stamp_s, FusionOutput& output);
  // The entity, created if unknown, marked active with data at stamp_s.
  Entity& Touch(const std::string& entity_id, double stamp_s, FusionOutput& output);
  // After a local map or alignment change: placement for unplaced entities, then the rebuild.
  void AfterLocalChange(Entity& entity, FusionOutput& output);
  // The global map must follow a change: rebuilt now, or at the next Publish.
  void Changed(FusionOutput& output);
  // Rebuilds the global map from the plan and every placed entity; sets output.global_delta.
  void Rebuild(FusionOutput& output);

  FusionOptions options_;
  std::vector<line_map::LineSegment> plan_;
  GlobalMap global_;
  std::map<std::string, Entity> entities_;
  std::map<std::int64_t, Annotation> annotations_;
  std::uint64_t annotation_version_ = 0;
  std::int64_t next_annotation_id_ = 1;
  bool rebuild_pending_ = false;
};

}  // namespace pena::fusion
