#include "plan_stage.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

namespace pena::pipeline {
namespace {

// The odometry of the unknown phase: its frame starts at an arbitrary heading, so an absolute
// compass heading would fight the gyro; a huge compass noise gives its readings no weight.
odometry::LaserOdometryOptions UnknownPhase(odometry::LaserOdometryOptions options) {
  options.dead_reckoning.heading.compass_noise_rad = 1e6;
  return options;
}

// The unknown phase's odometry started at the first compass reading keeps the compass. Its
// initial spread allows for a disturbed first reading (up to the tolerance), so that the next
// readings can still pull the heading instead of being gated out.
odometry::LaserOdometryOptions CompassPhase(odometry::LaserOdometryOptions options, double tolerance_rad) {
  auto& heading = options.dead_reckoning.heading;
  heading.initial_heading_sigma_rad = std::max(heading.initial_heading_sigma_rad, tolerance_rad / 3.0);
  return options;
}

// A person whose motion prior is the gyro + compass dead reckoning carries a compass.
bool HasCompass(const odometry::LaserOdometryOptions& options, sensors::EntityKind kind) {
  const auto prior = options.motion_prior;
  return kind == sensors::EntityKind::kHuman &&
         (prior == odometry::MotionPrior::kAuto || prior == odometry::MotionPrior::kDeadReckoning);
}

}  // namespace

PlanStage::PlanStage(const PlanLocalisationOptions& options, const odometry::LaserOdometryOptions& odometry_options,
                     sensors::EntityKind kind, std::vector<geometry::Segment2> plan,
                     const geometry::Pose2& map_from_odom, double start_stamp_s, odometry::LaserOdometry& odometry)
    : options_(options),
      odometry_options_(odometry_options),
      kind_(kind),
      map_(options.map, plan, options.global_start ? geometry::Pose2{} : map_from_odom),
      anchored_(!options.global_start),
      start_stamp_s_(start_stamp_s) {
  if (options.global_start) {
    // The unknown phase: the odometry starts anew in a frame of its own, hypotheses on the whole
    // plan are followed until one wins (section 4 needs a known start; this supplies it).
    global_ = std::make_unique<localisation::GlobalLocaliser>(std::move(plan), options.global);
    tracker_ = std::make_unique<localisation::GlobalTracker>(*global_, options.tracker);
    odometry = odometry::LaserOdometry(UnknownPhase(odometry_options), kind, geometry::Pose2{}, start_stamp_s);
    waiting_for_compass_ = options.compass_tolerance_rad > 0.0 && HasCompass(odometry_options, kind);
  }
  if (options.lost.enabled) {
    lost_global_ = std::make_unique<localisation::GlobalLocaliser>(map_.scanner().segments(), options.global);
    lost_ = std::make_unique<localisation::LostAndFound>(options.lost, *lost_global_);
  }
}

bool PlanStage::Admit(const sensors::SensorRecord& record, odometry::LaserOdometry& odometry) {
  if (waiting_for_compass_) {
    // Before the first scan is used: the first compass reading gives the odometry frame the
    // mission frame's heading, and the tracker keeps to headings near it.
    if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) {
      odometry = odometry::LaserOdometry(CompassPhase(odometry_options_, options_.compass_tolerance_rad), kind_,
                                         geometry::Pose2{0.0, 0.0, compass->heading_rad}, compass->stamp_s);
      localisation::GlobalTrackerOptions bounded = options_.tracker;
      bounded.odom_heading_tolerance_rad = options_.compass_tolerance_rad;
      tracker_ = std::make_unique<localisation::GlobalTracker>(*global_, bounded);
      waiting_for_compass_ = false;
    } else if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
      // No compass after all: every heading, with the odometry fed since the start (as with 0).
      if (scan->stamp_s - start_stamp_s_ > options_.compass_wait_s) waiting_for_compass_ = false;
      if (waiting_for_compass_) return false;
    }
  }
  if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) compass_heading_rad_ = compass->heading_rad;
  return true;
}

PlanUpdate PlanStage::Update(const sensors::SensorRecord& record, odometry::OdometryEstimate& estimate,
                             odometry::LaserOdometry& odometry) {
  const auto& scan = std::get<sensors::LaserScan>(record);
  PlanUpdate update;
  localisation::LocalisedPose& out = update.pose;
  out.stamp_s = estimate.stamp_s;
  out.odometry = estimate;
  const bool first = estimate.status == odometry::MatchStatus::kFirst;
  if (!anchored_ && (first || estimate.reference_changed)) {
    update.odometry_restarted = TryGlobal(record, scan, odometry, out);
  }
  if (anchored_) {
    // Right after anchoring (or at the first scan) a round checks the start against the plan.
    const bool force = first || out.global.has_value();
    out.correction = map_.Update(scan, out.odometry, force);
    if (out.correction) WatchEvidence(scan, out);
    if (options_.relocalise_after_rounds > 0 && out.correction) {
      WatchLost(*out.correction);
      if (relocaliser_ && estimate.reference_changed && TryRelocalise(record, scan, odometry, out)) {
        update.odometry_restarted = true;
      }
    }
  }
  out.map_from_body = anchored_ ? map_.map_from_body() : map_.MapFromBody(out.odometry.world_from_body);
  out.status = map_.status();
  out.anchored = anchored_;
  estimate = out.odometry;
  return update;
}

// The keyframe's evidence to the lost-and-found watch; found at a new place, the odometry frame
// is placed anew on the plan there and a forced round checks it.
void PlanStage::WatchEvidence(const sensors::LaserScan& scan, localisation::LocalisedPose& out) {
  if (!lost_) return;
  const Eigen::Matrix3d& covariance = out.odometry.covariance;
  const double variance_m2 = covariance(0, 0) + covariance(1, 1);
  if (out.correction->accepted) good_position_variance_m2_ = variance_m2;
  const double sigma_m = std::sqrt(std::max(0.0, variance_m2 - good_position_variance_m2_));
  const geometry::Pose2& odom_from_body = out.odometry.world_from_body;
  const localisation::LostStep step = lost_->Update(scan, out.correction, odom_from_body, map_.map_from_body(), sigma_m);
  out.lost_search_radius_m = step.searched_radius_m;
  out.found = step.found.has_value() || step.found_by_round;
  if (out.found) good_position_variance_m2_ = variance_m2;
  if (step.found) {
    map_.Relocalise(geometry::Compose(*step.found, geometry::Inverse(odom_from_body)));
    out.correction = map_.Update(scan, out.odometry, true);
  }
  out.lost = lost_->lost();
}

// Counts the lost rounds; starts following global hypotheses after relocalise_after_rounds of
// them and stops as soon as a plan round is accepted (the entity was re-acquired on its own).
void PlanStage::WatchLost(const localisation::MapCorrection& round) {
  const scan_matching::SearchWindow& max = options_.map.max_window;
  const bool at_max = round.window_xy_m >= std::max(max.size_x_m, max.size_y_m) &&
                      round.window_theta_rad >= max.size_theta_rad;
  lost_rounds_ = !round.accepted && at_max ? lost_rounds_ + 1 : 0;
  if (lost_rounds_ == 0) {
    relocaliser_.reset();
  } else if (lost_rounds_ >= options_.relocalise_after_rounds && !relocaliser_ && compass_heading_rad_) {
    // Every heading: the loss may be a heading error beyond the window.
    if (!global_) global_ = std::make_unique<localisation::GlobalLocaliser>(map_.scanner().segments(), options_.global);
    relocaliser_ = std::make_unique<localisation::GlobalTracker>(*global_, options_.tracker);
  }
}

// A global decision: the odometry starts again at the decided pose on the plan (so its frame is
// the plan's), with this scan as its first.
void PlanStage::RestartOdometryAt(const geometry::Pose2& map_from_body, const sensors::SensorRecord& record,
                                  const sensors::LaserScan& scan, odometry::LaserOdometry& odometry,
                                  localisation::LocalisedPose& out) {
  odometry = odometry::LaserOdometry(odometry_options_, kind_, map_from_body, scan.stamp_s);
  if (const auto restarted = odometry.Add(record)) out.odometry = *restarted;
}

// Lost: the keyframe feeds the global hypotheses; when one wins, the odometry restarts at it on
// the plan (as after a global start) and a forced round checks it, reported as relocalised.
bool PlanStage::TryRelocalise(const sensors::SensorRecord& record, const sensors::LaserScan& scan,
                              odometry::LaserOdometry& odometry, localisation::LocalisedPose& out) {
  out.relocalising = true;
  const localisation::TrackerUpdate update = relocaliser_->Update(scan, out.odometry.world_from_body);
  if (!update.decided) return false;
  const double off_compass_rad =
      std::abs(geometry::NormalizeAngle(update.decided->map_from_body.theta_rad - *compass_heading_rad_));
  if (off_compass_rad > options_.relocalise_compass_tolerance_rad) {
    relocaliser_ = std::make_unique<localisation::GlobalTracker>(*global_, options_.tracker);
    return false;
  }
  RestartOdometryAt(update.decided->map_from_body, record, scan, odometry, out);
  map_.Relocalise(geometry::Pose2{});
  relocaliser_.reset();
  lost_rounds_ = 0;
  out.correction = map_.Update(scan, out.odometry, true);
  return true;
}

// Unknown start: hypotheses are followed over keyframes until one wins. Then the odometry restarts
// at the winner on the plan, with the compass, exactly as with a known start.
bool PlanStage::TryGlobal(const sensors::SensorRecord& record, const sensors::LaserScan& scan,
                          odometry::LaserOdometry& odometry, localisation::LocalisedPose& out) {
  const localisation::TrackerUpdate update = tracker_->Update(scan, out.odometry.world_from_body);
  out.global = update.ranked;
  out.global_searched = update.searched;
  if (!update.decided) return false;
  RestartOdometryAt(update.decided->map_from_body, record, scan, odometry, out);
  map_.Reset(geometry::Pose2{});
  anchored_ = true;
  tracker_.reset();
  global_.reset();
  return true;
}

}  // namespace pena::pipeline
