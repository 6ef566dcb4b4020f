#pragma once
// Options of the keyframe SLAM above the laser odometry (docs/slam.md).

#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/sensors/entity.hpp"

namespace pena::slam {

// Validated by ValidateSlamOptions (and the KeyframeSlam constructor); messages name the field.
struct SlamOptions {
  // A scan becomes a keyframe (a graph node) after this much odometry motion.
  double keyframe_distance_m = 0.3;
  double keyframe_angle_rad = 0.17453292519943295;  // 10 deg
  double min_range_m = 0.1;   // closer returns are the carrier's own body
  double max_range_m = 30.0;  // farther returns are too sparse to match on
  // Loop closure: a keyframe is matched against the submap around the nearest older keyframe
  // that lies at least loop_min_path_m back along the path and within the search radius.
  double loop_min_path_m = 4.0;
  int submap_keyframes = 12;         // keyframes on each side of that one in its submap
  double submap_radius_m = 12.0;     // submap points farther from its centre are left out
  // Half-width of the search window right after a closure. The graph has just been made to agree
  // with the older keyframes, so the next closure has little to correct; a wide window lets
  // corridor closures creep 0.4-0.6 m each, one after another (docs/slam.md).
  double loop_window_m = 0.2;
  double loop_window_per_m = 0.02;   // grows by this per metre walked since the last closure
  double loop_window_max_m = 2.0;    // up to this
  double loop_window_rad = 0.08726646259971647;      // 5 deg half-width after a closure
  double loop_window_rad_per_m = 0.002;              // growth per metre
  // A match on the heading edge is searched again with the heading half-width doubled, up to
  // this; a match on the position edge is refused (submap_matcher.cpp, docs/slam.md).
  double loop_window_max_rad = 0.2617993877991494;   // 15 deg
  // A revisit after a long walk can be farther off than the narrow window ever grows (the
  // window restarts at every closure, and closures nearby keep it small): a keyframe without a
  // closure is also matched, every loop_wide_check_every keyframes, against the submap around the
  // nearest keyframe at least loop_wide_min_path_m back within this half-width (0: off).
  // kAutoWideWindow: kRobotWideWindowM for robots, off for people, whose laser odometry drifts
  // well under the narrow window per loop and whose tilting scans fit aliases along doorless
  // corridors better than the true place (docs/slam.md, "Wide closures").
  static constexpr double kAutoWideWindow = -1.0;
  static constexpr double kRobotWideWindowM = 4.0;
  double loop_wide_window_m = kAutoWideWindow;
  double loop_wide_min_path_m = 30.0;
  int loop_wide_check_every = 5;
  double loop_min_score = 0.6;       // eq. 2 score a closure needs
  double degenerate_eigen_ratio = 0.05;  // translation eigenvalue ratio below: corridor, refused
  int loop_check_every = 1;          // try a closure at every n-th keyframe
  scan_matching::CorrelationMatcherOptions matcher{0.06, 0.02, 8, 10, true};
  // Edge uncertainties (1 sigma). Odometry between consecutive keyframes: a floor plus a share
  // of the motion; loop closures: fixed.
  double odometry_sigma_m = 0.02;
  double odometry_sigma_per_m = 0.10;
  double odometry_sigma_rad = 0.005;
  double odometry_sigma_rad_per_m = 0.01;
  double loop_sigma_m = 0.05;
  double loop_sigma_rad = 0.01;
  // Closure edges shaped by their match. A corridor closure pins the walls' across position to a
  // centimetre or two and its along position to several (opposite walking directions, 19 office
  // maps: sd 0.019 m across, 0.076 m along), so the position sigma is loop_sigma_m along the
  // best-pinned direction of the match's J^T J and loop_sigma_m * sqrt(lambda_max / lambda_min)
  // along the weakest, at most this (m; with degenerate_eigen_ratio 0.05 the ratio gives at most
  // 0.22 m). 0: loop_sigma_m both ways (docs/slam.md).
  double loop_weak_sigma_max_m = 0.5;
  int optimize_iterations = 10;
  double max_loop_chi2 = 25.0;  // a closure disagreeing more than this after optimising is dropped
};

// The automatic options resolved for an entity kind.
SlamOptions ForEntity(SlamOptions options, sensors::EntityKind kind);

// Throws std::invalid_argument naming the field and its unit, e.g.
// "slam.keyframe_distance_m must be > 0 m, got -1".
void ValidateSlamOptions(const SlamOptions& options);

}  // namespace pena::slam
