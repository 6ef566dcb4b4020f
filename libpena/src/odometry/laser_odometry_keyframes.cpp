// The keyframe and prior-gate decisions of LaserOdometry (see laser_odometry_impl.hpp): when a
// match may anchor later priors, when it is held or gated, and how a keyframe enters the
// reference.
#include <Eigen/Geometry>
#include <cmath>

#include "laser_odometry_impl.hpp"
#include "reference_fill.hpp"

namespace pena::odometry {

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
  fell_back = true;  // its covariance is the prior's, not the match's
  match_weak_direction.reset();  // the keyframe is the prior's in every direction
  // The keyframe-anchored prior carries every keyframe's heading error along; the gyro + compass
  // heading is bounded by the compass (ff1 of team seed 1 alone: 0.5 deg RMS). Take that one.
  if (motion.mode() == MotionPrior::kDeadReckoning && motion.last_pose()) {
    estimate.theta_rad = motion.last_pose()->theta_rad;
  }
  local_map.Clear();
  TakeKeyframe(points, out);
}

void LaserOdometry::Impl::AbsorbStrideJumps() {
  // The poses paired with the keyframe (and with a held candidate that may become one) were
  // taken before the jump: moved with it, the motion since them leaves the corrected guess out.
  // Along a degenerate match's weak direction the pose is the prior's, extrapolation included:
  // there the jump is motion since it (keyframe_stride_jump_across_weak).
  auto absorb = [this](std::optional<geometry::Pose2>& pose, double stamp_s,
                       const std::optional<Eigen::Vector2d>& weak_direction) {
    if (!pose) return;
    Eigen::Vector2d jump_m = StrideJumpAbsorbedM(stamp_s);
    if (weak_direction) jump_m -= *weak_direction * weak_direction->dot(jump_m);
    pose->x_m += jump_m.x();
    pose->y_m += jump_m.y();
  };
  absorb(keyframe_motion_pose, keyframe_motion_stamp_s, keyframe_weak_direction);
  if (held) absorb(held->motion_pose, held->stamp_s, held->weak_direction);
}

std::optional<Eigen::Vector2d> LaserOdometry::Impl::WeakDirectionInMotionFrame(
    const std::optional<geometry::Pose2>& motion_pose) const {
  if (!options.keyframe_stride_jump_across_weak || !match_weak_direction || !motion_pose) {
    return std::nullopt;
  }
  return Eigen::Rotation2Dd(motion_pose->theta_rad - estimate.theta_rad) * *match_weak_direction;
}

Eigen::Vector2d LaserOdometry::Impl::StrideJumpAbsorbedM(double stamp_s) const {
  if (!options.keyframe_stride_jump_share) return motion.stride_jump_m();
  // Only what the pose had accrued of the corrected stride by its stamp: a keyframe taken just
  // after a report held almost none of the next stride's guess, and the rest was walked since.
  Eigen::Vector2d share_m = Eigen::Vector2d::Zero();
  for (const dead_reckoning::StrideJump& jump : motion.stride_jumps()) {
    share_m += jump.ShareAt(stamp_s);
  }
  return share_m;
}

// The held candidate becomes the latest keyframe, and the scan being matched is predicted from
// it (the prior anchored there, as in Predict).
void LaserOdometry::Impl::CommitHeld(OdometryEstimate& out) {
  HeldCandidate candidate = std::move(*held);
  held.reset();
  AddKeyframe(candidate.points, candidate.world_from_body, candidate.poor_timing,
              candidate.stamp_s, candidate.covariance);
  keyframe_motion_pose = candidate.motion_pose;
  keyframe_motion_stamp_s = candidate.stamp_s;
  keyframe_heading_sigma_rad = candidate.heading_sigma_rad;
  keyframe_weak_direction = candidate.weak_direction;
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
std::optional<LaserOdometry::Impl::GateAllowance> LaserOdometry::Impl::PriorGateAllowance() const {
  if (options.prior_gate_rad <= 0.0 || !motion_since_keyframe) return std::nullopt;
  const double moved_m = std::hypot(motion_since_keyframe->x_m, motion_since_keyframe->y_m);
  const double turned_rad = std::abs(geometry::NormalizeAngle(motion_since_keyframe->theta_rad));
  const double fraction_rad = motion.mode() == MotionPrior::kDeadReckoning
                                  ? options.prior_gate_fraction_gyro
                                  : options.prior_gate_fraction;
  return GateAllowance{options.prior_gate_m + options.prior_gate_fraction * moved_m,
                       GateBaseRad() + fraction_rad * turned_rad};
}

// Against the filter's own heading, not the prior's: the prior carries the keyframes' heading
// errors, which a right match has to correct.
bool LaserOdometry::Impl::OffTheGyroHeading() const {
  const double refuse_rad = options.prior_gate_refuse_gyro_rad;
  if (refuse_rad <= 0.0 || motion.mode() != MotionPrior::kDeadReckoning || !motion.last_pose()) {
    return false;
  }
  return std::abs(geometry::NormalizeAngle(estimate.theta_rad - motion.last_pose()->theta_rad)) >
         refuse_rad;
}

LaserOdometry::Impl::GateDecision LaserOdometry::Impl::CheckPriorGate(const OdometryEstimate& out) {
  const std::optional<GateAllowance> allowed = PriorGateAllowance();
  if (!allowed) return GateDecision::kInside;
  const geometry::Pose2 deviation = geometry::Between(out.world_from_prior, estimate);
  const bool outside = std::abs(deviation.theta_rad) > allowed->rad ||
                       std::hypot(deviation.x_m, deviation.y_m) > allowed->m;
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
  if (agree && OffTheGyroHeading()) {
    gate_confirmation.Inside();  // no evidence against the motion sensor: the run is over
    return GateDecision::kRefused;
  }
  return gate_confirmation.Outside(deviation, confirm, agree) ? GateDecision::kTrusted
                                                              : GateDecision::kGated;
}

// The place choice's reference is small when the entity drives on (3-4 keyframes where
// recency keeps 8); at mit-csail's turn ends and odometry freezes it matched at 0.40-0.44 where
// the recency reference matched at 0.76-0.83, and the poor match became a keyframe. Filling it
// everywhere loses the place choice's gain on intel and aces (session 11), so only here.
scan_matching::MatchResult LaserOdometry::Impl::SearchFilled(
    const scan_matching::Points2& points, const geometry::Pose2& prior,
    const internal::WindowScale& window_before, scan_matching::MatchResult first,
    OdometryEstimate& out) {
  std::optional<scan_matching::Points2> filled = local_map.FilledReference();
  if (!filled) return first;
  const internal::WindowScale window_after = window;
  std::optional<scan_matching::CorrelationScanMatcher> chosen = std::move(matcher);
  matcher.emplace(options.matcher, *filled);
  window = window_before;
  scan_matching::MatchResult other = Search(points, prior, out);
  if (other.score > first.score) {
    local_map.FillFreeSlots();  // the reference the kept match used
    return other;
  }
  matcher = std::move(chosen);
  window = window_after;
  return first;
}

// While the wheel odometry is frozen and local_map_place_fill_frozen_scans scans after.
bool LaserOdometry::Impl::FillWhileFrozen() const {
  const std::optional<int> scans = frozen_odometry.scans_since_frozen();
  return options.local_map_place_fill_frozen_scans > 0 && scans &&
         *scans <= options.local_map_place_fill_frozen_scans;
}

void LaserOdometry::Impl::TakeKeyframe(const scan_matching::Points2& points, OdometryEstimate& out) {
  held.reset();
  AddKeyframe(points, estimate, poor_timing, out.stamp_s, covariance);
  keyframe_from_this_scan = true;
  keyframe_motion_pose = frozen_odometry.PairedPose(motion.last_pose(), estimate);
  keyframe_motion_stamp_s = out.stamp_s;
  keyframe_heading_sigma_rad = motion.heading_sigma_rad();
  keyframe_weak_direction = WeakDirectionInMotionFrame(keyframe_motion_pose);
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
                                      double stamp_s, const Eigen::Matrix3d& keyframe_covariance) {
  const double max_gap_beams = bursty ? options.reference_fill_max_gap_beams_bursty
                                      : options.reference_fill_max_gap_beams;
  local_map.Add({world_from_body,
                 internal::FillReference(scan_matching::TransformPoints(world_from_body, points),
                                         world_from_body, fill_spacing_m,
                                         options.reference_fill_max_gap_m, max_gap_beams,
                                         fill_max_range_m, options.reference_fill_band_spacing_m),
                 stamp_s, keyframe_covariance});
  gated_in_row = 0;
  matcher.emplace(options.matcher, local_map.Reference());
}


}  // namespace pena::odometry
