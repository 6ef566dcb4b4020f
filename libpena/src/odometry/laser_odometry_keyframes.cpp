// The keyframe and prior-gate decisions of LaserOdometry (see laser_odometry_impl.hpp): when a
// match may anchor later priors, when it is gated, and how a keyframe enters the reference.
#include <Eigen/Geometry>
#include <cmath>

#include "laser_odometry_impl.hpp"
#include "pose_covariance.hpp"
#include "reference_fill.hpp"

namespace pena::odometry {

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
                       options.prior_gate_rad + fraction_rad * turned_rad};
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

LaserOdometry::Impl::GateDecision LaserOdometry::Impl::CheckPriorGate(OdometryEstimate& out) {
  if (motion.mode() == MotionPrior::kOdometry && motion_since_keyframe) {
    const Eigen::Matrix3d match_covariance = internal::MatchCovariance(
        match_information, 0.5 * std::max(last_searched.size_x_m, last_searched.size_y_m),
        0.5 * last_searched.size_theta_rad, options.covariance);
    out.innovation_nees = internal::ComputeInnovation(out.world_from_prior, estimate,
                                                      *motion_since_keyframe, match_covariance,
                                                      options.covariance)
                              .nees;
  }
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
  // lasts: then the heading it gives is no evidence against the scans.
  const bool compass_held =
      !motion.CompassRejectedWithin(out.stamp_s, options.prior_gate_compass_window_s);
  if (compass_held && OffTheGyroHeading()) {
    gate_confirmation.Inside();  // no evidence against the motion sensor: the run is over
    return GateDecision::kRefused;
  }
  return gate_confirmation.Outside(confirm) ? GateDecision::kTrusted : GateDecision::kGated;
}

// The place choice's reference is small when the entity drives on (3-4 keyframes where
// recency keeps 8); at mit-csail's turn ends and odometry freezes it matched at 0.40-0.44 where
// the recency reference matched at 0.76-0.83, and the poor match became a keyframe. Filling it
// everywhere loses the place choice's gain on intel and aces, so only here.
scan_matching::MatchResult LaserOdometry::Impl::SearchFilled(
    const scan_matching::Points2& points, const geometry::Pose2& prior,
    const internal::WindowScale& window_before, scan_matching::MatchResult first,
    OdometryEstimate& out) {
  std::optional<Timed> timed(std::in_place, clock, OdometryStage::kReference);
  std::optional<scan_matching::Points2> filled = local_map.FilledReference();
  if (!filled) return first;
  const internal::WindowScale window_after = window;
  std::optional<scan_matching::CorrelationScanMatcher> chosen = std::move(matcher);
  matcher.emplace(options.matcher, *filled);
  timed.reset();
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
  AddKeyframe(points, estimate, poor_timing, out.stamp_s, covariance);
  keyframe_from_this_scan = true;
  keyframe_motion_pose = frozen_odometry.PairedPose(motion.last_pose(), estimate);
  out.reference_changed = true;
  ++counts.keyframes;
}

bool LaserOdometry::Impl::NearAKeyframe(const geometry::Pose2& moved) const {
  return std::hypot(moved.x_m, moved.y_m) <= options.keyframe_distance_m &&
         std::abs(moved.theta_rad) <= options.keyframe_angle_rad;
}

void LaserOdometry::Impl::AddKeyframe(const scan_matching::Points2& points,
                                      const geometry::Pose2& world_from_body, bool bursty,
                                      double stamp_s, const Eigen::Matrix3d& keyframe_covariance) {
  const Timed timed(clock, OdometryStage::kReference);
  const double max_gap_beams = bursty ? options.reference_fill_max_gap_beams_bursty
                                      : options.reference_fill_max_gap_beams;
  local_map.Add({world_from_body,
                 internal::FillReference(scan_matching::TransformPoints(world_from_body, points),
                                         world_from_body, fill_spacing_m,
                                         options.reference_fill_max_gap_m, max_gap_beams),
                 stamp_s, keyframe_covariance});
  matcher.emplace(options.matcher, local_map.Reference());
}


}  // namespace pena::odometry
