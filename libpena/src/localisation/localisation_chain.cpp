#include "pena/localisation/localisation_chain.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace pena::localisation {
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

void Validate(const LocalisationChainOptions& o) {
  if (!(o.compass_tolerance_rad >= 0.0) || !std::isfinite(o.compass_tolerance_rad)) {
    throw std::invalid_argument("localisation_chain.compass_tolerance_rad must be >= 0 rad, got " +
                                std::to_string(o.compass_tolerance_rad));
  }
  if (!(o.compass_wait_s >= 0.0) || !std::isfinite(o.compass_wait_s)) {
    throw std::invalid_argument("localisation_chain.compass_wait_s must be >= 0 s, got " +
                                std::to_string(o.compass_wait_s));
  }
  if (o.relocalise_after_rounds < 0) {
    throw std::invalid_argument("localisation_chain.relocalise_after_rounds must be >= 0 rounds, got " +
                                std::to_string(o.relocalise_after_rounds));
  }
  if (!(o.relocalise_compass_tolerance_rad > 0.0) || !std::isfinite(o.relocalise_compass_tolerance_rad)) {
    throw std::invalid_argument("localisation_chain.relocalise_compass_tolerance_rad must be > 0 rad, got " +
                                std::to_string(o.relocalise_compass_tolerance_rad));
  }
}

}  // namespace

struct LocalisationChain::Impl {
  LocalisationChainOptions options;
  sensors::EntityKind kind;
  odometry::LaserOdometry odometry;
  MapLocaliser map;
  std::unique_ptr<GlobalLocaliser> global;  // while the start is unknown, and once lost
  std::unique_ptr<GlobalTracker> tracker;
  bool anchored = true;
  double start_stamp_s = 0.0;
  bool waiting_for_compass = false;  // unknown start with a compass: no scan used before it
  std::unique_ptr<GlobalTracker> relocaliser;  // while lost (relocalise_after_rounds)
  int lost_rounds = 0;  // plan rounds in a row rejected with the window at its maximum
  std::optional<double> compass_heading_rad;  // the latest compass reading (mission frame)
  // Lost and found once anchored, with its own whole-plan localiser (the a priori plan).
  std::unique_ptr<GlobalLocaliser> lost_global;
  std::unique_ptr<LostAndFound> lost;
  double good_position_variance_m2 = 0.0;  // odometry x + y variance at the last accepted round

  // The keyframe's evidence to the lost-and-found watch; found at a new place, the odometry frame
  // is placed anew on the plan there and a forced round checks it.
  void WatchEvidence(const sensors::LaserScan& scan, LocalisedPose& out) {
    if (!lost) return;
    const Eigen::Matrix3d& covariance = out.odometry.covariance;
    const double variance_m2 = covariance(0, 0) + covariance(1, 1);
    if (out.correction->accepted) good_position_variance_m2 = variance_m2;
    const double sigma_m = std::sqrt(std::max(0.0, variance_m2 - good_position_variance_m2));
    const geometry::Pose2& odom_from_body = out.odometry.world_from_body;
    const LostStep step = lost->Update(scan, out.correction, odom_from_body, map.map_from_body(), sigma_m);
    out.lost_search_radius_m = step.searched_radius_m;
    out.found = step.found.has_value() || step.found_by_round;
    if (out.found) good_position_variance_m2 = variance_m2;
    if (step.found) {
      map.Relocalise(geometry::Compose(*step.found, geometry::Inverse(odom_from_body)));
      out.correction = map.Update(scan, out.odometry, true);
    }
    out.lost = lost->lost();
  }

  // Counts the lost rounds; starts following global hypotheses after relocalise_after_rounds of
  // them and stops as soon as a plan round is accepted (the entity was re-acquired on its own).
  void WatchLost(const MapCorrection& round) {
    const scan_matching::SearchWindow& max = options.map.max_window;
    const bool at_max = round.window_xy_m >= std::max(max.size_x_m, max.size_y_m) &&
                        round.window_theta_rad >= max.size_theta_rad;
    lost_rounds = !round.accepted && at_max ? lost_rounds + 1 : 0;
    if (lost_rounds == 0) {
      relocaliser.reset();
    } else if (lost_rounds >= options.relocalise_after_rounds && !relocaliser && compass_heading_rad) {
      // Every heading: the loss may be a heading error beyond the window.
      if (!global) global = std::make_unique<GlobalLocaliser>(map.scanner().segments(), options.global);
      relocaliser = std::make_unique<GlobalTracker>(*global, options.tracker);
    }
  }

  // A global decision: the odometry starts again at the decided pose on the plan (so its frame is
  // the plan's), with this scan as its first.
  void RestartOdometryAt(const geometry::Pose2& map_from_body, const sensors::SensorRecord& record,
                         const sensors::LaserScan& scan, LocalisedPose& out) {
    odometry = odometry::LaserOdometry(options.odometry, kind, map_from_body, scan.stamp_s);
    if (const auto restarted = odometry.Add(record)) out.odometry = *restarted;
  }

  // Lost: the keyframe feeds the global hypotheses; when one wins, the odometry restarts at it on
  // the plan (as after a global start) and a forced round checks it, reported as relocalised.
  void TryRelocalise(const sensors::SensorRecord& record, const sensors::LaserScan& scan, LocalisedPose& out) {
    out.relocalising = true;
    const TrackerUpdate update = relocaliser->Update(scan, out.odometry.world_from_body);
    if (!update.decided) return;
    const double off_compass_rad =
        std::abs(geometry::NormalizeAngle(update.decided->map_from_body.theta_rad - *compass_heading_rad));
    if (off_compass_rad > options.relocalise_compass_tolerance_rad) {
      relocaliser = std::make_unique<GlobalTracker>(*global, options.tracker);
      return;
    }
    RestartOdometryAt(update.decided->map_from_body, record, scan, out);
    map.Relocalise(geometry::Pose2{});
    relocaliser.reset();
    lost_rounds = 0;
    out.correction = map.Update(scan, out.odometry, true);
  }

  // Unknown start: hypotheses are followed over keyframes until one wins (section 4 needs a known
  // start; this supplies it). Then the odometry restarts at the winner on the plan, with the
  // compass, exactly as with a known start.
  void TryGlobal(const sensors::SensorRecord& record, const sensors::LaserScan& scan, LocalisedPose& out) {
    const TrackerUpdate update = tracker->Update(scan, out.odometry.world_from_body);
    out.global = update.ranked;
    out.global_searched = update.searched;
    if (!update.decided) return;
    RestartOdometryAt(update.decided->map_from_body, record, scan, out);
    map.Reset(geometry::Pose2{});
    anchored = true;
    tracker.reset();
    global.reset();
  }

  // Before the first scan is used: the first compass reading gives the odometry frame the
  // mission frame's heading, and the tracker keeps to headings near it. Returns false for a scan
  // that must wait for the compass.
  bool AwaitCompass(const sensors::SensorRecord& record) {
    if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) {
      odometry = odometry::LaserOdometry(CompassPhase(options.odometry, options.compass_tolerance_rad), kind,
                                         geometry::Pose2{0.0, 0.0, compass->heading_rad}, compass->stamp_s);
      GlobalTrackerOptions bounded = options.tracker;
      bounded.odom_heading_tolerance_rad = options.compass_tolerance_rad;
      tracker = std::make_unique<GlobalTracker>(*global, bounded);
      waiting_for_compass = false;
      return true;
    }
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (!scan) return true;
    // No compass after all: every heading, with the odometry fed since the start (as with 0).
    if (scan->stamp_s - start_stamp_s > options.compass_wait_s) waiting_for_compass = false;
    return !waiting_for_compass;
  }
};

LocalisationChain::LocalisationChain(const LocalisationChainOptions& options,
                                     sensors::EntityKind kind, std::vector<geometry::Segment2> plan,
                                     const geometry::Pose2& map_from_start, double start_stamp_s) {
  Validate(options);
  const bool unknown = options.global_start;
  std::unique_ptr<GlobalLocaliser> global;
  std::unique_ptr<GlobalTracker> tracker;
  if (unknown) {
    global = std::make_unique<GlobalLocaliser>(plan, options.global);
    tracker = std::make_unique<GlobalTracker>(*global, options.tracker);
  }
  impl_ = std::make_unique<Impl>(Impl{
      options, kind,
      odometry::LaserOdometry(unknown ? UnknownPhase(options.odometry) : options.odometry, kind,
                              unknown ? geometry::Pose2{} : map_from_start, start_stamp_s),
      MapLocaliser(options.map, std::move(plan), geometry::Pose2{}), std::move(global), std::move(tracker),
      !unknown, start_stamp_s,
      unknown && options.compass_tolerance_rad > 0.0 && HasCompass(options.odometry, kind), nullptr, 0, std::nullopt,
      nullptr, nullptr, 0.0});
  if (options.lost.enabled) {
    impl_->lost_global = std::make_unique<GlobalLocaliser>(impl_->map.scanner().segments(), options.global);
    impl_->lost = std::make_unique<LostAndFound>(options.lost, *impl_->lost_global);
  }
}

LocalisationChain::~LocalisationChain() = default;
LocalisationChain::LocalisationChain(LocalisationChain&&) noexcept = default;
LocalisationChain& LocalisationChain::operator=(LocalisationChain&&) noexcept = default;

std::optional<LocalisedPose> LocalisationChain::Add(const sensors::SensorRecord& record) {
  if (impl_->waiting_for_compass && !impl_->AwaitCompass(record)) return std::nullopt;
  if (const auto* compass = std::get_if<sensors::CompassSample>(&record)) impl_->compass_heading_rad = compass->heading_rad;
  std::optional<odometry::OdometryEstimate> estimate = impl_->odometry.Add(record);
  if (!estimate) return std::nullopt;
  const auto& scan = std::get<sensors::LaserScan>(record);
  LocalisedPose out;
  out.stamp_s = estimate->stamp_s;
  out.odometry = *estimate;
  const bool first = estimate->status == odometry::MatchStatus::kFirst;
  if (!impl_->anchored && (first || estimate->reference_changed)) impl_->TryGlobal(record, scan, out);
  if (impl_->anchored) {
    // Right after anchoring (or at the first scan) a round checks the start against the plan.
    const bool force = first || out.global.has_value();
    out.correction = impl_->map.Update(scan, out.odometry, force);
    if (out.correction) impl_->WatchEvidence(scan, out);
    if (impl_->options.relocalise_after_rounds > 0 && out.correction) {
      impl_->WatchLost(*out.correction);
      if (impl_->relocaliser && estimate->reference_changed) impl_->TryRelocalise(record, scan, out);
    }
  }
  out.map_from_body = impl_->anchored ? impl_->map.map_from_body()
                                      : impl_->map.MapFromBody(out.odometry.world_from_body);
  out.status = impl_->map.status();
  out.anchored = impl_->anchored;
  return out;
}

const std::vector<geometry::Segment2>& LocalisationChain::plan() const {
  return impl_->map.scanner().segments();
}

const std::vector<SegmentShift>& LocalisationChain::plan_shifts() const { return impl_->map.plan_shifts(); }
const std::vector<PlanOpening>& LocalisationChain::plan_openings() const { return impl_->map.plan_openings(); }

const odometry::OdometryCounts& LocalisationChain::odometry_counts() const {
  return impl_->odometry.counts();
}

}  // namespace pena::localisation
