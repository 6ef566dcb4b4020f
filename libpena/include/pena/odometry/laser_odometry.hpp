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
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"
#include "pena/stage_clock.hpp"

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
// The reasons and figures behind each default are in docs/odometry.md.
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
  // Scans that take time (LaserGeometry::sweep_s > 0) are turned to mid-sweep by the rotation
  // rate since the previous scan before they are matched or kept: a robot turning at 60 deg/s
  // turns 0.4 deg during one SICK sweep. Not when scans are closer than deskew_min_interval_s.
  bool deskew_scans = true;
  double deskew_min_interval_s = 0.05;
  // Scans whose stamps are delivery times (bursts) are deskewed with the mean scan interval.
  bool deskew_bursty_scans = true;
  // Logged odometry may lag the laser: the deskewed scan is matched this many times, each match's
  // turn giving the rate of the next deskew (0: the prior's rate only).
  int deskew_match_passes = 2;
  // Fewer usable points: no match, the prior is kept (kNoPoints). A laser going blind in smoke
  // gives scans of 10-20 points, on which a wide search finds a high-scoring wrong heading.
  int min_match_points = 30;
  // The reference: a local map of the last local_map_keyframes keyframes. kAutoLocalMapKeyframes:
  // the short one for robots, the long one for people (weak matches along corridors drift less).
  static constexpr int kAutoLocalMapKeyframes = -1;
  static constexpr int kShortLocalMapKeyframes = 8;
  static constexpr int kLongLocalMapKeyframes = 24;
  int local_map_keyframes = kShortLocalMapKeyframes;
  double keyframe_distance_m = 0.5;
  double keyframe_angle_rad = 0.2617993877991494;  // 15 deg
  double keyframe_min_score = 0.5;                 // overlap fallen below: new keyframe
  // The reference chosen by place: a pool of local_map_pool_keyframes keyframes, of which the
  // latest local_map_recent_keyframes and those taken nearest the pose (within
  // local_map_place_radius_m and local_map_pool_age_s) make the reference, so that turning back
  // matches the keyframe made facing that way. 0: recency. kAutoPoolKeyframes: robots only.
  static constexpr int kAutoPoolKeyframes = -1;
  static constexpr int kRobotPoolKeyframes = 40;
  int local_map_pool_keyframes = kAutoPoolKeyframes;
  double local_map_pool_age_s = 60.0;
  int local_map_recent_keyframes = 3;
  double local_map_place_radius_m = 2.0;
  // With the place choice: a match scoring below this is searched again against the reference
  // with its free slots filled by the latest keyframes; the better match is kept. 0: off.
  double local_map_place_fill_below_score = 0.5;
  // ... and the reference is always filled while the wheel odometry is frozen and this many
  // scans after (a constant-velocity prior needs the larger reference). 0: off.
  int local_map_place_fill_frozen_scans = 5;
  // Keyframes are densified between neighbouring returns at most reference_fill_max_gap_m apart
  // (and reference_fill_max_gap_beams beam spacings; 0: no limit), a point every
  // reference_fill_spacing_m (0: none), so that eq. 2 measures the distance to walls, not to the
  // nearest beam's sample. Not with reference confirmation (floor-hit streaks would confirm).
  double reference_fill_spacing_m = 0.03;
  double reference_fill_max_gap_m = 0.5;
  double reference_fill_max_gap_beams = 3.0;
  // Timing quality: a scan within timing_burst_gap_s of the previous one arrived in a burst.
  // While more than timing_burst_fraction of the last timing_burst_window_scans (0: all so far)
  // did, the stamps are delivery times and keyframes are filled with
  // reference_fill_max_gap_beams_bursty. timing_burst_gap_s = 0: off.
  double timing_burst_gap_s = 0.02;
  double timing_burst_fraction = 0.05;
  int timing_burst_window_scans = 0;
  double reference_fill_max_gap_beams_bursty = 3.0;  // 0: no limit
  // Tilt robustness for body-worn lasers (paper Fig. 2b): only reference points a second
  // keyframe saw enter the reference (floor and ceiling hits move with the person). kAuto:
  // people only (a level robot laser loses accuracy with it).
  enum class Confirm { kAuto, kNever, kAlways };
  Confirm confirm_reference = Confirm::kAuto;
  // J^T J translation eigenvalue ratio below which a match is degenerate (a corridor): its
  // component along the weak direction is taken from the prior.
  double degenerate_eigen_ratio = 0.05;
  // Pace check (people with spread strides): a weakly constrained match (ratio below
  // pace_check_weak_ratio) that fell behind the dead reckoning's progress over the last
  // pace_check_window_m by more than pace_check_tolerance of it keeps the prior along the walk:
  // floor lines that move with the walker pull matches back, never ahead. 0: off.
  double pace_check_tolerance = 0.1;
  double pace_check_window_m = 4.0;
  double pace_check_weak_ratio = 0.2;
  // Slide check: a weakly constrained match (ratio below degenerate_slide_ratio) that slid more
  // than degenerate_max_slide_m along its weak direction away from the prior is treated as
  // degenerate. kAutoSlideRatio: kPeopleSlideRatio for people with spread strides, else off.
  static constexpr double kAutoSlideRatio = -1.0;
  static constexpr double kPeopleSlideRatio = 0.2;
  double degenerate_slide_ratio = kAutoSlideRatio;
  double degenerate_max_slide_m = 0.15;
  // Only slides back against the direction of travel count (returns that move with the person
  // read as an end wall that keeps its distance and pull matches back). false: both ways.
  bool degenerate_slide_backward_only = true;
  // Only where the prior lies within this of the match across the weak direction (a side step
  // read as a step forward is off along the corridor too). 0: no such check.
  double degenerate_slide_max_across_m = 0.1;
  // ... and only while the latest well-constrained match lay within this of its own prior (after
  // a step back or a stop the stride model is off until a keyframe re-anchors it). 0: no check.
  double degenerate_slide_prior_agreed_m = 0.15;
  PoseCovarianceOptions covariance;  // how OdometryEstimate::covariance grows
  // Prior-consistency gate: a match farther from the motion prior than prior_gate_rad plus
  // prior_gate_fraction of the rotation since the keyframe (prior_gate_fraction_gyro with a gyro)
  // or prior_gate_m plus prior_gate_fraction of the distance is output but not made a keyframe;
  // prior_gate_confirm such scans in a row (prior_gate_confirm_gyro for people) are trusted: the
  // motion sensor slipped. prior_gate_rad = 0: no gate.
  double prior_gate_rad = 0.17453292519943295;  // 10 deg
  double prior_gate_fraction = 0.25;
  double prior_gate_fraction_gyro = 0.05;
  double prior_gate_m = 0.3;
  int prior_gate_confirm = 3;
  int prior_gate_confirm_gyro = 3;
  // People: a gated match more than this off the gyro + compass heading is refused (output at
  // the prior, never trusted): a room's corners alias a match by 30-90 deg in a turn on the spot,
  // while the compass holds the heading to about a degree. 0: off.
  double prior_gate_refuse_gyro_rad = 0.3490658503988659;  // 20 deg
  // ... except within this long after the heading filter rejected a compass reading.
  double prior_gate_compass_window_s = 1.0;
  // Frozen wheel odometry (robots): a sensor pose repeated at the next scan while the estimate
  // moved by at least frozen_odometry_min_turn_rad or frozen_odometry_min_move_m is a logger that
  // stopped updating; meanwhile the prior is constant velocity and the catch-up is not added on
  // top. Not within bursts of scans. Both 0: off.
  double frozen_odometry_min_turn_rad = 0.0175;
  double frozen_odometry_min_move_m = 0.15;
  // Stale scans (robots): a scan repeating one of the last stale_history_scans (median beam
  // difference at most stale_repeat_m) while differing from the previous scan by more than
  // stale_changed_m was delivered late: matched and output, never a keyframe. 0: no check.
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
  // Wheel odometry: the match's squared Mahalanobis distance from its prior under the odometry's
  // noise model (covariance.motion_*) plus the match's covariance; chi-square with 3 degrees of
  // freedom when both are honest. 0 where not computed (people, unmatched scans).
  double innovation_nees = 0.0;
};

// Counters over the run, for logs and reports.
struct OdometryCounts {
  long scans = 0, matched = 0, degenerate = 0, failed = 0, no_points = 0, keyframes = 0;
  long wide_searches = 0;
  long gated = 0;            // matches outside the prior-consistency gate (not made keyframes)
  long refused = 0;          // of those, refused against the gyro (prior_gate_refuse_gyro_rad)
  long stale = 0;            // scans repeating an earlier scan (not made keyframes)
  long pace_held = 0;        // matches that kept the prior along the walk (pace_check_*)
  long deskewed = 0;         // scans turned to mid-sweep (deskew_scans; swept lasers only)
  long records_ignored = 0;  // out of order or not usable (see dead reckoning counts too)
  // The laser's interlace as its turning scans showed it (1 or the configured one); 0 while
  // undecided or not in question (one sweep configured): the configured one is used.
  int laser_interlace = 0;
};

// Where LaserOdometry::Add spends its time (LaserOdometry::stage_times(); docs/odometry.md,
// "Where the time goes"). Exclusive: a stage's seconds exclude the stages inside it.
enum class OdometryStage {
  kPrediction,      // the motion prior: dead reckoning or odometry records, Predict
  kPoints,          // ranges to points, range filter (again after each deskew pass)
  kDeskew,          // interlace evidence and the deskew passes' matches (refinement included)
  kReference,       // place choice, keyframe densification, local map, the matcher's lookups
                    // (branch and bound's max-grids included, built at a reference's first use)
  kSearchBase,      // exhaustive search in the paper's window (refinement excluded)
  kSearchWide,      // branch and bound in grown windows (refinement, max-grids excluded)
  kRefinement,      // least squares after each search
  kCovariance,      // the pose covariance and the reference's
  kKeyframePolicy,  // weak direction, pace check, prior gate, keyframe decision
  kOther,           // the rest of Add: stale check, bookkeeping
  kCount
};
using OdometryStageTimes = StageTimes<OdometryStage>;

// "prediction", "points", "deskew", "reference", "search_base", "search_wide", "refinement",
// "covariance", "keyframe_policy", "other".
const char* ToString(OdometryStage stage);

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
  // Wall time per stage over the run; total: inside Add, calls: the records added.
  const OdometryStageTimes& stage_times() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "first", "matched", "degenerate", "failed", "no_points", "prior_only".
const char* ToString(MatchStatus status);

}  // namespace pena::odometry
