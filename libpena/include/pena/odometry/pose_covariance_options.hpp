#pragma once
// How the laser odometry's pose covariance grows (odometry::internal pose_covariance.hpp,
// docs/odometry.md "Pose covariance"); a field of LaserOdometryOptions.

namespace pena::odometry {

// The covariance of world_from_body (x_m, y_m, theta_rad) is that of what the scan was placed
// against, carried to the scan (heading uncertainty times the lever arm): a matched scan the
// reference keyframes' (weighted by their points), an unmatched one the pose its prior was
// composed from (the latest keyframe, or the previous scan). To that it adds the step's own: the
// match's where the scan was matched; the motion prior's drift (with a person's stride not yet
// reported) along a degenerate direction and where it was not matched; and the disagreement with
// the prior along a weak direction and where the match left the prior's gate. Odometry never
// closes loops, so it does not shrink. Checked by the LaserOdometry constructor.
struct PoseCovarianceOptions {
  // The motion prior's drift between keyframes: variance per metre moved (both axes), per metre
  // and per radian turned (heading). m / sqrt(m), rad / sqrt(m), rad / sqrt(rad).
  double motion_m_per_sqrt_m = 0.05;
  double motion_rad_per_sqrt_m = 0.01;
  double motion_rad_per_sqrt_rad = 0.03;
  // A match: residual_sd_m^2 (J^T J)^-1 of its point-to-line residuals, plus these floors (the
  // residuals of neighbouring points are correlated, so J^T J alone is far too confident).
  double match_residual_sd_m = 0.03;
  double match_min_sd_m = 0.01;
  double match_min_sd_rad = 0.002;
  // The share of the squared disagreement (match minus prior) added when the gate trusts the
  // scans after prior_gate_confirm: the scans were right in 24 of 33 trusts over ten simulated
  // missions, and a two-way choice right with p = 0.73 has variance p (1 - p) = 0.2 of it,
  // rounded up to a quarter.
  double gate_trusted_disagreement_share = 0.25;
  // Along a weakly constrained direction (its J^T J eigenvalue below weak_ratio times the
  // strongest: a corridor's axis) a match that disagrees with the prior may be the wrong one:
  // this share of the squared disagreement along it is added. 0 turns it off.
  double weak_ratio = 0.2;
  double weak_disagreement_share = 1.0;
};

}  // namespace pena::odometry
