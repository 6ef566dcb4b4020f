#include "nearest_neighbours.hpp"

#include <Eigen/Eigenvalues>

namespace pena::scan_matching::internal {

NearestNeighbours::NearestNeighbours(Points2 points)
    : cloud_(std::make_unique<Cloud>(Cloud{std::move(points)})) {
  tree_ = std::make_unique<Tree>(2, *cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree_->buildIndex();
  normals_.assign(cloud_->points.size(), Eigen::Vector2d::Zero());
  normal_known_.assign(cloud_->points.size(), false);
}

void NearestNeighbours::EstimateNormal(std::uint32_t index) const {
  constexpr std::size_t kNeighbours = 5;
  constexpr double kMaxSpreadM = 0.5;  // neighbours farther apart are not one surface
  normal_known_[index] = true;
  if (cloud_->points.size() < kNeighbours) return;
  std::uint32_t indices[kNeighbours];
  double distances_sq[kNeighbours];
  const double query[2] = {cloud_->points[index].x(), cloud_->points[index].y()};
  tree_->knnSearch(query, kNeighbours, indices, distances_sq);
  if (distances_sq[kNeighbours - 1] > kMaxSpreadM * kMaxSpreadM) return;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto neighbour : indices) mean += cloud_->points[neighbour];
  mean /= static_cast<double>(kNeighbours);
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const auto neighbour : indices) {
    const Eigen::Vector2d d = cloud_->points[neighbour] - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
  // Line-like: the spread across is small against the spread along.
  if (solver.eigenvalues()(0) > 0.1 * solver.eigenvalues()(1)) return;
  normals_[index] = solver.eigenvectors().col(0).normalized();
}

bool NearestNeighbours::Find(const Eigen::Vector2d& query_m, std::uint32_t& index,
                             double& distance_sq_m2) const {
  if (cloud_->points.empty()) return false;
  const double query[2] = {query_m.x(), query_m.y()};
  return tree_->knnSearch(query, 1, &index, &distance_sq_m2) == 1;
}

}  // namespace pena::scan_matching::internal
