#pragma once
// The pipeline's plan-localisation stage (paper section 4.2, and the unknown start and lost and
// found beyond it): virtual scan matching against an a priori plan on top of the pipeline's
// odometry. A global decision restarts that odometry on the plan, so the stage is given it.
// Private to the pipeline module.

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
#include "pena/pipeline/plan_localisation_options.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::pipeline {

// What the stage did at one scan.
struct PlanUpdate {
  localisation::LocalisedPose pose;
  bool odometry_restarted = false;  // a global decision restarted the odometry on the plan
};

class PlanStage {
 public:
  // `map_from_odom`: where the odometry frame lies on the plan (ignored with global_start, which
  // restarts `odometry` for its unknown phase; then no record may have reached it yet).
  PlanStage(const PlanLocalisationOptions& options, const odometry::LaserOdometryOptions& odometry_options,
            sensors::EntityKind kind, std::vector<geometry::Segment2> plan, const geometry::Pose2& map_from_odom,
            double start_stamp_s, odometry::LaserOdometry& odometry);

  // Before the odometry sees `record`: false for a record that must wait for the first compass
  // sample (unknown start with a compass); that sample restarts `odometry` at its heading.
  bool Admit(const sensors::SensorRecord& record, odometry::LaserOdometry& odometry);
  // After the odometry placed `record` (a laser scan) at `estimate`: a round against the plan, the
  // unknown start and lost and found. A global decision restarts `odometry` and replaces `estimate`.
  PlanUpdate Update(const sensors::SensorRecord& record, odometry::OdometryEstimate& estimate,
                    odometry::LaserOdometry& odometry);

  // Where the odometry frame lies on the plan now.
  const geometry::Pose2& map_from_odom() const { return map_.map_from_odom(); }
  // Re-anchors the odometry frame (a correction from outside); the next round uses the narrow window.
  void Reset(const geometry::Pose2& map_from_odom) { map_.Reset(map_from_odom); }
  // The plan as matched now (with the walls plan adaptation moved), and those moves.
  const std::vector<geometry::Segment2>& plan() const { return map_.scanner().segments(); }
  const std::vector<localisation::SegmentShift>& plan_shifts() const { return map_.plan_shifts(); }
  const std::vector<localisation::PlanOpening>& plan_openings() const { return map_.plan_openings(); }

 private:
  void WatchEvidence(const sensors::LaserScan& scan, localisation::LocalisedPose& out);
  void WatchLost(const localisation::MapCorrection& round);
  void RestartOdometryAt(const geometry::Pose2& map_from_body, const sensors::SensorRecord& record,
                         const sensors::LaserScan& scan, odometry::LaserOdometry& odometry,
                         localisation::LocalisedPose& out);
  bool TryRelocalise(const sensors::SensorRecord& record, const sensors::LaserScan& scan,
                     odometry::LaserOdometry& odometry, localisation::LocalisedPose& out);
  bool TryGlobal(const sensors::SensorRecord& record, const sensors::LaserScan& scan,
                 odometry::LaserOdometry& odometry, localisation::LocalisedPose& out);

  PlanLocalisationOptions options_;
  odometry::LaserOdometryOptions odometry_options_;
  sensors::EntityKind kind_;
  localisation::MapLocaliser map_;
  std::unique_ptr<localisation::GlobalLocaliser> global_;  // while the start is unknown, and once lost
  std::unique_ptr<localisation::GlobalTracker> tracker_;
  bool anchored_ = true;
  double start_stamp_s_ = 0.0;
  bool waiting_for_compass_ = false;  // unknown start with a compass: no scan used before it
  std::unique_ptr<localisation::GlobalTracker> relocaliser_;  // while lost (relocalise_after_rounds)
  int lost_rounds_ = 0;  // plan rounds in a row rejected with the window at its maximum
  std::optional<double> compass_heading_rad_;  // the latest compass reading (mission frame)
  // Lost and found once anchored, with its own whole-plan localiser (the a priori plan).
  std::unique_ptr<localisation::GlobalLocaliser> lost_global_;
  std::unique_ptr<localisation::LostAndFound> lost_;
  double good_position_variance_m2_ = 0.0;  // odometry x + y variance at the last accepted round
};

}  // namespace pena::pipeline
