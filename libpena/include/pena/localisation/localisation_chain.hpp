#pragma once
// One entity's localisation on an a priori plan: the laser odometry (section 2) with virtual scan
// matching on top (section 4.2), and, when the start is unknown, a global localisation of the
// first scans on the whole plan. One call per sensor record, like odometry::LaserOdometry.

#include <memory>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/global_tracker.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::localisation {

// Options of the whole chain; each part validates its own.
struct LocalisationChainOptions {
  odometry::LaserOdometryOptions odometry;
  MapLocaliserOptions map;
  // Unknown start: the odometry runs in a frame of its own while global hypotheses are followed
  // over the first keyframes (GlobalTracker); when one wins, the odometry restarts at it on the
  // plan. In the unknown phase the compass is not used (its absolute heading does not hold in a
  // frame started at an arbitrary heading) ...
  bool global_start = false;
  // ... unless this is > 0 and the entity has a compass (a person whose motion prior is the
  // gyro + compass dead reckoning): then no scan is used before the first compass sample, the
  // unknown phase's odometry starts at the compass heading and keeps the compass, and the whole-
  // plan searches and the followed hypotheses keep to headings within this of the odometry's
  // (GlobalTrackerOptions::odom_heading_tolerance_rad); it allows for a compass disturbed where
  // the walk starts. Without a compass sample within compass_wait_s of the start, or for a robot,
  // every heading is searched as with 0. Works with the tracker's pairwise freeze
  // (docs/localisation.md, "Global localisation").
  double compass_tolerance_rad = 0.5235987755982988;  // 30 deg
  double compass_wait_s = 1.0;
  GlobalLocaliserOptions global;
  GlobalTrackerOptions tracker;
  // Relocalisation of a lost entity (beyond the paper; 0 = off, the default): after this many
  // plan rounds in a row rejected with the window at its maximum (map.max_window), a
  // GlobalTracker (the `tracker` options, every heading) follows whole-plan hypotheses over the
  // keyframes from then on, beside the plan rounds. If a plan round is accepted first it is
  // dropped; if it decides first, the odometry restarts at the winner as after a global start and
  // the round reports MapStatus::kRelocalised. Why: a heading error beyond the window (a fast turn
  // the laser odometry lost) is never re-acquired by plan rounds. A winner whose heading is more
  // than relocalise_compass_tolerance_rad off the latest compass reading is refused and the
  // tracker starts afresh (an unmapped room can look like a plan corridor turned 90 deg); an
  // entity without a compass (a robot) is never relocalised.
  int relocalise_after_rounds = 0;
  double relocalise_compass_tolerance_rad = 0.5235987755982988;  // 30 deg
};

// The estimate at one scan.
struct LocalisedPose {
  double stamp_s = 0.0;
  geometry::Pose2 map_from_body;          // on the plan
  odometry::OdometryEstimate odometry;    // the odometry's own estimate (its world frame)
  MapStatus status = MapStatus::kUnknown; // after this scan
  std::optional<MapCorrection> correction;     // a match round ran at this scan
  std::optional<GlobalResult> global;          // the followed global hypotheses at this scan
  bool global_searched = false;                // a whole-plan search ran at this scan
  bool anchored = false;                  // the odometry frame is placed on the plan
  bool relocalising = false;              // lost: global hypotheses are followed (relocalise_after_rounds)
};

// The chain for one entity. Not thread-safe.
class LocalisationChain {
 public:
  // `map_from_start`: the known start pose on the plan (ignored with global_start).
  LocalisationChain(const LocalisationChainOptions& options, sensors::EntityKind kind,
                    std::vector<geometry::Segment2> plan, const geometry::Pose2& map_from_start,
                    double start_stamp_s);
  ~LocalisationChain();
  LocalisationChain(LocalisationChain&&) noexcept;
  LocalisationChain& operator=(LocalisationChain&&) noexcept;

  // Feeds one record in time order; a laser scan yields its estimate, anything else nullopt.
  std::optional<LocalisedPose> Add(const sensors::SensorRecord& record);

  const odometry::OdometryCounts& odometry_counts() const;
  // The plan as matched now (with the walls MapLocaliserOptions::plan_adaptation moved) and
  // those moves.
  const std::vector<geometry::Segment2>& plan() const;
  const std::vector<SegmentShift>& plan_shifts() const;
  const std::vector<PlanOpening>& plan_openings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::localisation
