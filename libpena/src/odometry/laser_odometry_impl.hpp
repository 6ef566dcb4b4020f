#pragma once
// LaserOdometry's state (internal): the facade's steps are in laser_odometry.cpp, the keyframe
// and prior-gate decisions in laser_odometry_keyframes.cpp.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "burst_timing.hpp"
#include "frozen_odometry.hpp"
#include "gate_confirmation.hpp"
#include "local_map.hpp"
#include "motion_tracker.hpp"
#include "pace_check.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "search_window.hpp"
#include "stale_scan.hpp"
#include "walker_fixed_points.hpp"
#include "weak_direction.hpp"
#include "seen_through_points.hpp"

namespace pena::odometry {
namespace internal {

inline WeakDirectionOptions WeakDirectionOf(const LaserOdometryOptions& o) {
  return {o.degenerate_eigen_ratio,          o.degenerate_slide_ratio,        o.degenerate_max_slide_m,
          o.degenerate_slide_backward_only, o.degenerate_slide_max_across_m, o.degenerate_slide_prior_agreed_m};
}

inline PlaceChoice PlaceChoiceOf(const LaserOdometryOptions& o) {
  return {o.local_map_pool_keyframes, o.local_map_pool_age_s, o.local_map_recent_keyframes,
          o.local_map_place_radius_m, o.keyframe_distance_m, o.keyframe_angle_rad,
          o.local_map_place_fill_recent};
}

}  // namespace internal

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
                  wall_only_range_m, internal::PlaceChoiceOf(checked)),
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
            mode == MotionPrior::kOdometry ? checked.frozen_odometry_min_move_m : 0.0),
        walker_fixed(checked.walker_fixed_points),  // checked even when off
        drop_walker_fixed(checked.drop_walker_fixed_points && mode == MotionPrior::kDeadReckoning),
        drop_seen_through(checked.drop_seen_through_points && mode == MotionPrior::kDeadReckoning),
        weak_check(internal::WeakDirectionOf(checked)),
        pace_check({mode == MotionPrior::kDeadReckoning &&
                            checked.dead_reckoning.stride_interpolation.enabled
                        ? checked.pace_check_tolerance
                        : 0.0,
                    checked.pace_check_window_m}) {}

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
  double keyframe_motion_stamp_s = 0.0;  // when keyframe_motion_pose was taken
  std::optional<double> keyframe_heading_sigma_rad;  // the heading filter's there (dead reckoning)
  // keyframe_stride_jump_across_weak: the weak direction of the scan being added when its match
  // was degenerate (world frame), and of the latest keyframe's match (motion sensor's frame).
  std::optional<Eigen::Vector2d> match_weak_direction;
  std::optional<Eigen::Vector2d> keyframe_weak_direction;
  geometry::Pose2 previous_estimate;  // at the previous scan
  geometry::Pose2 velocity;           // estimated motion over the previous scan interval
  // Of `estimate` (PoseCovarianceOptions); zero at the start. Keyframes keep theirs.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // The pose this scan's prior was composed from (the latest keyframe, or the previous scan) and
  // its covariance: what an unmatched scan's covariance grows from (set by Predict).
  geometry::Pose2 prior_anchor;
  Eigen::Matrix3d prior_anchor_covariance = Eigen::Matrix3d::Zero();
  // A match inherits the covariance of the reference it was matched against (ReferenceCovariance).
  Eigen::Matrix3d match_reference_covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d match_information = Eigen::Matrix3d::Zero();  // J^T J of this scan's match
  bool keyframe_from_this_scan = false;  // its covariance is set once UpdateCovariance knows it
  scan_matching::SearchWindow last_searched;  // the window of the latest search (bounds a match)
  bool gate_trusted = false;  // this scan's match was trusted after prior_gate_confirm
  bool fell_back = false;     // this scan's match was dropped for the prior (FallBackToPrior)
  // The motion sensor's motion since the latest keyframe (nullopt without a sensor pose): the
  // prior-consistency gate's allowance grows with it.
  std::optional<geometry::Pose2> motion_since_keyframe;
  internal::GateConfirmation gate_confirmation;
  internal::FrozenOdometry frozen_odometry;  // wheel odometry only (frozen_odometry_*)
  int gated_in_row = 0;  // gated scans since the last keyframe (see prior_gate_fallback_scans)
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
    std::optional<Eigen::Vector2d> weak_direction;  // as keyframe_weak_direction
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // the held scan's (UpdateCovariance)
  };
  std::optional<HeldCandidate> held;
  // drop_walker_fixed_points (people's dead reckoning only): the previous scan's usable returns
  // (laser frame, beam order) and the dead reckoning's motion since it, stride jumps taken out.
  internal::WalkerFixedPoints walker_fixed;
  bool drop_walker_fixed;
  bool drop_seen_through;
  internal::SeenThroughPoints seen_through;
  scan_matching::Points2 previous_points;
  geometry::Pose2 smooth_increment;
  internal::WeakDirection weak_check;  // degenerate and slid matches keep the prior along the weak direction
  // People with spread strides (pace_check_*): the raw stream moves in whole strides, a pace
  // over a few metres is off by up to one.
  internal::PaceCheck pace_check;
  OdometryCounts counts;

  OdometryEstimate AddScan(const sensors::LaserScan& scan);
  // This scan's covariance; the keyframe's and the held candidate's too when it became one.
  void UpdateCovariance(const OdometryEstimate& out);
  // The reference keyframes' covariances carried to `world_from_body`, weighted by their points:
  // the match aligns the scan with all of them at once. (The weighted mean bounds the covariance
  // of the weighted mean of their errors however those are correlated.)
  Eigen::Matrix3d ReferenceCovariance(const geometry::Pose2& world_from_body) const;
  geometry::Pose2 Predict(const sensors::LaserScan& scan);
  // The time between this scan and the previous one that deskew divides a turn by (the mean
  // interval where the stamps are delivery times), or nullopt where deskew does not apply.
  std::optional<double> DeskewInterval(const sensors::LaserScan& scan) const;
  // The scan's usable points, turned to mid-sweep where deskew applies: by the turn since the
  // previous scan of the prior, then of each match of the points (deskew_match_passes).
  scan_matching::Points2 MidSweepPoints(const sensors::LaserScan& scan, const OdometryEstimate& out);
  // The best match of `points` around `around` in the current window (current_window) or the
  // base one, or nullopt without a reference or a match scoring min_score.
  std::optional<geometry::Pose2> MatchForDeskew(const scan_matching::Points2& points,
                                                const geometry::Pose2& around,
                                                bool current_window) const;
  // drop_walker_fixed_points: `points` without the returns that move with the body.
  scan_matching::Points2 DropWalkerFixed(scan_matching::Points2 points);
  // keyframe_absorbs_stride_jumps: moves the keyframe's (and a held candidate's) motion pose.
  void AbsorbStrideJumps();
  // The part of the jumps since the previous scan that a motion pose taken at stamp_s absorbs.
  Eigen::Vector2d StrideJumpAbsorbedM(double stamp_s) const;
  // match_weak_direction turned into the frame of motion_pose (paired with `estimate`); nullopt
  // unless keyframe_stride_jump_across_weak is on and the match was degenerate.
  std::optional<Eigen::Vector2d> WeakDirectionInMotionFrame(
      const std::optional<geometry::Pose2>& motion_pose) const;
  void Match(const scan_matching::Points2& points, OdometryEstimate& out);
  // pace_check_*: a weakly constrained match that fell behind the walk keeps the prior along it.
  void CheckPace(const Eigen::Matrix3d& information, const geometry::Pose2& prior);
  scan_matching::MatchResult Search(const scan_matching::Points2& points,
                                    const geometry::Pose2& prior, OdometryEstimate& out);
  // local_map_place_fill_below_score: `first` (searched from `window_before`) against the
  // reference with the free slots filled; the better of the two.
  scan_matching::MatchResult SearchFilled(const scan_matching::Points2& points,
                                          const geometry::Pose2& prior,
                                          const internal::WindowScale& window_before,
                                          scan_matching::MatchResult first, OdometryEstimate& out);
  bool FillWhileFrozen() const;
  void TakeKeyframe(const scan_matching::Points2& points, OdometryEstimate& out);
  void AddKeyframe(const scan_matching::Points2& points, const geometry::Pose2& world_from_body,
                   bool bursty, double stamp_s, const Eigen::Matrix3d& covariance);
  bool NearAKeyframe(const geometry::Pose2& moved) const;
  void CommitHeld(OdometryEstimate& out);
  // kGated: outside the prior-consistency gate; kRefused: outside and far off the gyro + compass
  // heading (prior_gate_refuse_gyro_rad: aliased, output at the prior); kTrusted: outside, but
  // the last prior_gate_confirm scans all were (the motion sensor is what is wrong).
  enum class GateDecision { kInside, kGated, kRefused, kTrusted };
  GateDecision CheckPriorGate(const OdometryEstimate& out);
  bool OffTheGyroHeading() const;
  bool HoldDuringFastTurn(double score, const OdometryEstimate& out) const;
  double GateBaseRad() const;
  // How far a match may deviate from the prior before the gate holds it (nullopt: no gate now).
  struct GateAllowance {
    double m = 0.0;
    double rad = 0.0;
  };
  std::optional<GateAllowance> PriorGateAllowance() const;
  void FallBackToPrior(const scan_matching::Points2& points, OdometryEstimate& out);
};

}  // namespace pena::odometry
