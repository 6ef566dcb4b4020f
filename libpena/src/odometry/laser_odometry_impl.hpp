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
#include "innovation.hpp"
#include "interlace_evidence.hpp"
#include "local_map.hpp"
#include "motion_tracker.hpp"
#include "pace_check.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "search_window.hpp"
#include "stale_scan.hpp"
#include "weak_direction.hpp"

namespace pena::odometry {
namespace internal {

inline WeakDirectionOptions WeakDirectionOf(const LaserOdometryOptions& o) {
  return {o.degenerate_eigen_ratio,          o.degenerate_slide_ratio,        o.degenerate_max_slide_m,
          o.degenerate_slide_backward_only, o.degenerate_slide_max_across_m, o.degenerate_slide_prior_agreed_m};
}

inline PlaceChoice PlaceChoiceOf(const LaserOdometryOptions& o) {
  return {o.local_map_pool_keyframes, o.local_map_pool_age_s, o.local_map_recent_keyframes,
          o.local_map_place_radius_m, o.keyframe_distance_m, o.keyframe_angle_rad};
}

}  // namespace internal

struct LaserOdometry::Impl {
  Impl(const LaserOdometryOptions& checked, MotionPrior mode, bool confirm,
       const geometry::Pose2& world_from_start, double start_stamp_s)
      : options(checked),
        motion(mode, checked.dead_reckoning, world_from_start, start_stamp_s),
        local_map(checked.local_map_keyframes, 2.0 * checked.matcher.threshold_m, confirm,
                  internal::PlaceChoiceOf(checked)),
        window(checked),
        stale_scans(checked.stale_history_scans, checked.stale_repeat_m, checked.stale_changed_m),
        timing(checked.timing_burst_gap_s, checked.timing_burst_fraction,
               checked.timing_burst_window_scans),
        fill_spacing_m(confirm ? 0.0 : checked.reference_fill_spacing_m),
        estimate(world_from_start),
        previous_estimate(world_from_start),
        frozen_odometry(  // robots' wheel odometry only
            mode == MotionPrior::kOdometry ? checked.frozen_odometry_min_turn_rad : 0.0,
            mode == MotionPrior::kOdometry ? checked.frozen_odometry_min_move_m : 0.0),
        weak_check(internal::WeakDirectionOf(checked)),
        pace_check({mode == MotionPrior::kDeadReckoning &&
                            checked.dead_reckoning.stride_interpolation.enabled
                        ? checked.pace_check_tolerance
                        : 0.0,
                    checked.pace_check_window_m}) {}

  LaserOdometryOptions options;
  internal::MotionTracker motion;
  internal::LocalMap local_map;
  std::optional<scan_matching::CorrelationScanMatcher> matcher;  // built from local_map
  internal::WindowScale window;
  internal::StaleScanDetector stale_scans;
  internal::BurstTiming timing;
  bool poor_timing = false;  // scans arrive in bursts now: keyframes keep the bursty fill limit
  // Keyframes are densified only where no floor or ceiling hit can be: with a tilting body-worn
  // laser (reference confirmation) filled floor-hit streaks would confirm each other.
  double fill_spacing_m;
  geometry::Pose2 estimate;
  // The motion sensor's pose at the latest keyframe: priors are anchored there (see Predict).
  std::optional<geometry::Pose2> keyframe_motion_pose;
  // The weak direction of this scan's match when it was degenerate or held by the pace check
  // (world frame): the covariance takes the prior's variance along it.
  std::optional<Eigen::Vector2d> match_weak_direction;
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
  bool fell_back = false;     // this scan's match was refused: it is output at the prior
  // The motion sensor's motion since the latest keyframe (nullopt without a sensor pose): the
  // prior-consistency gate's allowance grows with it.
  std::optional<geometry::Pose2> motion_since_keyframe;
  internal::GateConfirmation gate_confirmation;
  internal::InterlaceEvidence interlace_evidence;  // one sweep or the configured interlace
  internal::FrozenOdometry frozen_odometry;  // wheel odometry only (frozen_odometry_*)
  std::optional<double> last_scan_stamp_s;
  std::optional<double> previous_scan_stamp_s;  // of the scan before the one being added
  internal::WeakDirection weak_check;  // degenerate and slid matches keep the prior along the weak direction
  // People with spread strides (pace_check_*): the raw stream moves in whole strides, a pace
  // over a few metres is off by up to one.
  internal::PaceCheck pace_check;
  OdometryCounts counts;
  // Where Add's time goes (stage_times()); mutable: the const searches are timed too.
  mutable StageClock<OdometryStage> clock;
  using Timed = StageClock<OdometryStage>::Scope;

  OdometryEstimate AddScan(const sensors::LaserScan& scan);
  // This scan's covariance; the keyframe's too when it became one.
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
  // previous scan of the prior, then of each match of the points (deskew_match_passes); with
  // the interlace the evidence supports (interlace_evidence).
  scan_matching::Points2 MidSweepPoints(const sensors::LaserScan& logged, const OdometryEstimate& out);
  // The best match of `points` around `around` in the current window (current_window) or the
  // base one, or nullopt without a reference or a match scoring min_score.
  std::optional<geometry::Pose2> MatchForDeskew(const scan_matching::Points2& points,
                                                const geometry::Pose2& around,
                                                bool current_window) const;
  void Match(const scan_matching::Points2& points, OdometryEstimate& out);
  // One search of the matcher (exhaustive or branch and bound), timed as `stage`; a max-grid
  // build goes to kReference, except in deskew (whose matches are all its own).
  scan_matching::MatchResult RunMatcher(const scan_matching::Points2& points,
                                        const geometry::Pose2& around,
                                        const scan_matching::SearchWindow& searched,
                                        bool exhaustive, OdometryStage stage,
                                        scan_matching::Polish polish = scan_matching::Polish::kRefine) const;
  // pace_check_*: a weakly constrained match that fell behind the walk keeps the prior along it.
  void CheckPace(const Eigen::Matrix3d& information, const geometry::Pose2& prior);
  // The window regrowth around one prior; the result is the best grid pose, not yet refined.
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
  // Within keyframe_distance_m and keyframe_angle_rad of the latest keyframe (moved: from there).
  bool NearAKeyframe(const geometry::Pose2& moved) const;
  // kGated: outside the prior-consistency gate; kRefused: outside and far off the gyro + compass
  // heading (prior_gate_refuse_gyro_rad: aliased, output at the prior); kTrusted: outside, but
  // the last prior_gate_confirm scans all were (the motion sensor is what is wrong).
  enum class GateDecision { kInside, kGated, kRefused, kTrusted };
  // Also sets out.innovation_nees for wheel odometry (innovation.hpp).
  GateDecision CheckPriorGate(OdometryEstimate& out);
  bool OffTheGyroHeading() const;
  // How far a match may deviate from the prior before the gate holds it (nullopt: no gate now).
  struct GateAllowance {
    double m = 0.0;
    double rad = 0.0;
  };
  std::optional<GateAllowance> PriorGateAllowance() const;
};

}  // namespace pena::odometry
