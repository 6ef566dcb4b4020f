#pragma once
// The per-entity laser odometry of the paper (section 2): predict with dead reckoning (or wheel
// odometry), match the scan against a reference built from recent scans, correct the pose, and
// change the reference when the entity has moved on. One call per sensor record.

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/odometry/pose_covariance_options.hpp"
#include "pena/odometry/walker_fixed_points_options.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"

namespace pena::odometry {

// Where the motion prior between scans comes from.
enum class MotionPrior {
  kAuto,           // dead reckoning for people, wheel odometry for robots (or the scans' own)
  kDeadReckoning,  // gyro + compass + stride (human)
  kStrideOnly,     // strides along the last estimated heading, no gyro or compass (wide window)
  kOdometry,       // wheel odometry records or the scans' odometry poses
  kNone,           // no motion sensor: zero motion, wide window
};

// Options of the whole chain; validated by the constructor (messages name the field and unit).
struct LaserOdometryOptions {
  MotionPrior motion_prior = MotionPrior::kAuto;
  bool match_scans = true;  // false: dead reckoning / odometry alone (for comparison)
  dead_reckoning::HumanDeadReckoningOptions dead_reckoning;
  scan_matching::CorrelationMatcherOptions matcher;
  scan_matching::SearchWindow window;          // the paper's window, used after good matches
  scan_matching::SearchWindow wide_window{0.80, 0.60, 1.3962634015954636, 0.02,
                                          0.008726646259971648};  // 80 cm x 60 cm x 80 deg
  double window_growth = 2.0;      // window factor after a failed match (up to wide_window)
  double min_score = 0.4;          // eq. 2 score below which a match has failed
  double min_range_m = 0.1;        // closer returns are the carrier's own body
  double max_range_m = 40.0;       // farther returns are too sparse to match on
  // Scans that take time (LaserGeometry::sweep_s > 0: the CARMEN logs' SICK lasers) are turned
  // to mid-sweep by the rotation rate since the previous scan (the prior's, then the matched
  // turn's: deskew_match_passes) before they are matched or kept
  // (scan_matching::ScanToPointsAtMidSweep). A robot wiggling at 60 deg/s turns 0.4 deg
  // during one sweep; uncorrected, that was mit-csail's heading drift of 3-7 deg over its loop
  // (docs/odometry.md, "Scan deskew"). Not when the scans are closer than deskew_min_interval_s.
  bool deskew_scans = true;
  double deskew_min_interval_s = 0.05;
  // Scans that arrive in bursts (stamps that are delivery times: intel) are deskewed too, with
  // the mean interval between scans as the time the turn took; off, they are matched as taken
  // at once. Intel's long relations lost 1.8 deg of heading that way (docs/odometry.md,
  // "Deskew by the matched turn").
  bool deskew_bursty_scans = true;
  // The prior's rate is the motion sensor's, and a logged odometry may not be in step with the
  // laser: mit-csail's odometry turns match the scans' turns best 0.1 s earlier (docs/odometry.md,
  // "Deskew by the matched turn"). So the deskewed scan is matched this many times, and each
  // match's turn since the previous scan gives the rate for the next deskew (0: the prior's).
  // The first pass searches as the match will; later ones search the base window only.
  int deskew_match_passes = 2;
  // Fewer usable points than this: no match, the prior is kept (kNoPoints). A laser going blind
  // (smoke in the office scenario) gives scans of 10-20 points first, and a wide search on so few
  // finds a high-scoring wrong heading (office seed 4: 18 deg off, kept for the rest of the run).
  int min_match_points = 30;
  // The reference: a local map of the last keyframes, changed when the entity has moved far.
  // kAutoLocalMapKeyframes: kShortLocalMapKeyframes for robots, kLongLocalMapKeyframes for
  // people, as `pena map` runs it. A person's keyframes come every 0.5 m along corridors whose
  // matches are weak along the walk; a longer reference drifts less there (30 simulated walks:
  // odometry RMSE 0.369 -> 0.274 m, SLAM map coverage 65.1 -> 68.2 %). Not the default: on a
  // plan global localisation lost starts with it, and tests built on the short one's behaviour
  // change (docs/odometry.md, session 28). Robots: 16 was worse and four times slower on intel.
  static constexpr int kAutoLocalMapKeyframes = -1;
  static constexpr int kShortLocalMapKeyframes = 8;
  static constexpr int kLongLocalMapKeyframes = 24;
  int local_map_keyframes = kShortLocalMapKeyframes;
  double keyframe_distance_m = 0.5;
  double keyframe_angle_rad = 0.2617993877991494;  // 15 deg
  double keyframe_min_score = 0.5;                 // overlap fallen below: new keyframe
  // The reference chosen by place (issue 3, twelfth round): local_map_pool_keyframes > 0 keeps
  // that many keyframes, and the reference is the latest local_map_recent_keyframes of them plus
  // those taken nearest the pose (within local_map_place_radius_m and local_map_pool_age_s;
  // ranked by distance / keyframe_distance_m + heading difference / keyframe_angle_rad),
  // local_map_keyframes in all; chosen again at a scan whose best-ranked keyframe is not in it.
  // Turning back on the spot then matches the keyframe made facing that way before instead of
  // chaining new ones. The pool is a short window, not a map: no loop closure. 0: off (recency).
  // kAutoPoolKeyframes (the default): kRobotPoolKeyframes for robots (level laser, wheel
  // odometry: together with the frozen-odometry handling below better on the five-start means
  // of all three Freiburg logs, session 11), off for people (mixed on the simulated
  // firefighters, twelfth round b).
  static constexpr int kAutoPoolKeyframes = -1;
  static constexpr int kRobotPoolKeyframes = 40;
  int local_map_pool_keyframes = kAutoPoolKeyframes;
  double local_map_pool_age_s = 60.0;
  int local_map_recent_keyframes = 3;
  double local_map_place_radius_m = 2.0;
  // With the place choice: slots that no keyframe within the radius and age takes are filled
  // with the next latest keyframes, so that the reference never holds fewer keyframes than the
  // recency choice. Without it, a robot driving on while turning has only the 3 recent keyframes
  // plus the few within 2 m (mit-csail scan 1679: 4 instead of 8, matched at 0.44 against the
  // recency reference's 0.83, made a keyframe 5 deg off; docs/odometry.md, session 11). Off:
  // better on mit-csail, worse on intel and aces (five-start means, session 11).
  bool local_map_place_fill_recent = false;
  // The fill only where the small reference fails (with the place choice; issue 3, session 12):
  // a match scoring below local_map_place_fill_below_score is searched again against the
  // reference with the free slots filled as above, and the better match is kept (the filled
  // reference with it, until the reference is next chosen). 0: off. 0.5 (keyframe_min_score)
  // since session 12: with the fill below while frozen, five-start means mit-csail 0.196 ->
  // 0.165 m, intel 0.175 -> 0.174 m, aces 0.146 -> 0.143 m (docs/odometry.md). Acts only with
  // the place choice (robots by default).
  double local_map_place_fill_below_score = 0.5;
  // ... and while the wheel odometry is frozen (frozen_odometry_*: robots only) and for this
  // many scans after the freeze ends, the reference is always filled: the prior is constant
  // velocity there, and a small reference matched the freezes poorly (mit-csail scan 805,
  // session 11). 0: off. 5 since session 12: five-start means mit-csail 0.196 -> 0.172 m, aces
  // 0.146 -> 0.143 m, intel unchanged (it never freezes; docs/odometry.md).
  int local_map_place_fill_frozen_scans = 5;
  // With the place choice: a new keyframe only when no keyframe of the reference (not only the
  // latest) lies within keyframe_distance_m and keyframe_angle_rad, or the score fell below.
  bool keyframe_by_place = false;
  // Keyframes during fast turns (issue 3): while the entity turns faster than
  // keyframe_turn_rate_rad_s (the larger of the matched and the predicted rotation since the
  // previous scan, over at least keyframe_turn_min_interval_s), a match scoring below
  // keyframe_turn_min_score is not made a keyframe: the reference stays where it was until a
  // good match arrives or the turn ends (mit-csail scan 1333: score 0.48 in a 280 deg turn, made
  // a keyframe 4.6 deg off). If the next match against the kept reference is poor too, the held
  // scan becomes the keyframe after all and the scan is matched again (without that, mit-csail
  // failed two scans after a hold). A match the prior gate trusted is still made one. 0: off.
  double keyframe_turn_rate_rad_s = 0.0;
  double keyframe_turn_min_score = 0.6;
  double keyframe_turn_min_interval_s = 0.05;  // bursty stamps (intel) must not read as fast turns
  // Keyframes are densified along the surface between neighbouring returns at most
  // reference_fill_max_gap_m apart, a point every reference_fill_spacing_m (0: not filled), so
  // that eq. 2 measures distance to walls, not to the nearest beam's sample. Not applied when the
  // reference confirmation below is on (filled floor-hit streaks would confirm each other).
  double reference_fill_spacing_m = 0.03;
  double reference_fill_max_gap_m = 0.5;
  double reference_fill_max_gap_beams = 3.0;  // and at most this many beam spacings (0: no limit)
  // Timing quality (robots and people): a scan stamped within timing_burst_gap_s of the previous
  // one arrived in a burst (intel: 4671 of 13631 scans; aces, mit-csail: none). While more than
  // timing_burst_fraction of the last timing_burst_window_scans scans (0: all so far) did, the
  // stamps are delivery times and the odometry paired with a keyframe may not be its own; its
  // fill then keeps reference_fill_max_gap_beams_bursty instead. timing_burst_gap_s = 0: off.
  double timing_burst_gap_s = 0.02;
  double timing_burst_fraction = 0.05;
  int timing_burst_window_scans = 0;
  double reference_fill_max_gap_beams_bursty = 3.0;  // 0: no limit
  double reference_fill_band_spacing_m = 0.0;  // beyond the beam limit: this spacing (0: none)
  // Tilt robustness for body-worn lasers: keep only reference points a second keyframe saw
  // again (floor and ceiling hits move with the person). Over three seeds it lowers the
  // firefighters' RMSE (office 0.64 -> 0.36 m, loop170 1.41 -> 1.14 m); on the level lasers of
  // the Freiburg robots it costs accuracy. kAuto: for people only. Figures in docs/odometry.md.
  enum class Confirm { kAuto, kNever, kAlways };
  Confirm confirm_reference = Confirm::kAuto;
  // The tilt model of the paper's eq. (1) and Fig. 2b, used with the reference confirmation: a
  // laser tilt_laser_height_m above the floor, pitched by at most tilt_max_pitch_rad, cannot see
  // the floor (or the ceiling tilt_ceiling_height_m up) nearer than h / tan(max pitch) (6.8 m
  // for 1.2 m and 10 deg). Nearer returns are walls: kept without confirmation and filled; only
  // farther ones must be seen again by another keyframe. 0 disables the model (all confirmed).
  double tilt_max_pitch_rad = 0.0;
  double tilt_laser_height_m = 1.2;
  double tilt_ceiling_height_m = 2.6;
  // Degenerate places: translation eigenvalue ratio of J^T J below this means a corridor-like
  // direction; that component is taken from the prior.
  double degenerate_eigen_ratio = 0.05;
  // People with spread strides only (dead reckoning, dead_reckoning.stride_interpolation on): the
  // pace check (docs/odometry.md, session 19). A weakly constrained match (translation
  // eigenvalue ratio below pace_check_weak_ratio) whose position has fallen behind the dead
  // reckoning's progress over the last pace_check_window_m walked by more than
  // pace_check_tolerance of it (and by more than the prior has) keeps the prior's component
  // along the walk, as a degenerate match does. It stops the corridor slides of floor lines that
  // move with the walker. 0 turns it off.
  double pace_check_tolerance = 0.1;
  double pace_check_window_m = 4.0;
  double pace_check_weak_ratio = 0.2;
  // Weakly constrained places (translation eigenvalue ratio below degenerate_slide_ratio: a
  // corridor whose only along-track features are a few door frames, or floor hits across it that
  // move with the person): a match that slid more than degenerate_max_slide_m along the weak
  // direction away from the prior is treated as degenerate too (the prior's component is kept).
  // kAutoSlideRatio (the default): kPeopleSlideRatio for people whose strides are spread over
  // their scans (dead reckoning, dead_reckoning.stride_interpolation on), off otherwise: between
  // keyframes such matches fell 0.2-0.5 m behind a prior that was right (office seed 5 at
  // 104.75-106.25 s) and the output jumped back and forth (docs/odometry.md, session 24). 0: off.
  static constexpr double kAutoSlideRatio = -1.0;
  static constexpr double kPeopleSlideRatio = 0.2;
  double degenerate_slide_ratio = kAutoSlideRatio;
  double degenerate_max_slide_m = 0.15;
  // Only slides back against the direction of travel (the predicted motion over the last scan
  // interval) count. Returns that move with the person (a bend's floor line across a corridor a
  // few metres ahead, far floor hits along it) read as an end wall that keeps its distance, so
  // they always pull the match back towards the reference keyframes; a genuine correction of the
  // prior can go either way, and over 48 simulated walks the prior was nearer the truth in 75 %
  // of the backward slides but in only 37 % of the forward ones (session 24). Off: both ways.
  bool degenerate_slide_backward_only = true;
  // The prior's component is kept only where the prior lies within this of the match across the
  // weak direction: a prior that is off across a corridor (a side step the stride model reads as
  // a step forward: office seed 8 at 7 s, 0.3 m) is off along it too. 0: no such check.
  double degenerate_slide_max_across_m = 0.1;
  // ... and only while the latest match that pinned the position down (ratio at or above
  // degenerate_slide_ratio) lay within this of its own prior: after a step back or a stop the
  // stride model reads as steps forward, and the prior is off until a keyframe re-anchors it
  // (team seed 1 ff1 at 15 s: 0.3 m). 0: no such check.
  double degenerate_slide_prior_agreed_m = 0.15;
  // People only (dead reckoning): returns that move with the body are dropped from the scan before
  // it is matched or made a keyframe (odometry::internal::WalkerFixedPoints): a return near where
  // one of the previous scan's was in the laser frame, but not near the previous scan moved by the
  // dead reckoning's motion between the two scans (thresholds in walker_fixed_points). A bend's
  // floor line across a corridor 4-6 m ahead keeps its distance from the walker and reads as an
  // end wall that pulls the match back (loop170 seed 8 at 106-109 s, twelfth round d5). Off by
  // default: measured worse (docs/odometry.md, thirteenth round).
  bool drop_walker_fixed_points = false;
  // People only (dead reckoning): returns inside space one of the last 16 scans saw through
  // (odometry::internal::SeenThroughPoints, placed by the motion prior: more than 1 m + 10 % of
  // the range short of where that scan's beams ended) are dropped before matching and
  // keyframing. A bend's floor line across a corridor is such a return; a static wall never is.
  // Off by default: over 28 simulated people it lowers the odometry's mean RMSE from 0.42 to
  // 0.33 m, but the office plan localisation and the SLAM maps built on it get worse
  // (docs/odometry.md, session 22).
  bool drop_seen_through_points = false;
  WalkerFixedPointsOptions walker_fixed_points;  // its thresholds (checked even when off)
  PoseCovarianceOptions covariance;  // how OdometryEstimate::covariance grows
  // Prior-consistency gate (people and robots with a motion sensor): a match that moved the
  // pose farther from the motion prior than the sensor can be wrong by is not trusted at once:
  // the scan is not made a keyframe (a stale or aliased scan must not anchor the next priors). The allowance grows with the motion since the latest keyframe. After
  // prior_gate_confirm such scans in a row the scans win over the motion sensor (it slipped).
  // prior_gate_rad = 0 disables the gate.
  double prior_gate_rad = 0.17453292519943295;  // 10 deg, plus the fraction below
  double prior_gate_fraction = 0.25;            // of the rotation / distance since the keyframe
  // With a gyro (dead reckoning) the heading prior does not degrade with the turn like wheel
  // odometry does: its rotation allowance grows by this fraction instead (office seed 4: a
  // 47-point scan after a smoke dropout matched 40 deg off and passed the 25 % allowance).
  double prior_gate_fraction_gyro = 0.05;
  // With dead reckoning the heading change since the keyframe is known to the gyro + compass
  // filter's uncertainty (about 1 deg), and 10 deg (sized for wheel odometry) lets aliased
  // matches become keyframes (team seed 1, ff1 in the open lobby, half its returns floor hits:
  // a match 8 deg off a prior good to 0.4 deg, then 31 deg off to the end). > 0: the heading
  // allowance is this many standard deviations of that change (the filter's heading sigmas at
  // the keyframe and now, root-sum-square) instead of prior_gate_rad. 0: prior_gate_rad.
  double prior_gate_gyro_sigmas = 0.0;
  double prior_gate_m = 0.3;                    // plus the fraction of the distance
  int prior_gate_confirm = 3;
  // The same count for people (dead reckoning with a gyro), kept apart because the two disagree:
  // 5 ends loop170 seed 3 at 0.19 % of the path instead of 1.38 %, but takes the office plan
  // localisation from 0.27 to 0.68 m in the map (docs/odometry.md, sixth round).
  int prior_gate_confirm_gyro = 3;
  // With a gyro, only gated matches that agree with each other count towards
  // prior_gate_confirm_gyro: each one's deviation from the prior within prior_gate_agree_gyro_m
  // and prior_gate_agree_gyro_rad of the previous one's (a wrong prior is off by the same offset
  // scan after scan; an aliased match is not). 0 m: a plain count. Wheel odometry: a plain count.
  // Off by default: 0.1 m puts loop170 seeds 1-5 under 1 % of the path but takes the office
  // plan localisation from 0.27 to 0.68 m (docs/odometry.md, sixth round continued).
  double prior_gate_agree_gyro_m = 0.0;
  double prior_gate_agree_gyro_rad = 0.05235987755982989;  // 3 deg
  // With a gyro and the compass accepted (none rejected within prior_gate_compass_window_s), a
  // gated match whose heading is more than this off the dead reckoning's own gyro + compass
  // heading is refused: it never counts towards trust, and its scan is output at the prior. The
  // compass holds that heading to about a degree, while a room's corners alias a match by 90 deg
  // in a turn on the spot (office seed 13 with 15 cm walls: three gated matches 34, 90 and 90 deg
  // off were trusted and the walk went on 90 deg off, 16 m RMSE; refused, 1.0 m). Measured from
  // the keyframe-anchored prior instead, it refused right matches after the keyframes had drifted
  // (team seed 2 ff3, 15 cm walls: 1.15 -> 4.8 m). 0: off. Figures: docs/odometry.md.
  double prior_gate_refuse_gyro_rad = 0.3490658503988659;  // 20 deg
  // After this many gated scans in a row that were never trusted (they disagree: only possible
  // with prior_gate_agree_gyro_m > 0 or a count above this), the scan is handled like a failed
  // match: the pose is the motion prior's (with dead reckoning: its position, and the gyro +
  // compass filter's own heading, which does not carry keyframe errors along) and the reference
  // restarts there, so that it does not stay behind a walking person (office seed 4 with the
  // agreement gate: 8 s without a keyframe). 0: off. Figures: docs/odometry.md, issue 6.
  int prior_gate_fallback_scans = 0;
  // People only (dead reckoning): the priors are anchored at the keyframe's dead-reckoning pose,
  // so when a stride report replaces the extrapolated stride in progress (or
  // dead_reckoning.overdue_turn_rad drops it) after a keyframe, the jump (a corrected guess about
  // the past, up to 0.9 m after turns on the spot: team3 ff3 at 39.5 s) reads as motion since
  // that keyframe. On: the keyframe's paired pose is moved by the same jump, so the prior does not
  // jump. Off by default: measured worse on office/loop170 (docs/odometry.md, twelfth round d2).
  bool keyframe_absorbs_stride_jumps = false;
  // With keyframe_absorbs_stride_jumps: move the keyframe's pose only by its share of each jump,
  // the part that had accrued by the keyframe's stamp with the corrected stride walked evenly in
  // time from its start to the report (HumanDeadReckoning's StrideJump::ShareAt); the rest is
  // motion since the keyframe. Off (the default with the flag on): the whole jump, even when the
  // keyframe was taken before the stride began. Off by default: with the flag and option set A the
  // mean RMSE is the lowest measured, but loop170 seed 3 ends over 1 % in two perturbed draws
  // (docs/odometry.md, twelfth round d3).
  bool keyframe_stride_jump_share = false;
  // With keyframe_stride_jump_share: a keyframe whose match was degenerate (its position along the
  // weak direction is the prior's, extrapolation error included) absorbs only the part of its
  // share across that direction; along it the jump stays motion since the keyframe, so along a
  // corridor the chain of priors still sums to the dead reckoning's own distance (loop170 seed 3
  // at 28.5 s: 0.4 m along the corridor kept for good with the share alone). Off by default:
  // loop170 seeds 1-5 under 1 % in both start draws, but seeds 6 and 8 more than 0.2 m worse
  // than the defaults in both (docs/odometry.md, twelfth round d4).
  bool keyframe_stride_jump_across_weak = false;
  // ... except within this long after the heading filter rejected a compass reading (a
  // magnetic disturbance: the prior's heading is bent, the scans win on the count alone).
  double prior_gate_compass_window_s = 1.0;
  // Wheel odometry that freezes (robots, MotionPrior::kOdometry): a sensor pose repeated exactly
  // at the next scan while the estimate moved by at least frozen_odometry_min_turn_rad or
  // frozen_odometry_min_move_m over the interval before is a logger that stopped updating
  // (mit-csail: three to four scans of zeros in a turn, then a 50-85 deg catch-up); not within a
  // burst of scans (timing_burst_*: intel repeats the pose of scans delivered together). While it
  // lasts the prior is constant velocity, and keyframes are paired with the frozen pose moved on
  // by the estimated motion, so the catch-up is not added on top. Both 0: off. 1 deg and 0.15 m
  // (a standing aces robot's estimate jitters by up to 0.1 m a scan): mit-csail 0.190 -> 0.151 m,
  // aces and intel unchanged (twelfth round); the default since session 11, with the robots'
  // place choice (docs/odometry.md). People's dead reckoning is never taken for frozen.
  double frozen_odometry_min_turn_rad = 0.0175;
  double frozen_odometry_min_move_m = 0.15;
  // Stale scans: a scan whose ranges repeat one of the last stale_history_scans scans (median
  // beam difference at most stale_repeat_m) while differing from the previous scan by more than
  // stale_changed_m was delivered late (intel: 40 such scans, during turns on the spot). It is
  // matched and output but never made a keyframe. stale_history_scans = 0 disables the check.
  // Robots only: a walking person's sway brings scans back (71 false repeats on loop170 seed 1).
  int stale_history_scans = 12;
  double stale_repeat_m = 0.02;
  double stale_changed_m = 0.1;
};

// What happened at a scan.
enum class MatchStatus {
  kFirst,       // the first scan: it starts the map at the start pose
  kMatched,     // corrected by scan matching
  kDegenerate,  // matched, but one direction unconstrained: that component from the prior
  kFailed,      // score too low: the prior is kept and the window grown
  kNoPoints,    // an empty or all-no-return scan: the prior is kept
  kPriorOnly,   // matching disabled
};

// The estimate at one scan, in the mission (world) frame.
struct OdometryEstimate {
  double stamp_s = 0.0;
  geometry::Pose2 world_from_body;
  // Of world_from_body (x_m, y_m, theta_rad): zero at the known start, growing with the drift
  // (PoseCovarianceOptions, docs/odometry.md "Pose covariance"); a match that disagrees with the
  // prior (outside its gate, or along a corridor) adds that disagreement.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  geometry::Pose2 world_from_prior;  // the prediction the matcher searched around
  MatchStatus status = MatchStatus::kFirst;
  double score = 0.0;                // eq. 2 at the best grid pose
  int points = 0;                    // scan points matched
  bool reference_changed = false;    // this scan became a keyframe (map localisation runs here)
  bool wide_search = false;          // the window was larger than the paper's
  bool gated = false;  // matched far from the motion prior: not a keyframe (prior-consistency gate)
  // gated and refused against the gyro + compass heading: output at the prior
  bool refused = false;
  bool stale = false;  // repeats an earlier scan (delivered late): not a keyframe
};

// Counters over the run, for logs and reports.
struct OdometryCounts {
  long scans = 0, matched = 0, degenerate = 0, failed = 0, no_points = 0, keyframes = 0;
  long wide_searches = 0;
  long gated = 0;            // matches outside the prior-consistency gate (not made keyframes)
  long refused = 0;          // of those, refused against the gyro (prior_gate_refuse_gyro_rad)
  long stale = 0;            // scans repeating an earlier scan (not made keyframes)
  long turn_held = 0;        // poor matches in fast turns not made keyframes (keyframe_turn_*)
  long pace_held = 0;        // matches that kept the prior along the walk (pace_check_*)
  long walker_fixed_dropped = 0;  // returns dropped as moving with the body (drop_walker_fixed_points)
  long seen_through_dropped = 0;  // returns dropped where an earlier scan saw through (drop_seen_through_points)
  long deskewed = 0;         // scans turned to mid-sweep (deskew_scans; swept lasers only)
  long records_ignored = 0;  // out of order or not usable (see dead reckoning counts too)
};

// The chain for one entity. Not thread-safe; one instance per entity.
class LaserOdometry {
 public:
  LaserOdometry(const LaserOdometryOptions& options, sensors::EntityKind kind,
                const geometry::Pose2& world_from_start, double start_stamp_s);
  ~LaserOdometry();
  LaserOdometry(LaserOdometry&&) noexcept;
  LaserOdometry& operator=(LaserOdometry&&) noexcept;

  // Feeds one record in time order; a laser scan yields its estimate, anything else nullopt.
  std::optional<OdometryEstimate> Add(const sensors::SensorRecord& record);

  const OdometryCounts& counts() const;
  const dead_reckoning::DeadReckoningCounts& dead_reckoning_counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "first", "matched", "degenerate", "failed", "no_points", "prior_only".
const char* ToString(MatchStatus status);

}  // namespace pena::odometry
