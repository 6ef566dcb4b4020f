#include "pena/scan_matching/hit_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::scan_matching {

HitGrid::HitGrid(const Points2& reference_m, double resolution_m, double threshold_m, bool graded)
    : origin_m_(Eigen::Vector2d::Zero()), resolution_m_(resolution_m) {
  if (!(resolution_m > 0.0)) {
    throw std::invalid_argument("hit_grid.resolution_m must be > 0 m, got " +
                                std::to_string(resolution_m));
  }
  if (!(threshold_m > 0.0)) {
    throw std::invalid_argument("hit_grid.threshold_m must be > 0 m, got " +
                                std::to_string(threshold_m));
  }
  if (reference_m.empty()) return;
  Eigen::Vector2d low = reference_m.front();
  Eigen::Vector2d high = reference_m.front();
  for (const auto& point : reference_m) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  origin_m_ = low.array() - threshold_m - resolution_m;
  width_ = static_cast<int>(std::ceil((high.x() - origin_m_.x() + threshold_m) / resolution_m)) + 2;
  height_ = static_cast<int>(std::ceil((high.y() - origin_m_.y() + threshold_m) / resolution_m)) + 2;
  cells_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
  // Stamp a disc of radius threshold around each reference point: exact for cell centres; a
  // cell keeps the weight of its nearest reference point.
  const int reach = static_cast<int>(std::ceil(threshold_m / resolution_m)) + 1;
  const double threshold_sq = threshold_m * threshold_m;
  for (const auto& point : reference_m) {
    const Eigen::Vector2i centre = CellOf(point);
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const int cx = centre.x() + dx;
        const int cy = centre.y() + dy;
        if (cx < 0 || cy < 0 || cx >= width_ || cy >= height_) continue;
        const Eigen::Vector2d cell_centre =
            origin_m_ + resolution_m_ * Eigen::Vector2d(cx + 0.5, cy + 0.5);
        const double distance_sq = (cell_centre - point).squaredNorm();
        if (distance_sq > threshold_sq) continue;
        // At least 1 inside the threshold, so graded and binary grids agree on what is a hit.
        const auto weight = graded ? static_cast<std::uint8_t>(std::max(
                                         1.0, std::floor(kFullWeight * (1.0 - distance_sq / threshold_sq))))
                                   : kFullWeight;
        auto& cell = cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(cx)];
        cell = std::max(cell, weight);
      }
    }
  }
}

}  // namespace pena::scan_matching
