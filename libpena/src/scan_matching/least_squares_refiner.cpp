#include "least_squares_refiner.hpp"

#include <algorithm>
#include <Eigen/Cholesky>
#include <cmath>

namespace pena::scan_matching::internal {
namespace {

// Normal equations of one Gauss-Newton step on the point-to-line residuals
// r_i = n_i . (R(theta) p_i + t - q_i), unknowns (x, y, theta).
struct NormalEquations {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  // J^T J
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();     // J^T r
  int pairs = 0;
};

NormalEquations Linearise(const NearestNeighbours& neighbours, double threshold_m,
                          const Points2& scan, const geometry::Pose2& pose) {
  NormalEquations equations;
  const double c = std::cos(pose.theta_rad);
  const double s = std::sin(pose.theta_rad);
  const geometry::PointTransform transform(pose);
  for (const auto& point : scan) {
    const Eigen::Vector2d moved = transform(point);
    std::uint32_t index = 0;
    double distance_sq = 0.0;
    if (!neighbours.Find(moved, index, distance_sq) || distance_sq > threshold_m * threshold_m) continue;
    const Eigen::Vector2d& normal = neighbours.normal(index);
    if (normal.isZero()) continue;
    const Eigen::Vector2d d_rotation(-s * point.x() - c * point.y(), c * point.x() - s * point.y());
    const Eigen::Vector3d jacobian(normal.x(), normal.y(), normal.dot(d_rotation));
    const double residual = normal.dot(moved - neighbours.point(index));
    equations.information += jacobian * jacobian.transpose();
    equations.gradient += jacobian * residual;
    ++equations.pairs;
  }
  return equations;
}

}  // namespace

int CountHits(const HitGrid& hits, const Points2& scan, const geometry::Pose2& reference_from_scan) {
  int count = 0;
  const geometry::PointTransform transform(reference_from_scan);
  for (const auto& point : scan) {
    const Eigen::Vector2i cell = hits.CellOf(transform(point));
    count += hits.At(cell.x(), cell.y()) > 0 ? 1 : 0;
  }
  return count;
}

long WeightAt(const HitGrid& hits, const Points2& scan, const geometry::Pose2& reference_from_scan) {
  long weight = 0;
  const geometry::PointTransform transform(reference_from_scan);
  for (const auto& point : scan) {
    const Eigen::Vector2i cell = hits.CellOf(transform(point));
    weight += hits.At(cell.x(), cell.y());
  }
  return weight;
}

Refinement RefineLeastSquares(const NearestNeighbours& neighbours,
                              const CorrelationMatcherOptions& options, const Points2& scan,
                              const geometry::Pose2& reference_from_scan) {
  Refinement refinement{reference_from_scan, Eigen::Matrix3d::Zero()};
  for (int iteration = 0; iteration < options.refine_iterations; ++iteration) {
    const NormalEquations equations =
        Linearise(neighbours, options.threshold_m, scan, refinement.reference_from_scan);
    refinement.information = equations.information;
    if (equations.pairs < options.min_refine_pairs) break;
    // Levenberg-style damping keeps an unconstrained direction (a corridor) from running away.
    const Eigen::Matrix3d damped =
        equations.information + 1e-6 * Eigen::Matrix3d::Identity() * equations.information.trace();
    const Eigen::Vector3d step = damped.ldlt().solve(-equations.gradient);
    if (!step.allFinite()) break;
    auto& pose = refinement.reference_from_scan;
    pose = {pose.x_m + step.x(), pose.y_m + step.y(), geometry::NormalizeAngle(pose.theta_rad + step.z())};
    if (step.head<2>().norm() < 1e-5 && std::abs(step.z()) < 1e-6) break;
  }
  return refinement;
}

MatchResult Finish(const NearestNeighbours& neighbours, const HitGrid& hits,
                   const CorrelationMatcherOptions& options, const Points2& scan, const WindowGrid& grid,
                   const geometry::Pose2& reference_from_prior, const Candidate& best, long scored,
                   scan_matching::Polish polish) {
  MatchResult result;
  result.points = static_cast<int>(scan.size());
  result.candidates_scored = scored;
  result.grid_pose = best.score >= 0 ? PoseOf(grid, reference_from_prior, best) : reference_from_prior;
  result.weight = std::max(best.score, 0L);
  result.hits = best.score > 0 ? CountHits(hits, scan, result.grid_pose) : 0;
  result.score = scan.empty() ? 0.0 : static_cast<double>(result.hits) / static_cast<double>(scan.size());
  result.converged = result.hits > 0;
  result.reference_from_scan = result.grid_pose;
  if (polish == scan_matching::Polish::kRefine) RefineResult(neighbours, hits, options, scan, result);
  return result;
}

void RefineResult(const NearestNeighbours& neighbours, const HitGrid& hits,
                  const CorrelationMatcherOptions& options, const Points2& scan, MatchResult& result) {
  result.reference_from_scan = result.grid_pose;
  result.information = Eigen::Matrix3d::Zero();
  if (!result.converged) return;
  const Refinement refinement = RefineLeastSquares(neighbours, options, scan, result.grid_pose);
  // Least squares polishes the grid pose; it is kept unless it lowers the score (a false pairing
  // pulled it away), so its reach is not tied to the grid step.
  if (WeightAt(hits, scan, refinement.reference_from_scan) >= result.weight) {
    result.reference_from_scan = refinement.reference_from_scan;
  }
  result.information = refinement.information;
}

}  // namespace pena::scan_matching::internal
