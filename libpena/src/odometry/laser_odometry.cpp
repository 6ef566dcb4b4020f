#include "pena/odometry/laser_odometry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "local_map.hpp"
#include "motion_tracker.hpp"
#include "options_check.hpp"
#include "reference_fill.hpp"
#include "search_window.hpp"
#include "burst_timing.hpp"
#include "frozen_odometry.hpp"
#include "gate_confirmation.hpp"
#include "stale_scan.hpp"

namespace pena::odometry {
namespace {

internal::PlaceChoice PlaceChoiceOf(const LaserOdometryOptions& o) {
  return {o.local_map_pool_keyframes, o.local_map_pool_age_s, o.local_map_recent_keyframes,
          o.local_map_place_radius_m, o.keyframe_distance_m, o.keyframe_angle_rad};
}

}  // namespace

struct LaserOdometry::Impl {
  Impl(const LaserOdometryOptions& checked, MotionPrior mode, bool confirm,
       const geometry::Pose2& world_from_start, double start_stamp_s)
      : options(checked),
        motion(mode, checked.dead_reckoning, world_from_start, start_stamp_s),
        wall_only_range_m(confirm ? internal::WallOnlyRangeM(checked.tilt_laser_height_m,
                                                             checked.tilt_ceiling_height_m,
                                                             checked.tilt_max_pitch_rad)
                                  : 0.0),
        local_map(checked.local_map_keyframes, 2.0 * checked.matcher.threshold_m, confirm,
                  wall_only_range_m, PlaceChoiceOf(checked)),
        window(checked),
        stale_scans(checked.stale_history_scans, checked.stale_repeat_m, checked.stale_changed_m),
        timing(checked.timing_burst_gap_s, checked.timing_burst_fraction,
               checked.timing_burst_window_scans),
        fill_spacing_m(confirm && wall_only_range_m <= 0.0 ? 0.0 : checked.reference_fill_spacing_m),
        fill_max_range_m(confirm ? wall_only_range_m : std::numeric_limits<double>::infinity()),
        estimate(world_from_start),
        previous_estimate(world_from_start),
        gate_confirmation(mode == MotionPrior::kDeadReckoning ? checked.prior_gate_agree_gyro_m : 0.0,
                          checked.prior_gate_agree_gyro_rad),
        frozen_odometry(  // robots' wheel odometry only
            mode == MotionPrior::kOdometry ? checked.frozen_odometry_min_turn_rad : 0.0,
            mode == MotionPrior::kOdometry ? checked.frozen_odometry_min_move_m : 0.0) {}

  LaserOdometryOptions options;
  internal::MotionTracker motion;
  // With reference confirmation: the tilt model's range within which returns are walls (0: none).
  double wall_only_range_m;
  internal::LocalMap local_map;
  std::optional<scan_matching::CorrelationScanMatcher> matcher;  // built from local_map
  internal::WindowScale window;
  internal::StaleScanDetector stale_scans;
  internal::BurstTiming timing;
  bool poor_timing = false;  // scans arrive in bursts now: keyframes keep the bursty fill limit
  // Keyframes are densified only where no floor or ceiling hit can be: with a tilting body-worn
  // laser filled floor-hit streaks confirm each other (measured in docs/odometry.md). Without
  // confirmation everywhere; with it, within the tilt model's wall-only range (if any).
  double fill_spacing_m;
  double fill_max_range_m;
  geometry::Pose2 estimate;
  // The motion sensor's pose at the latest keyframe: priors are anchored there (see Predict).
  std::optional<geometry::Pose2> keyframe_motion_pose;
  std::optional<double> keyframe_heading_sigma_rad;  // the heading filter's there (dead reckoning)
  geometry::Pose2 previous_estimate;  // at the previous scan
  geometry::Pose2 velocity;           // estimated motion over the previous scan interval
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // The motion sensor's motion since the latest keyframe (nullopt without a sensor pose): the
  // prior-consistency gate's allowance grows with it.
  std::optional<geometry::Pose2> motion_since_keyframe;
  internal::GateConfirmation gate_confirmation;
  internal::FrozenOdometry frozen_odometry;  // wheel odometry only (frozen_odometry_*)
  int gated_in_row = 0;  // gated scans since the last keyframe (see prior_gate_fallback_scans)
  int heading_off_in_row = 0;  // matched scans off the gyro + compass heading (heading_bound_rad)
  std::optional<double> last_scan_stamp_s;
  std::optional<double> previous_scan_stamp_s;  // of the scan before the one being added
  // A poor match in a fast turn not made a keyframe (keyframe_turn_*): if the next match against
  // the kept reference is poor too, the reference no longer covers the turn and this candidate
  // becomes the keyframe after all (the mit-csail runs without it failed two scans later).
  struct HeldCandidate {
    scan_matching::Points2 points;  // scan frame
    geometry::Pose2 world_from_body;
    std::optional<geometry::Pose2> motion_pose;
    std::optional<double> heading_sigma_rad;
    bool poor_timing = false;
    double stamp_s = 0.0;
  };
  std::optional<HeldCandidate> held;
  OdometryCounts counts;

  OdometryEstimate AddScan(const sensors::LaserScan& scan);
  geometry::Pose2 Predict(const sensors::LaserScan& scan);
  void Match(const scan_matching::Points2& points, OdometryEstimate& out);
  scan_matching::MatchResult Search(const scan_matching::Points2& points,
                                    const geometry::Pose2& prior, OdometryEstimate& out);
  void TakeKeyframe(const scan_matching::Points2& points, OdometryEstimate& out);
  void AddKeyframe(const scan_matching::Points2& points, const geometry::Pose2& world_from_body,
                   bool bursty, double stamp_s);
  bool NearAKeyframe(const geometry::Pose2& moved) const;
  void CommitHeld(OdometryEstimate& out);
  // kGated: outside the prior-consistency gate; kTrusted: outside, but the last
  // prior_gate_confirm scans all were (the motion sensor is what is wrong).
  enum class GateDecision { kInside, kGated, kTrusted };
  GateDecision CheckPriorGate(const OdometryEstimate& out);
  bool HoldDuringFastTurn(double score, const OdometryEstimate& out) const;
  double GateBaseRad() const;
  void FallBackToPrior(const scan_matching::Points2& points, OdometryEstimate& out);
  bool HeadingOffTheFilter();
};

namespace {

bool ResolveConfirm(LaserOdometryOptions::Confirm confirm, sensors::EntityKind kind) {
  if (confirm == LaserOdometryOptions::Confirm::kAuto) return kind == sensors::EntityKind::kHuman;
  return confirm == LaserOdometryOptions::Confirm::kAlways;
}

MotionPrior Resolve(MotionPrior prior, sensors::EntityKind kind) {
  if (prior != MotionPrior::kAuto) return prior;
  return kind == sensors::EntityKind::kHuman ? MotionPrior::kDeadReckoning : MotionPrior::kOdometry;
}

scan_matching::Points2 UsablePoints(const sensors::LaserScan& scan, const LaserOdometryOptions& o) {
  scan_matching::Points2 points = scan_matching::ScanToPoints(scan, o.min_range_m);
  std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > o.max_range_m; });
  return points;
}

// Degenerate places (a featureless corridor): the matched translation is only trusted across
// the weak direction of J^T J; along it the prior's component is kept instead of sliding. Weakly
// constrained ones (below slide_ratio) too when the match slid farther than max_slide_m along it:
// their few along-track points (floor hits moving with the person, one door frame) pulled it.
bool KeepPriorAlongWeakDirection(const Eigen::Matrix3d& information,
                                 const LaserOdometryOptions& options,
                                 const geometry::Pose2& prior, geometry::Pose2& pose) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information.topLeftCorner<2, 2>());
  const double weak = solver.eigenvalues()(0);
  const double strong = solver.eigenvalues()(1);
  if (!(strong > 0.0)) return false;
  const Eigen::Vector2d direction = solver.eigenvectors().col(0);
  const Eigen::Vector2d offset(prior.x_m - pose.x_m, prior.y_m - pose.y_m);
  const double slide_m = std::abs(direction.dot(offset));
  const bool degenerate = weak < options.degenerate_eigen_ratio * strong;
  const bool slid = weak < options.degenerate_slide_ratio * strong &&
                    slide_m > options.degenerate_max_slide_m;
  if (!degenerate && !slid) return false;
  const Eigen::Vector2d shift = direction * direction.dot(offset);
  pose.x_m += shift.x();
  pose.y_m += shift.y();
  return true;
}

}  // namespace

LaserOdometry::LaserOdometry(const LaserOdometryOptions& options, sensors::EntityKind kind,
                             const geometry::Pose2& world_from_start, double start_stamp_s)
    : impl_(std::make_unique<Impl>(internal::CheckedOptions(options),
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
  if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
    if (impl_->last_scan_stamp_s && !(scan->stamp_s > *impl_->last_scan_stamp_s)) {
      ++impl_->counts.records_ignored;  // a scan not after the previous one: time must advance
      return std::nullopt;
    }
    impl_->last_scan_stamp_s = scan->stamp_s;
    return impl_->AddScan(*scan);
  }
  if (!std::holds_alternative<sensors::GroundTruth>(record) && !impl_->motion.Add(record)) {
    ++impl_->counts.records_ignored;
  }
  return std::nullopt;
}

OdometryEstimate LaserOdometry::Impl::AddScan(const sensors::LaserScan& scan) {
  ++counts.scans;
  OdometryEstimate out;
  out.stamp_s = scan.stamp_s;
  out.world_from_prior = Predict(scan);
  poor_timing = timing.Add(scan.stamp_s);
  const scan_matching::Points2 points = UsablePoints(scan, options);
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
    Match(points, out);
  }
  out.world_from_body = estimate;
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
  return out;
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
  if (!motion_pose || !keyframe_motion_pose || local_map.empty()) {
    return geometry::Compose(estimate, increment);
  }
  if (coasting) {  // the odometry froze while the scans moved: constant velocity meanwhile
    motion_since_keyframe = geometry::Between(
        *keyframe_motion_pose, *frozen_odometry.PairedPose(motion_pose, *coasting));
    return *coasting;
  }
  motion_since_keyframe = geometry::Between(*keyframe_motion_pose, *motion_pose);
  // Anchored at the keyframe, not chained scan to scan: logged odometry often repeats a pose for
  // several scans and then jumps (mit-csail: 85 deg in one step after 1 s of zeros); chaining
  // would add that catch-up on top of the motion the matcher already found.
  return geometry::Compose(local_map.latest().world_from_body,
                           geometry::Between(*keyframe_motion_pose, *motion_pose));
}

scan_matching::MatchResult LaserOdometry::Impl::Search(const scan_matching::Points2& points,
                                                       const geometry::Pose2& prior,
                                                       OdometryEstimate& out) {
  for (;;) {
    const scan_matching::SearchWindow searched = window.Current();
    out.wide_search = out.wide_search || window.IsWide();
    scan_matching::MatchResult result =
        window.IsBase() ? matcher->MatchExhaustive(points, prior, searched)
                        : matcher->MatchBranchAndBound(points, prior, searched);
    // A low score or a best pose on the window's edge (the optimum may lie outside): search
    // again at once with a grown window, up to the wide one, before giving up on this scan.
    const bool retry = result.score < options.min_score ||
                       internal::OnWindowEdge(result.grid_pose, prior, searched);
    if (!retry || !window.Grow()) return result;
  }
}

// The gate's heading allowance before the turn fraction. With dead reckoning and
// prior_gate_gyro_sigmas > 0 it is that many standard deviations of the heading change since the
// keyframe (the heading filter's at both ends, taken as independent); it widens by itself while
// the compass is rejected or the gyro was silent. Otherwise the fixed prior_gate_rad.
double LaserOdometry::Impl::GateBaseRad() const {
  const std::optional<double>& now_rad = motion.heading_sigma_rad();
  if (!(options.prior_gate_gyro_sigmas > 0.0) || !now_rad || !keyframe_heading_sigma_rad) {
    return options.prior_gate_rad;
  }
  return options.prior_gate_gyro_sigmas * std::hypot(*now_rad, *keyframe_heading_sigma_rad);
}

// Gated scans that keep disagreeing with the prior and with each other (never trusted) mean the
// scans cannot be matched here (aliasing, floor hits): go on from the motion prior as after a
// failed match, so that the reference follows the entity instead of staying behind.
void LaserOdometry::Impl::FallBackToPrior(const scan_matching::Points2& points,
                                          OdometryEstimate& out) {
  estimate = out.world_from_prior;
  // The keyframe-anchored prior carries every keyframe's heading error along; the gyro + compass
  // heading is bounded by the compass (ff1 of team seed 1 alone: 0.5 deg RMS). Take that one.
  if (motion.mode() == MotionPrior::kDeadReckoning && motion.last_pose()) {
    estimate.theta_rad = motion.last_pose()->theta_rad;
  }
  local_map.Clear();
  TakeKeyframe(points, out);
}

// True when the matched heading has been off the gyro + compass filter's heading by more than
// heading_bound_rad for heading_bound_scans scans in a row (people only; off at 0).
bool LaserOdometry::Impl::HeadingOffTheFilter() {
  if (!(options.heading_bound_rad > 0.0) || motion.mode() != MotionPrior::kDeadReckoning ||
      !motion.last_pose()) {
    return false;
  }
  const double off_rad = geometry::NormalizeAngle(estimate.theta_rad - motion.last_pose()->theta_rad);
  heading_off_in_row = std::abs(off_rad) > options.heading_bound_rad ? heading_off_in_row + 1 : 0;
  if (heading_off_in_row < options.heading_bound_scans) return false;
  heading_off_in_row = 0;
  return true;
}

void LaserOdometry::Impl::Match(const scan_matching::Points2& points, OdometryEstimate& out) {
  geometry::Pose2 prior = out.world_from_prior;
  // The place choice: back where an earlier keyframe was taken, match against that one again.
  if (local_map.ChooseAgain(prior, out.stamp_s)) {
    matcher.emplace(options.matcher, local_map.Reference());
  }
  scan_matching::MatchResult result = Search(points, prior, out);
  if (held && result.score < options.keyframe_turn_min_score) {
    CommitHeld(out);
    prior = out.world_from_prior;
    // A failed match below restarts the local map at `estimate`: it must be the prior anchored
    // at the committed keyframe, not the one anchored at the keyframe before the hold (office
    // seed 3 at 144.25 s: that one carried a poor turn keyframe's +6 deg into the new map).
    estimate = prior;
    result = Search(points, prior, out);
  }
  if (result.score < options.min_score) {
    // The motion sensor itself may be wrong (logged odometry that froze, then jumped): try
    // constant velocity and standing still too, and keep the best-scoring hypothesis.
    for (const geometry::Pose2& alternative :
         {geometry::Compose(previous_estimate, velocity), previous_estimate}) {
      scan_matching::MatchResult other = Search(points, alternative, out);
      if (other.score > result.score) {
        result = other;
        prior = alternative;
      }
    }
  }
  counts.wide_searches += out.wide_search ? 1 : 0;
  out.score = result.score;
  if (result.score < options.min_score) {
    out.status = MatchStatus::kFailed;
    ++counts.failed;
    if (out.stale) return;  // a stale scan restarts nothing
    // Lost the reference: restart the local map from this scan at the dead-reckoning pose.
    local_map.Clear();
    TakeKeyframe(points, out);
    return;
  }
  estimate = result.reference_from_scan;
  const bool degenerate =
      KeepPriorAlongWeakDirection(result.information, options, prior, estimate);
  out.status = degenerate ? MatchStatus::kDegenerate : MatchStatus::kMatched;
  ++(degenerate ? counts.degenerate : counts.matched);
  if (out.stale) return;  // where the earlier scan was taken: output, but it anchors nothing
  const GateDecision gate = CheckPriorGate(out);
  if (gate == GateDecision::kGated) {
    out.gated = true;  // the pose is the match's, but it anchors nothing
    ++counts.gated;
    const int fallback = options.prior_gate_fallback_scans;
    if (fallback > 0 && ++gated_in_row >= fallback) FallBackToPrior(points, out);
    return;
  }
  gated_in_row = 0;
  if (HeadingOffTheFilter()) {
    ++counts.heading_resets;
    FallBackToPrior(points, out);
    return;
  }
  window.Shrink();
  const geometry::Pose2 moved = geometry::Between(local_map.latest().world_from_body, estimate);
  // A deviation trusted after prior_gate_confirm scans must re-anchor the priors at once: without
  // a keyframe here the next prior is as far off again and is gated again.
  if (gate == GateDecision::kTrusted) {
    TakeKeyframe(points, out);
    return;
  }
  if (result.score >= options.keyframe_turn_min_score) held.reset();  // the reference still holds
  if (NearAKeyframe(moved) && result.score >= options.keyframe_min_score) return;
  if (HoldDuringFastTurn(result.score, out)) {
    ++counts.turn_held;  // the pose is output; the reference waits for a better match
    held = HeldCandidate{points, estimate, frozen_odometry.PairedPose(motion.last_pose(), estimate),
                         motion.heading_sigma_rad(), poor_timing, out.stamp_s};
    return;
  }
  TakeKeyframe(points, out);
}

// The held candidate becomes the latest keyframe, and the scan being matched is predicted from
// it (the prior anchored there, as in Predict).
void LaserOdometry::Impl::CommitHeld(OdometryEstimate& out) {
  HeldCandidate candidate = std::move(*held);
  held.reset();
  AddKeyframe(candidate.points, candidate.world_from_body, candidate.poor_timing,
              candidate.stamp_s);
  keyframe_motion_pose = candidate.motion_pose;
  keyframe_heading_sigma_rad = candidate.heading_sigma_rad;
  ++counts.keyframes;
  const auto& motion_pose = motion.last_pose();
  if (!motion_pose || !keyframe_motion_pose) return;
  motion_since_keyframe = geometry::Between(*keyframe_motion_pose, *motion_pose);
  out.world_from_prior = geometry::Compose(candidate.world_from_body, *motion_since_keyframe);
}

// A poor match in a fast turn is the one most likely to be a few degrees off (the scan blurs,
// the overlap with the reference shrinks), and as a keyframe it would anchor every later prior
// and match: its heading error stays. The reference the last good match used is kept instead.
bool LaserOdometry::Impl::HoldDuringFastTurn(double score, const OdometryEstimate& out) const {
  if (!(options.keyframe_turn_rate_rad_s > 0.0) || score >= options.keyframe_turn_min_score ||
      !previous_scan_stamp_s) {
    return false;
  }
  const double interval_s =
      std::max(out.stamp_s - *previous_scan_stamp_s, options.keyframe_turn_min_interval_s);
  // The matched and the predicted rotation: logged odometry may freeze in a turn (mit-csail),
  // a poor match may be the one that under-turned.
  const double matched_rad =
      std::abs(geometry::NormalizeAngle(estimate.theta_rad - previous_estimate.theta_rad));
  const double predicted_rad = std::abs(
      geometry::NormalizeAngle(out.world_from_prior.theta_rad - previous_estimate.theta_rad));
  return std::max(matched_rad, predicted_rad) / interval_s > options.keyframe_turn_rate_rad_s;
}

// A match far from the motion prior is either an aliased optimum found by a grown window or a
// scan that does not belong to its stamp (intel: scans from a second earlier re-delivered during
// a turn on the spot). Either way it must not become a keyframe: the next priors are anchored
// there. Trusted after prior_gate_confirm in a row: then the motion sensor is what is wrong.
LaserOdometry::Impl::GateDecision LaserOdometry::Impl::CheckPriorGate(const OdometryEstimate& out) {
  if (options.prior_gate_rad <= 0.0 || !motion_since_keyframe) return GateDecision::kInside;
  const geometry::Pose2 deviation = geometry::Between(out.world_from_prior, estimate);
  const double moved_m = std::hypot(motion_since_keyframe->x_m, motion_since_keyframe->y_m);
  const double turned_rad = std::abs(geometry::NormalizeAngle(motion_since_keyframe->theta_rad));
  const double fraction_rad = motion.mode() == MotionPrior::kDeadReckoning
                                  ? options.prior_gate_fraction_gyro
                                  : options.prior_gate_fraction;
  const double allowed_rad = GateBaseRad() + fraction_rad * turned_rad;
  const double allowed_m = options.prior_gate_m + options.prior_gate_fraction * moved_m;
  const bool outside = std::abs(deviation.theta_rad) > allowed_rad ||
                       std::hypot(deviation.x_m, deviation.y_m) > allowed_m;
  if (!outside) {
    gate_confirmation.Inside();
    return GateDecision::kInside;
  }
  const int confirm = motion.mode() == MotionPrior::kDeadReckoning
                          ? options.prior_gate_confirm_gyro
                          : options.prior_gate_confirm;
  // A disturbed compass (readings being rejected) bends the gyro+compass heading while it
  // lasts: the scans' deviations then change scan to scan and must count without agreeing
  // (the disturbed-compass tests: 0.97 -> 4.9 m RMS if they have to agree).
  const bool agree = !motion.CompassRejectedWithin(out.stamp_s, options.prior_gate_compass_window_s);
  return gate_confirmation.Outside(deviation, confirm, agree) ? GateDecision::kTrusted
                                                              : GateDecision::kGated;
}

void LaserOdometry::Impl::TakeKeyframe(const scan_matching::Points2& points, OdometryEstimate& out) {
  held.reset();
  AddKeyframe(points, estimate, poor_timing, out.stamp_s);
  keyframe_motion_pose = frozen_odometry.PairedPose(motion.last_pose(), estimate);
  keyframe_heading_sigma_rad = motion.heading_sigma_rad();
  out.reference_changed = true;
  ++counts.keyframes;
}

// Within keyframe_distance_m and keyframe_angle_rad of the latest keyframe (moved: from there),
// or with keyframe_by_place and the place choice of any keyframe of the reference.
bool LaserOdometry::Impl::NearAKeyframe(const geometry::Pose2& moved) const {
  if (options.keyframe_by_place && local_map.place_choice()) {
    return local_map.Covers(estimate, options.keyframe_distance_m, options.keyframe_angle_rad);
  }
  return std::hypot(moved.x_m, moved.y_m) <= options.keyframe_distance_m &&
         std::abs(moved.theta_rad) <= options.keyframe_angle_rad;
}

void LaserOdometry::Impl::AddKeyframe(const scan_matching::Points2& points,
                                      const geometry::Pose2& world_from_body, bool bursty,
                                      double stamp_s) {
  const double max_gap_beams = bursty ? options.reference_fill_max_gap_beams_bursty
                                      : options.reference_fill_max_gap_beams;
  local_map.Add({world_from_body,
                 internal::FillReference(scan_matching::TransformPoints(world_from_body, points),
                                         world_from_body, fill_spacing_m,
                                         options.reference_fill_max_gap_m, max_gap_beams,
                                         fill_max_range_m, options.reference_fill_band_spacing_m),
                 stamp_s});
  gated_in_row = 0;
  matcher.emplace(options.matcher, local_map.Reference());
}

const OdometryCounts& LaserOdometry::counts() const { return impl_->counts; }

const dead_reckoning::DeadReckoningCounts& LaserOdometry::dead_reckoning_counts() const {
  return impl_->motion.dead_reckoning_counts();
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
