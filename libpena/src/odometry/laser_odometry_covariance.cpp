// The laser odometry's pose covariance (PoseCovarianceOptions, docs/odometry.md "Pose
// covariance"): what each scan's estimate inherits and what its own step adds.
#include <algorithm>
#include <optional>

#include "laser_odometry_impl.hpp"
#include "pose_covariance.hpp"

namespace pena::odometry {

void LaserOdometry::Impl::UpdateCovariance(const OdometryEstimate& out) {
  const PoseCovarianceOptions& o = options.covariance;
  // The start defines the frame (zero); unmatched scans (the first, failed, empty, prior only,
  // fallen back to the prior) add the motion prior's drift from the pose it was composed from.
  // A person's prior also lags by the stride in progress (the sensor reports it when it ends).
  Eigen::Matrix3d drift =
      internal::MotionCovariance(geometry::Between(prior_anchor, out.world_from_prior), o);
  drift.topLeftCorner<2, 2>() += motion.pending_position_covariance();
  const bool matched =
      !fell_back && (out.status == MatchStatus::kMatched || out.status == MatchStatus::kDegenerate);
  if (!matched) {
    covariance = internal::CarryCovariance(prior_anchor_covariance, prior_anchor, estimate) + drift;
  } else {
    // A match is bounded by the window it was searched in and, unless it left the gate (below),
    // by the gate around the prior.
    double bound_m = 0.5 * std::max(last_searched.size_x_m, last_searched.size_y_m);
    double bound_rad = 0.5 * last_searched.size_theta_rad;
    if (const std::optional<GateAllowance> gate = PriorGateAllowance()) {
      bound_m = std::min(bound_m, gate->m);
      bound_rad = std::min(bound_rad, gate->rad);
    }
    Eigen::Matrix3d step = internal::MatchCovariance(match_information, bound_m, bound_rad, o);
    if (match_weak_direction) {
      const Eigen::Vector2d& weak = *match_weak_direction;
      step = internal::WithVarianceAlong(step, weak, weak.dot(drift.topLeftCorner<2, 2>() * weak));
    } else {
      step += internal::WeakDisagreementCovariance(match_information, estimate,
                                                   out.world_from_prior, o);
    }
    // Outside the prior's gate the scans and the motion sensor disagree, and either may be off:
    // wholly while gated (the pose anchors nothing), by the trusted share once trusted.
    const Eigen::Matrix3d disagreement =
        internal::DisagreementCovariance(estimate, out.world_from_prior);
    if (out.gated) step += disagreement;
    if (gate_trusted) step += o.gate_trusted_disagreement_share * disagreement;
    covariance = match_reference_covariance + step;
  }
  if (keyframe_from_this_scan) local_map.SetLatestCovariance(covariance);
}

Eigen::Matrix3d LaserOdometry::Impl::ReferenceCovariance(
    const geometry::Pose2& world_from_body) const {
  const Timed timed(clock, OdometryStage::kCovariance);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  double weight = 0.0;
  for (const internal::Keyframe* keyframe : local_map.ReferenceKeyframes()) {
    const double points = static_cast<double>(keyframe->points_world.size());
    sum += points * internal::CarryCovariance(keyframe->covariance, keyframe->world_from_body,
                                              world_from_body);
    weight += points;
  }
  return weight > 0.0 ? (sum / weight).eval() : sum;
}

}  // namespace pena::odometry
