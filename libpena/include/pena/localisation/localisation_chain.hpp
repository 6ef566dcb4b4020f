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
#include "pena/localisation/localised_pose.hpp"
#include "pena/localisation/lost_and_found.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::localisation {

// Options of the whole chain; each part validates its own.
struct LocalisationChainOptions {
  odometry::LaserOdometryOptions odometry;
  MapLocaliserOptions map;
  // Unknown start: follow global hypotheses (GlobalTracker) until one wins, then restart the
  // odometry there (docs/localisation.md, "Global localisation").
  bool global_start = false;
  // With a compass, start the unknown phase at the compass heading and search only within this
  // of it (0: every heading; robots and entities without a compass search every heading).
  double compass_tolerance_rad = 0.5235987755982988;  // 30 deg
  double compass_wait_s = 1.0;  // wait this long for a first compass sample before searching all headings
  GlobalLocaliserOptions global;
  GlobalTrackerOptions tracker;
  // Relocalise a lost entity with a GlobalTracker after this many rejected rounds at the largest
  // window (0 = off); only entities with a compass, since a heading error beyond the window is
  // what plan rounds never re-acquire.
  int relocalise_after_rounds = 0;
  double relocalise_compass_tolerance_rad = 0.5235987755982988;  // winners this far off the compass are refused
  // Lost and found once anchored: lost judged from evidence, then searched for in a growing
  // region and over the whole plan (docs/localisation.md, "Lost and found").
  LostAndFoundOptions lost;
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
  // The plan as matched now (with the walls plan adaptation moved) and those moves.
  const std::vector<geometry::Segment2>& plan() const;
  const std::vector<SegmentShift>& plan_shifts() const;
  const std::vector<PlanOpening>& plan_openings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::localisation
