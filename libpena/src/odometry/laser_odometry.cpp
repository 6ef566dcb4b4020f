#include "pena/odometry/laser_odometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "laser_odometry_impl.hpp"
#include "options_check.hpp"

namespace pena::odometry {
namespace {

bool ResolveConfirm(LaserOdometryOptions::Confirm confirm, sensors::EntityKind kind) {
  if (confirm == LaserOdometryOptions::Confirm::kAuto) return kind == sensors::EntityKind::kHuman;
  return confirm == LaserOdometryOptions::Confirm::kAlways;
}

MotionPrior Resolve(MotionPrior prior, sensors::EntityKind kind) {
  if (prior != MotionPrior::kAuto) return prior;
  return kind == sensors::EntityKind::kHuman ? MotionPrior::kDeadReckoning : MotionPrior::kOdometry;
}

// The two profiles behind the automatic options: robots choose their reference by place (better
// with the frozen-odometry handling on all three Freiburg logs) from a short local map; people
// keep recency with the long local map, and the slide check where strides are spread (on the
// raw stride stream the prior moves in whole strides).
LaserOdometryOptions ForEntity(LaserOdometryOptions options, sensors::EntityKind kind) {
  if (options.local_map_keyframes == LaserOdometryOptions::kAutoLocalMapKeyframes) {
    options.local_map_keyframes = kind == sensors::EntityKind::kRobot
                                      ? LaserOdometryOptions::kShortLocalMapKeyframes
                                      : LaserOdometryOptions::kLongLocalMapKeyframes;
  }
  if (options.local_map_pool_keyframes == LaserOdometryOptions::kAutoPoolKeyframes) {
    options.local_map_pool_keyframes =
        kind == sensors::EntityKind::kRobot ? LaserOdometryOptions::kRobotPoolKeyframes : 0;
  }
  if (options.degenerate_slide_ratio == LaserOdometryOptions::kAutoSlideRatio) {
    const bool spread_strides = Resolve(options.motion_prior, kind) == MotionPrior::kDeadReckoning &&
                                options.dead_reckoning.stride_interpolation.enabled;
    options.degenerate_slide_ratio = spread_strides ? LaserOdometryOptions::kPeopleSlideRatio : 0.0;
  }
  return options;
}

scan_matching::Points2 UsablePoints(const sensors::LaserScan& scan, const LaserOdometryOptions& o,
                                    double rotation_rate_rad_s) {
  scan_matching::Points2 points =
      scan_matching::ScanToPointsAtMidSweep(scan, o.min_range_m, rotation_rate_rad_s);
  std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > o.max_range_m; });
  return points;
}

}  // namespace

LaserOdometry::LaserOdometry(const LaserOdometryOptions& options, sensors::EntityKind kind,
                             const geometry::Pose2& world_from_start, double start_stamp_s)
    : impl_(std::make_unique<Impl>(internal::CheckedOptions(ForEntity(options, kind)),
                                   Resolve(options.motion_prior, kind),
                                   ResolveConfirm(options.confirm_reference, kind),
                                   world_from_start, start_stamp_s)) {
  // Stale scans are a logging fault of robots (intel). A walking person's sway brings scans back
  // within 2 cm of one a few scans earlier: loop170 seed 1 had 71 such false repeats.
  if (kind != sensors::EntityKind::kRobot) impl_->stale_scans = internal::StaleScanDetector(0, 0.0, 0.0);
  // Without a heading source the paper needs the wide window from the start.
  const MotionPrior mode = impl_->motion.mode();
  if (mode == MotionPrior::kStrideOnly || mode == MotionPrior::kNone) impl_->window.SetWide();
}

LaserOdometry::~LaserOdometry() = default;
LaserOdometry::LaserOdometry(LaserOdometry&&) noexcept = default;
LaserOdometry& LaserOdometry::operator=(LaserOdometry&&) noexcept = default;

std::optional<OdometryEstimate> LaserOdometry::Add(const sensors::SensorRecord& record) {
  const StageClock<OdometryStage>::Call call(impl_->clock, OdometryStage::kOther);
  if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
    if (impl_->last_scan_stamp_s && !(scan->stamp_s > *impl_->last_scan_stamp_s)) {
      ++impl_->counts.records_ignored;  // a scan not after the previous one: time must advance
      return std::nullopt;
    }
    impl_->last_scan_stamp_s = scan->stamp_s;
    return impl_->AddScan(*scan);
  }
  if (std::holds_alternative<sensors::GroundTruth>(record)) return std::nullopt;
  const Impl::Timed timed(impl_->clock, OdometryStage::kPrediction);
  if (!impl_->motion.Add(record)) ++impl_->counts.records_ignored;
  return std::nullopt;
}

OdometryEstimate LaserOdometry::Impl::AddScan(const sensors::LaserScan& scan) {
  ++counts.scans;
  OdometryEstimate out;
  out.stamp_s = scan.stamp_s;
  gate_trusted = false;
  fell_back = false;
  keyframe_from_this_scan = false;
  {
    const Timed timed(clock, OdometryStage::kPrediction);
    out.world_from_prior = Predict(scan);
  }
  match_weak_direction.reset();
  poor_timing = timing.Add(scan.stamp_s);
  scan_matching::Points2 points;
  {
    const Timed timed(clock, OdometryStage::kPoints);
    points = MidSweepPoints(scan, out);
  }
  out.points = static_cast<int>(points.size());
  out.stale = stale_scans.IsStale(scan);
  counts.stale += out.stale ? 1 : 0;
  estimate = out.world_from_prior;
  if (local_map.empty()) {
    out.status = MatchStatus::kFirst;  // starts the map; until a scan has points, again and again
    if (points.size() >= 10) TakeKeyframe(points, out);
  } else if (!options.match_scans) {
    out.status = MatchStatus::kPriorOnly;
  } else if (static_cast<int>(points.size()) < options.min_match_points) {
    out.status = MatchStatus::kNoPoints;  // dead reckoning carries on
    ++counts.no_points;
  } else {
    const Timed timed(clock, OdometryStage::kKeyframePolicy);
    Match(points, out);
  }
  out.world_from_body = estimate;
  {
    const Timed timed(clock, OdometryStage::kCovariance);
    UpdateCovariance(out);
  }
  out.covariance = covariance;
  // Stretches matched in every direction calibrate the stride scale used in corridors.
  motion.AddPositionFix(scan.stamp_s, estimate,
                        out.status == MatchStatus::kMatched && !out.gated && !out.stale);
  previous_scan_stamp_s = scan.stamp_s;
  if (out.stale) {
    // Its pose is the earlier scan's: the next scans go on from the prediction for now.
    estimate = out.world_from_prior;
    previous_estimate = estimate;
    frozen_odometry.Estimated(estimate);
    return out;
  }
  velocity = geometry::Between(previous_estimate, estimate);
  previous_estimate = estimate;
  frozen_odometry.Estimated(estimate);
  if (motion.last_pose()) pace_check.Record(*motion.last_pose(), estimate);
  return out;
}

std::optional<double> LaserOdometry::Impl::DeskewInterval(const sensors::LaserScan& scan) const {
  if (!options.deskew_scans || scan.geometry.sweep_s == 0.0 || !previous_scan_stamp_s) {
    return std::nullopt;
  }
  double interval_s = scan.stamp_s - *previous_scan_stamp_s;
  if (poor_timing) {
    if (!options.deskew_bursty_scans) return std::nullopt;
    interval_s = timing.mean_interval_s();
  }
  if (interval_s < options.deskew_min_interval_s || interval_s <= 0.0) return std::nullopt;
  return interval_s;
}

scan_matching::Points2 LaserOdometry::Impl::MidSweepPoints(const sensors::LaserScan& logged,
                                                           const OdometryEstimate& out) {
  const std::optional<double> interval_s = DeskewInterval(logged);
  if (!interval_s) return UsablePoints(logged, options, 0.0);
  ++counts.deskewed;
  const auto turn_rate_rad_s = [&](const geometry::Pose2& world_from_scan) {
    return geometry::NormalizeAngle(world_from_scan.theta_rad - previous_estimate.theta_rad) /
           *interval_s;
  };
  // The interlace the scans show (interlace_evidence.hpp), not only the one the reader assumed.
  {
    const Timed timed(clock, OdometryStage::kDeskew);
    interlace_evidence.Add(logged, turn_rate_rad_s(out.world_from_prior), options.min_range_m);
  }
  sensors::LaserScan scan = logged;
  scan.geometry.interlace = interlace_evidence.Interlace(logged.geometry.interlace);
  counts.laser_interlace = interlace_evidence.decided().value_or(0);
  scan_matching::Points2 points =
      UsablePoints(scan, options, turn_rate_rad_s(out.world_from_prior));
  // The first pass searches from the prior as the match will; later ones only move the pose
  // found by as much as the paper's window (the turn rate changes by a fraction of a degree).
  std::optional<geometry::Pose2> matched;
  for (int pass = 0; pass < options.deskew_match_passes; ++pass) {
    matched = MatchForDeskew(points, matched ? *matched : out.world_from_prior, !matched);
    if (!matched) break;
    points = UsablePoints(scan, options, turn_rate_rad_s(*matched));
  }
  return points;
}

std::optional<geometry::Pose2> LaserOdometry::Impl::MatchForDeskew(
    const scan_matching::Points2& points, const geometry::Pose2& around,
    bool current_window) const {
  if (!matcher || local_map.empty() ||
      static_cast<int>(points.size()) < options.min_match_points) {
    return std::nullopt;
  }
  // Branch and bound finds the exhaustive search's pose, faster in grown windows.
  const bool base = !current_window || window.IsBase();
  const scan_matching::SearchWindow searched = base ? options.window : window.Current();
  const scan_matching::MatchResult result =
      RunMatcher(points, around, searched, base, OdometryStage::kDeskew);
  if (result.score < options.min_score) return std::nullopt;
  return result.reference_from_scan;
}

scan_matching::MatchResult LaserOdometry::Impl::RunMatcher(
    const scan_matching::Points2& points, const geometry::Pose2& around,
    const scan_matching::SearchWindow& searched, bool exhaustive, OdometryStage stage,
    scan_matching::Polish polish) const {
  const Timed timed(clock, stage);
  scan_matching::MatchResult result =
      exhaustive ? matcher->MatchExhaustive(points, around, searched, polish)
                 : matcher->MatchBranchAndBound(points, around, searched, polish);
  // Branch and bound's max-grids are built once per reference, at its first wide search. (The
  // kept match's refinement is timed where Match calls it; deskew's matches are all its own.)
  if (stage != OdometryStage::kDeskew && result.max_grids_s > 0.0) {
    clock.Move(OdometryStage::kReference, result.max_grids_s);
  }
  return result;
}

geometry::Pose2 LaserOdometry::Impl::Predict(const sensors::LaserScan& scan) {
  const geometry::Pose2 increment = motion.TakeIncrement(scan);
  const auto& motion_pose = motion.last_pose();
  motion_since_keyframe.reset();
  // Intel's bursts repeat the pose of the scan delivered with them (its Y frame: 0.249 -> 0.392 m
  // when they were taken as freezes).
  const bool burst =
      poor_timing || (previous_scan_stamp_s &&
                      scan.stamp_s - *previous_scan_stamp_s < options.timing_burst_gap_s);
  const std::optional<geometry::Pose2> coasting =
      frozen_odometry.Predict(motion_pose, previous_estimate, velocity, burst);
  // Chained from the previous scan, or anchored at the latest keyframe: the covariance of an
  // unmatched scan grows from the pose the prior was composed from.
  prior_anchor = estimate;
  prior_anchor_covariance = covariance;
  if (!motion_pose || !keyframe_motion_pose || local_map.empty()) {
    return geometry::Compose(estimate, increment);
  }
  if (coasting) {  // the odometry froze while the scans moved: constant velocity meanwhile
    motion_since_keyframe = geometry::Between(
        *keyframe_motion_pose, *frozen_odometry.PairedPose(motion_pose, *coasting));
    return *coasting;
  }
  motion_since_keyframe = geometry::Between(*keyframe_motion_pose, *motion_pose);
  prior_anchor = local_map.latest().world_from_body;
  prior_anchor_covariance = local_map.latest().covariance;
  // Anchored at the keyframe, not chained scan to scan: logged odometry often repeats a pose for
  // several scans and then jumps (mit-csail: 85 deg in one step after 1 s of zeros); chaining
  // would add that catch-up on top of the motion the matcher already found.
  return geometry::Compose(local_map.latest().world_from_body,
                           geometry::Between(*keyframe_motion_pose, *motion_pose));
}

const OdometryCounts& LaserOdometry::counts() const { return impl_->counts; }

const dead_reckoning::DeadReckoningCounts& LaserOdometry::dead_reckoning_counts() const {
  return impl_->motion.dead_reckoning_counts();
}

const OdometryStageTimes& LaserOdometry::stage_times() const { return impl_->clock.times(); }

const char* ToString(OdometryStage stage) {
  switch (stage) {
    case OdometryStage::kPrediction: return "prediction";
    case OdometryStage::kPoints: return "points";
    case OdometryStage::kDeskew: return "deskew";
    case OdometryStage::kReference: return "reference";
    case OdometryStage::kSearchBase: return "search_base";
    case OdometryStage::kSearchWide: return "search_wide";
    case OdometryStage::kRefinement: return "refinement";
    case OdometryStage::kCovariance: return "covariance";
    case OdometryStage::kKeyframePolicy: return "keyframe_policy";
    case OdometryStage::kOther: return "other";
    case OdometryStage::kCount: break;
  }
  return "unknown";
}

const char* ToString(MatchStatus status) {
  switch (status) {
    case MatchStatus::kFirst: return "first";
    case MatchStatus::kMatched: return "matched";
    case MatchStatus::kDegenerate: return "degenerate";
    case MatchStatus::kFailed: return "failed";
    case MatchStatus::kNoPoints: return "no_points";
    case MatchStatus::kPriorOnly: return "prior_only";
  }
  return "unknown";
}

}  // namespace pena::odometry
