#pragma once
// pena-console's picture of the mission: every entity's latest pose, covariance, status and trail,
// the global map (observed and plan-only pieces told apart), annotations and operator
// corrections. Owned by the console's one worker; no DDS, no threads. A browser gets Snapshot()
// when it connects, then the TakeDelta() of every tick: only what changed since the last one.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/trajectory.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/localisation/operator_corrections.hpp"

namespace pena::services {

// What the picture keeps (ConsoleOptions::picture).
struct PictureOptions {
  double stale_after_s = 3.0;       // wall seconds without a pose before an entity is "stale"
  std::size_t trail_points = 4000;  // per entity; the oldest go first
  double trail_step_m = 0.05;       // a pose closer than this to the last trail point is skipped
};

// One entity's latest pose as the picture takes it (from pena_dds::EntityPose).
struct PoseUpdate {
  std::string entity_id;
  std::uint64_t seq = 0;
  double stamp_s = 0.0;                  // mission time
  geometry::Pose2 world_from_body;
  geometry::Pose2 odom_from_body;        // the entity's own odometry frame (before corrections)
  double covariance[9] = {};             // of world_from_body, row-major (x, y, theta)
  std::string status;                    // "first", "matched", "degenerate", "failed", ...
  std::int64_t heard_ns = 0;             // this machine's clock at reception
  std::int64_t source_ns = 0;            // the writer's clock when it was written (0: unknown)
};

// One entity's heartbeat (from pena_dds::EntityStatus).
struct StatusUpdate {
  std::string entity_id;
  std::string kind;   // "human", "robot"
  std::string state;  // "starting", "running", "finished", "failed"
  std::string message;
  std::uint64_t corrections_applied = 0;
  std::int64_t heard_ns = 0;
};

// An operator's correction as the picture lists it (from pena_dds::OperatorCorrection).
struct CorrectionRecord {
  std::string correction_id;
  std::string operator_id;
  std::string kind;  // "rotate", "translate", "undo", "set_pose", ...
  std::string entity_id;
  std::string undoes;  // kind "undo": the correction it takes back
  double stamp_s = 0.0;  // mission time from which it applies
  std::optional<localisation::OperatorCorrection> geometry;  // rotate and translate
  bool applied = false;  // pena-fusion's answer: journalled, applied, sent to the entity
  std::string refusal;   // pena-fusion's answer: why it was not applied
  bool undone = false;   // an undo took it back
};

// A pena-gateway endpoint's report on the radio link (from pena_dds::LinkHealth).
struct LinkRecord {
  std::string gateway_id;
  bool peer_alive = false;
  double peer_heard_age_s = -1.0;  // < 0: never heard
  double budget_bit_s = 0.0, sent_bit_s = 0.0, received_frames_s = 0.0;
  std::uint32_t pending_reliable = 0, pending_map_updates = 0;
  std::uint64_t frames_rejected = 0, resyncs = 0;
  std::int64_t heard_ns = 0;  // this machine's clock when the report came
};

// A mark on the map (from pena_dds::Annotation).
struct AnnotationRecord {
  std::string annotation_id;
  std::string author_id;
  std::string kind;  // "victim_found", "dangerous_area", ...
  double stamp_s = 0.0;
  double x_m = 0.0, y_m = 0.0, radius_m = 0.0;
  std::vector<std::pair<double, double>> outline;
  std::string text;
  bool retracted = false;
};

class ConsolePicture {
 public:
  explicit ConsolePicture(PictureOptions options = {});

  void OnPose(const PoseUpdate& pose);
  void OnStatus(const StatusUpdate& status);
  // A global-map delta: applied if it follows the map's version, kept if it is early.
  void OnMapDelta(line_map::MapDelta delta);
  // A global-map snapshot newer than the map replaces it.
  void OnMapSnapshot(const line_map::MapSnapshot& snapshot);
  void OnAnnotation(const AnnotationRecord& annotation);
  // Listed; a rotation or translation also moves the entity's trail from its stamp on (the
  // picture shows the trajectory as corrected, section 4.1).
  // pena-fusion's answer to a listed correction updates it; a refused one's move is taken back.
  void OnCorrection(const CorrectionRecord& correction);
  void OnLinkHealth(const LinkRecord& link);

  // Everything, for a browser that just connected.
  nlohmann::json Snapshot(std::int64_t now_ns) const;
  // What changed since the last TakeDelta (states that time alone changed, e.g. "stale",
  // included); nullopt if nothing did.
  std::optional<nlohmann::json> TakeDelta(std::int64_t now_ns);

  // The entity's trail pose nearest to `point_m` (map frame): its stamp and distance; nullopt
  // for an unknown entity or an empty trail.
  struct Nearest {
    double stamp_s = 0.0;
    double distance_m = 0.0;
  };
  std::optional<Nearest> NearestTrailPose(const std::string& entity_id,
                                          const Eigen::Vector2d& point_m) const;
  bool HasEntity(const std::string& entity_id) const { return entities_.count(entity_id) > 0; }
  // The correction with that id, or nullptr.
  const CorrectionRecord* FindCorrection(const std::string& correction_id) const;
  // The last rotation or translation of the entity still in force (not undone, not refused),
  // or nullptr: what an undo may take back.
  const CorrectionRecord* LastInForce(const std::string& entity_id) const;
  // The annotation with that id, or nullptr.
  const AnnotationRecord* FindAnnotation(const std::string& annotation_id) const;
  // The latest mission time any entity's pose carried (0 before the first pose).
  double latest_stamp_s() const { return latest_stamp_s_; }
  std::uint64_t map_version() const { return map_.version(); }
  std::size_t entity_count() const { return entities_.size(); }

 private:
  struct Entity {
    std::optional<PoseUpdate> pose;
    std::optional<StatusUpdate> status;
    geometry::Trajectory trail;
    std::size_t trail_sent = 0;  // trail points already in a delta
    bool trail_replaced = false;  // a correction moved sent points: send the whole trail
    bool dirty = true;
    std::string shown_state;     // the state in the last delta
  };
  std::string StateOf(const Entity& entity, std::int64_t now_ns) const;
  nlohmann::json EntityJson(const std::string& id, const Entity& entity, std::int64_t now_ns,
                            bool whole_trail) const;
  void ApplyEarly();
  // Moves the entity's trail from the correction's stamp on (inverse: takes the move back).
  void MoveTrail(const CorrectionRecord& correction, bool inverse);
  // Marks a listed correction undone (or in force again when its undo was refused).
  void MarkUndone(const std::string& correction_id, bool undone);

  PictureOptions options_;
  double latest_stamp_s_ = 0.0;
  std::map<std::string, Entity> entities_;
  line_map::LineMap map_;
  std::map<std::uint64_t, line_map::MapDelta> early_;  // by from_version
  std::map<std::int64_t, line_map::LineSegment> shown_segments_;  // as of the last delta
  std::uint64_t shown_version_ = 0;
  std::map<std::string, AnnotationRecord> annotations_;
  std::vector<std::string> dirty_annotations_;
  std::vector<CorrectionRecord> corrections_;
  std::size_t corrections_sent_ = 0;
  std::vector<std::size_t> changed_corrections_;  // sent before, answered since
  std::map<std::string, LinkRecord> links_;
  bool links_dirty_ = false;
};

// A segment is observed when an entity contributed to it, plan-only when every source is the a
// priori plan ("plan:<id>"; absorbed ids "#<n>" say nothing of the source).
bool IsObserved(const line_map::LineSegment& segment);

}  // namespace pena::services
