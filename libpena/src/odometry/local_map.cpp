#include "local_map.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pena/scan_matching/hit_grid.hpp"

namespace pena::odometry::internal {

double WallOnlyRangeM(double laser_height_m, double ceiling_height_m, double max_pitch_rad) {
  if (!(max_pitch_rad > 0.0)) return 0.0;
  const double nearest_surface_m = std::min(laser_height_m, ceiling_height_m - laser_height_m);
  return nearest_surface_m / std::tan(max_pitch_rad);
}

LocalMap::LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed,
                   double confirm_beyond_m)
    : max_keyframes_(max_keyframes),
      confirm_distance_m_(confirm_distance_m),
      require_confirmed_(require_confirmed),
      confirm_beyond_m_(confirm_beyond_m) {}

void LocalMap::Add(Keyframe keyframe) {
  keyframes_.push_back(std::move(keyframe));
  while (static_cast<int>(keyframes_.size()) > max_keyframes_) keyframes_.pop_front();
}

scan_matching::Points2 LocalMap::Reference() const {
  scan_matching::Points2 reference;
  if (!require_confirmed_ || keyframes_.size() < 2) {
    for (const auto& keyframe : keyframes_) {
      reference.insert(reference.end(), keyframe.points_world.begin(), keyframe.points_world.end());
    }
    return reference;
  }
  // One hit grid per keyframe answers "did this keyframe see something here?" in O(1).
  std::vector<scan_matching::HitGrid> seen;
  seen.reserve(keyframes_.size());
  for (const auto& keyframe : keyframes_) {
    seen.emplace_back(keyframe.points_world, confirm_distance_m_ / 2.0, confirm_distance_m_);
  }
  const double beyond_squared_m2 = confirm_beyond_m_ * confirm_beyond_m_;
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    const Eigen::Vector2d origin(keyframes_[k].world_from_body.x_m,
                                 keyframes_[k].world_from_body.y_m);
    for (const auto& point : keyframes_[k].points_world) {
      if ((point - origin).squaredNorm() < beyond_squared_m2) {
        reference.push_back(point);  // nearer than the floor can be: a wall
        continue;
      }
      for (std::size_t other = 0; other < keyframes_.size(); ++other) {
        if (other == k) continue;
        const Eigen::Vector2i cell = seen[other].CellOf(point);
        if (seen[other].At(cell.x(), cell.y())) {
          reference.push_back(point);
          break;
        }
      }
    }
  }
  return reference;
}

}  // namespace pena::odometry::internal
