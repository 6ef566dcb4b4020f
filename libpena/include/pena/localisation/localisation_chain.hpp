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
#include "pena/localisation/map_localiser.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::localisation {

// Options of the whole chain; each part validates its own.
struct LocalisationChainOptions {
  odometry::LaserOdometryOptions odometry;
  MapLocaliserOptions map;
  bool global_start = false;       // unknown start: localise the first scans on the whole plan
  GlobalLocaliserOptions global;
  double global_min_score = 0.5;   // a global hypothesis is taken at this fine score ...
  double global_min_margin = 0.05; // ... and this lead over the second; else the next keyframe
};

// The estimate at one scan.
struct LocalisedPose {
  double stamp_s = 0.0;
  geometry::Pose2 map_from_body;          // on the plan
  odometry::OdometryEstimate odometry;    // the odometry's own estimate (its world frame)
  MapStatus status = MapStatus::kUnknown; // after this scan
  std::optional<MapCorrection> correction;     // a match round ran at this scan
  std::optional<GlobalResult> global;          // a global localisation ran at this scan
  bool anchored = false;                  // the odometry frame is placed on the plan
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

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::localisation
