#pragma once
// Loop-closure matching: a keyframe's scan against the submap of older keyframes around one of
// them (internal to pena::slam).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/scan_matching/point_set.hpp"
#include "pena/slam/keyframe_slam.hpp"
#include "pena/slam/slam_options.hpp"

namespace pena::slam::internal {

// A graph node's scan: its odometry pose, its points (laser frame) and the path walked to it.
struct Keyframe {
  double stamp_s = 0.0;
  geometry::Pose2 world_from_odometry;
  scan_matching::Points2 points;
  double path_m = 0.0;
};

// An accepted match: the scan's pose in the centre keyframe's frame, its score, and the
// refinement's J^T J in (x_m, y_m, theta_rad) of the centre frame (how well each direction is
// pinned down: a corridor leaves its length weak).
struct LoopMatch {
  geometry::Pose2 centre_from_scan;
  double score = 0.0;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

// Builds (and keeps while neither the centre nor the graph changed) the matcher of one submap.
class SubmapMatcher {
 public:
  // `clock` (outliving this) times the submap builds.
  SubmapMatcher(const SlamOptions& options, StageClock<SlamStage>& clock)
      : options_(options), clock_(&clock) {}

  // Matches `scan` around `centre_from_prior` in a window of half-widths half_m / half_rad
  // against keyframes [centre - submap_keyframes, centre + submap_keyframes] no later than
  // `last_allowed`, placed by `poses`
  // (world_from_keyframe). `graph_version` changes whenever `poses` do. nullopt when the match
  // failed, scored below loop_min_score, was degenerate (a corridor), lay on the window's
  // position edge, or on its heading edge even with the heading window at loop_window_max_rad.
  std::optional<LoopMatch> Match(const std::vector<Keyframe>& keyframes,
                                 const std::vector<geometry::Pose2>& poses, int centre,
                                 int submap_keyframes, int last_allowed, long graph_version,
                                 const scan_matching::Points2& scan,
                                 const geometry::Pose2& centre_from_prior, double half_m,
                                 double half_rad);

 private:
  void Build(const std::vector<Keyframe>& keyframes, const std::vector<geometry::Pose2>& poses,
             int first, int centre, int last);

  SlamOptions options_;
  StageClock<SlamStage>* clock_;
  std::optional<scan_matching::CorrelationScanMatcher> matcher_;
  int centre_ = -1;
  int first_ = -1;
  int last_ = -1;
  long graph_version_ = -1;
};

// The scan's returns between min_range_m and max_range_m, laser frame.
scan_matching::Points2 KeyframePoints(const sensors::LaserScan& scan, const SlamOptions& options);

}  // namespace pena::slam::internal
