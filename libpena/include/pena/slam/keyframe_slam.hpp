#pragma once
// Keyframe SLAM above the laser odometry (docs/slam.md): Cartographer's global SLAM in small.
// The odometry's poses chain keyframes into a pose graph; each keyframe is matched (correlation
// matcher, branch and bound in a window that grows with the distance walked since the last
// closure) against the submap around the nearest older keyframe; accepted matches become loop
// edges and the graph is re-optimised, so a place walked twice ends up drawn once.

#include <memory>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/trajectory.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/slam/pose_graph.hpp"
#include "pena/slam/slam_options.hpp"
#include "pena/stage_clock.hpp"

namespace pena::slam {

// Counters over the run, for summaries.
struct SlamCounts {
  long scans = 0;
  long keyframes = 0;
  long loop_checks = 0;       // matches tried
  long wide_checks = 0;       // of them in the wide window (loop_wide_window_m)
  long loop_matched = 0;      // scored above loop_min_score and well conditioned
  long loop_closures = 0;     // kept after optimisation
  long loop_rejected = 0;     // dropped by the chi2 test after optimisation, or wide and unconfirmed
  long optimisations = 0;
};

// Where KeyframeSlam's time goes (KeyframeSlam::stage_times(); docs/slam.md). Exclusive: a
// stage's seconds exclude the stages inside it.
enum class SlamStage {
  kKeyframes,     // a keyframe's points, its graph node and odometry edge
  kCandidates,    // the loop candidate search over older keyframes
  kSubmapBuild,   // a submap's points and matcher (lookups, max-grids) when centre or graph changed
  kLoopMatch,     // the narrow window's branch and bound and refinement
  kWideMatch,     // the wide checks' matches
  kOptimisation,  // pose-graph solves (after each closure, its removal, and at Finish)
  kOther,         // the rest of Add and Finish
  kCount
};
using SlamStageTimes = StageTimes<SlamStage>;

// "keyframes", "candidates", "submap_build", "loop_match", "wide_match", "optimisation", "other".
const char* ToString(SlamStage stage);

// A loop-closure match that scored and was well conditioned (docs/slam.md, "Closures"): what
// it measured, what the graph predicted, and whether the optimisation kept it.
struct LoopClosureRecord {
  double older_stamp_s = 0.0;               // the older keyframe the submap was centred on
  double stamp_s = 0.0;                     // the new keyframe
  geometry::Pose2 older_from_new;           // measured by the match
  geometry::Pose2 older_from_new_prior;     // predicted by the graph before the match
  double score = 0.0;                       // eq. 2 at the best grid pose
  double window_half_m = 0.0;               // search half-width (grows since the last closure)
  // false: dropped by the chi2 test (max_loop_chi2), or a wide match never confirmed
  bool kept = false;
};

// One entity's SLAM. Not thread-safe.
class KeyframeSlam {
 public:
  // Throws std::invalid_argument naming the field for invalid options.
  // Automatic options (SlamOptions::kAuto*) are resolved for `kind`.
  explicit KeyframeSlam(const SlamOptions& options = {},
                        sensors::EntityKind kind = sensors::EntityKind::kRobot);
  ~KeyframeSlam();
  KeyframeSlam(KeyframeSlam&&) noexcept;
  KeyframeSlam& operator=(KeyframeSlam&&) noexcept;

  // Adds a scan with its odometry pose (world frame, laser at the body origin), in time order.
  // Returns the corrected pose of the scan (world frame).
  geometry::Pose2 Add(const sensors::LaserScan& scan, const geometry::Pose2& world_from_odometry);

  // Re-optimises the graph (a last time after the final scan).
  void Finish();

  // Corrected poses of every scan added so far: each scan keeps its odometry motion relative to
  // the keyframe before it, which takes its optimised pose.
  geometry::Trajectory Trajectory() const;
  // The graph (nodes: keyframes in order).
  const PoseGraph& graph() const;
  const SlamCounts& counts() const;
  // Wall time per stage over the run; total: inside Add and Finish, calls: those calls.
  const SlamStageTimes& stage_times() const;
  // Every closure match that reached the graph, kept or dropped, in the order they were tried.
  const std::vector<LoopClosureRecord>& closures() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::slam
