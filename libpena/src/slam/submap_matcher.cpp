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
  const geometry::Pose2 centre_from_world =
      geometry::Inverse(poses[static_cast<std::size_t>(centre)]);
  scan_matching::Points2 points;
  for (int m = first; m <= last; ++m) {
    const geometry::Pose2 centre_from_m =
        geometry::Compose(centre_from_world, poses[static_cast<std::size_t>(m)]);
    for (const Eigen::Vector2d& point : keyframes[static_cast<std::size_t>(m)].points) {
      const Eigen::Vector2d p = geometry::TransformPoint(centre_from_m, point);
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
  window.size_theta_rad = 2.0 * std::ceil(half_rad / kStepThetaRad) * kStepThetaRad;
  const scan_matching::MatchResult result =
      matcher_->MatchBranchAndBound(scan, centre_from_prior, window);
  if (!result.converged || result.score < options_.loop_min_score) return std::nullopt;
  // The best pose on the window's edge: the optimum may lie outside, and the edge pose is then
  // only the best of a cut-off slope (loop170 seed 1 closed its loop 3.4 m off this way).
  if (options_.reject_window_edge &&
      scan_matching::OnWindowEdge(result.grid_pose, centre_from_prior, window)) {
    return std::nullopt;
  }
  if (!WellConditioned(result.information, options_.degenerate_eigen_ratio)) return std::nullopt;
  return LoopMatch{result.reference_from_scan, result.score, result.information};
}

}  // namespace pena::slam::internal
