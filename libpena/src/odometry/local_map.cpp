#include "local_map.hpp"

#include <vector>

#include "pena/scan_matching/hit_grid.hpp"

namespace pena::odometry::internal {

LocalMap::LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed)
    : max_keyframes_(max_keyframes),
      confirm_distance_m_(confirm_distance_m),
      require_confirmed_(require_confirmed) {}

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
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    for (const auto& point : keyframes_[k].points_world) {
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
