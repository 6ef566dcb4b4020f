#include "submap_matcher.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace pena::slam::internal {
namespace {

// Search steps: B&B finds the best pose of this grid exactly, least squares refines it.
constexpr double kStepXyCells = 2.0;
constexpr double kStepThetaRad = 0.004363323129985824;  // 0.25 deg: 13 cm at 30 m

// True when the translation part of J^T J is well conditioned (not a featureless corridor).
bool WellConditioned(const Eigen::Matrix3d& information, double min_ratio) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information.block<2, 2>(0, 0));
  const Eigen::Vector2d values = solver.eigenvalues();
  return values.y() > 0.0 && values.x() / values.y() >= min_ratio;
}

enum class Edge { kNone, kPosition, kHeading };

// Where the best grid pose lies among the window's outermost candidates (position first).
Edge WindowEdge(const geometry::Pose2& grid_pose, const geometry::Pose2& prior,
                const scan_matching::SearchWindow& window) {
  if (!scan_matching::OnWindowEdge(grid_pose, prior, window)) return Edge::kNone;
  scan_matching::SearchWindow position_only = window;
  position_only.size_theta_rad = 0.0;  // no heading steps: never on the heading edge
  return scan_matching::OnWindowEdge(grid_pose, prior, position_only) ? Edge::kPosition
                                                                      : Edge::kHeading;
}

}  // namespace

scan_matching::Points2 KeyframePoints(const sensors::LaserScan& scan, const SlamOptions& options) {
  scan_matching::Points2 points = scan_matching::ScanToPoints(scan, options.min_range_m);
  points.erase(std::remove_if(points.begin(), points.end(),
                              [&](const Eigen::Vector2d& p) {
                                return p.norm() > options.max_range_m;
                              }),
               points.end());
  return points;
}

void SubmapMatcher::Build(const std::vector<Keyframe>& keyframes,
                          const std::vector<geometry::Pose2>& poses, int first, int centre,
                          int last) {
  const StageClock<SlamStage>::Scope timed(*clock_, SlamStage::kSubmapBuild);
  const geometry::Pose2 centre_from_world =
      geometry::Inverse(poses[static_cast<std::size_t>(centre)]);
  scan_matching::Points2 points;
  for (int m = first; m <= last; ++m) {
    const geometry::Pose2 centre_from_m =
        geometry::Compose(centre_from_world, poses[static_cast<std::size_t>(m)]);
    const geometry::PointTransform transform(centre_from_m);
    for (const Eigen::Vector2d& point : keyframes[static_cast<std::size_t>(m)].points) {
      const Eigen::Vector2d p = transform(point);
      if (p.norm() <= options_.submap_radius_m) points.push_back(p);
    }
  }
  matcher_.emplace(options_.matcher, points);
  centre_ = centre;
  first_ = first;
  last_ = last;
}

std::optional<LoopMatch> SubmapMatcher::Match(const std::vector<Keyframe>& keyframes,
                                              const std::vector<geometry::Pose2>& poses,
                                              int centre, int submap_keyframes,
                                              int last_allowed, long graph_version,
                                              const scan_matching::Points2& scan,
                                              const geometry::Pose2& centre_from_prior,
                                              double half_m, double half_rad) {
  if (scan.size() < 20) return std::nullopt;
  const int first = std::max(0, centre - submap_keyframes);
  const int last = std::min(last_allowed, centre + submap_keyframes);
  if (!matcher_ || centre != centre_ || first != first_ || last != last_ ||
      graph_version != graph_version_) {
    Build(keyframes, poses, first, centre, last);
    graph_version_ = graph_version;
  }
  const double step_m = kStepXyCells * options_.matcher.grid_resolution_m;
  scan_matching::SearchWindow window;
  window.step_xy_m = step_m;
  window.step_theta_rad = kStepThetaRad;
  window.size_x_m = 2.0 * std::ceil(half_m / step_m) * step_m;
  window.size_y_m = window.size_x_m;
  scan_matching::MatchResult result;
  for (;;) {
    window.size_theta_rad = 2.0 * std::ceil(half_rad / kStepThetaRad) * kStepThetaRad;
    result = matcher_->MatchBranchAndBound(scan, centre_from_prior, window,
                                           scan_matching::Polish::kGridPoseOnly);
    // The max-grids are built at a submap's first match, again when a window needs more levels.
    if (result.max_grids_s > 0.0) clock_->Move(SlamStage::kSubmapBuild, result.max_grids_s);
    if (!result.converged || result.score < options_.loop_min_score) return std::nullopt;
    const Edge edge = WindowEdge(result.grid_pose, centre_from_prior, window);
    if (edge == Edge::kNone) break;
    // The best pose on the window's edge is only the best of a cut-off slope: the optimum lies
    // outside. In position that is a graph the submap disagrees with by more than the window
    // trusts, typically a corridor's along direction that each closure would then creep
    // (docs/slam.md): refused. In heading it is the odometry's heading drift, which every wall
    // of the submap observes without the corridor's ambiguity: searched again with the heading
    // window doubled, up to loop_window_max_rad.
    if (edge == Edge::kPosition || half_rad >= options_.loop_window_max_rad) return std::nullopt;
    half_rad = std::min(2.0 * half_rad, options_.loop_window_max_rad);
  }
  matcher_->Refine(scan, result);  // the search kept: refined once
  if (!WellConditioned(result.information, options_.degenerate_eigen_ratio)) return std::nullopt;
  return LoopMatch{result.reference_from_scan, result.score, result.information};
}

}  // namespace pena::slam::internal
