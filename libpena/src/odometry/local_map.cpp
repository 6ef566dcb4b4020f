#include "local_map.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "pena/scan_matching/hit_grid.hpp"

namespace pena::odometry::internal {

LocalMap::LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed,
                   PlaceChoice place)
    : max_keyframes_(max_keyframes),
      confirm_distance_m_(confirm_distance_m),
      require_confirmed_(require_confirmed),
      place_(place) {}

void LocalMap::Add(Keyframe keyframe) {
  const geometry::Pose2 world_from_body = keyframe.world_from_body;
  const double stamp_s = keyframe.stamp_s;
  keyframes_.push_back(std::move(keyframe));
  ids_.push_back(next_id_++);
  const int pool =
      place_choice() ? std::max(place_.pool_keyframes, max_keyframes_) : max_keyframes_;
  while (static_cast<int>(keyframes_.size()) > pool) {
    keyframes_.pop_front();
    ids_.pop_front();
  }
  chosen_ = ChosenFor(world_from_body, stamp_s);
}

void LocalMap::Clear() {
  keyframes_.clear();
  ids_.clear();
  chosen_.clear();
}

// Both terms in keyframe spacings: half a metre apart costs as much as 15 deg of heading (the
// default spacings), so that on the spot the keyframes facing the same way win.
double LocalMap::Cost(const Keyframe& keyframe, const geometry::Pose2& world_from_body) const {
  const double distance_m = std::hypot(keyframe.world_from_body.x_m - world_from_body.x_m,
                                       keyframe.world_from_body.y_m - world_from_body.y_m);
  const double turn_rad = std::abs(
      geometry::NormalizeAngle(keyframe.world_from_body.theta_rad - world_from_body.theta_rad));
  return distance_m / place_.distance_scale_m + turn_rad / place_.angle_scale_rad;
}

// A pool keyframe that is not one of the recent ones, young enough and near enough.
bool LocalMap::Candidate(std::size_t index, const geometry::Pose2& world_from_body,
                         double stamp_s) const {
  const std::size_t recent = static_cast<std::size_t>(place_.recent_keyframes);
  if (index + recent >= keyframes_.size()) return false;
  const Keyframe& keyframe = keyframes_[index];
  const double distance_m = std::hypot(keyframe.world_from_body.x_m - world_from_body.x_m,
                                       keyframe.world_from_body.y_m - world_from_body.y_m);
  return stamp_s - keyframe.stamp_s <= place_.pool_age_s && distance_m <= place_.radius_m;
}

std::vector<std::int64_t> LocalMap::ChosenFor(const geometry::Pose2& world_from_body,
                                              double stamp_s) const {
  const std::size_t count = keyframes_.size();
  if (!place_choice()) return {ids_.begin(), ids_.end()};  // the last max_keyframes
  // The latest few always: they hold what the entity sees now, wherever it is.
  const std::size_t recent = std::min(count, static_cast<std::size_t>(place_.recent_keyframes));
  std::vector<std::int64_t> chosen(ids_.end() - static_cast<std::ptrdiff_t>(recent), ids_.end());
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t i = 0; i < count; ++i) {
    if (Candidate(i, world_from_body, stamp_s)) {
      ranked.emplace_back(Cost(keyframes_[i], world_from_body), i);
    }
  }
  const std::size_t slots = static_cast<std::size_t>(max_keyframes_);
  const std::size_t others = std::min(ranked.size(), slots > recent ? slots - recent : 0);
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(others),
                    ranked.end());
  for (std::size_t k = 0; k < others; ++k) chosen.push_back(ids_[ranked[k].second]);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// Driving on, few pool keyframes lie within the radius: the free slots take the latest ones not
// chosen yet, as the recency choice would (chosen stays ascending).
void LocalMap::FillWithRecent(std::vector<std::int64_t>& chosen) const {
  const std::size_t slots = static_cast<std::size_t>(max_keyframes_);
  for (auto id = ids_.rbegin(); id != ids_.rend() && chosen.size() < slots; ++id) {
    if (!std::binary_search(chosen.begin(), chosen.end(), *id)) {
      chosen.insert(std::lower_bound(chosen.begin(), chosen.end(), *id), *id);
    }
  }
}

bool LocalMap::IsChosen(std::size_t index) const {
  return std::binary_search(chosen_.begin(), chosen_.end(), ids_[index]);
}

std::optional<scan_matching::Points2> LocalMap::FilledReference() const {
  if (!place_choice()) return std::nullopt;
  std::vector<std::int64_t> filled = chosen_;
  FillWithRecent(filled);
  if (filled == chosen_) return std::nullopt;
  return ReferenceOf(filled);
}

bool LocalMap::FillFreeSlots() {
  if (!place_choice()) return false;
  const std::size_t before = chosen_.size();
  FillWithRecent(chosen_);
  return chosen_.size() != before;
}

bool LocalMap::ChooseAgain(const geometry::Pose2& world_from_body, double stamp_s) {
  if (!place_choice() || keyframes_.empty()) return false;
  // Only when the best place is missing: re-ranking at every scan would rebuild the matcher for
  // marginal swaps.
  std::size_t best = keyframes_.size();
  double best_cost = 0.0;
  for (std::size_t i = 0; i < keyframes_.size(); ++i) {
    if (!Candidate(i, world_from_body, stamp_s)) continue;
    const double cost = Cost(keyframes_[i], world_from_body);
    if (best == keyframes_.size() || cost < best_cost) {
      best = i;
      best_cost = cost;
    }
  }
  if (best == keyframes_.size() || IsChosen(best)) return false;
  std::vector<std::int64_t> chosen = ChosenFor(world_from_body, stamp_s);
  if (chosen == chosen_) return false;
  chosen_ = std::move(chosen);
  return true;
}

bool LocalMap::Covers(const geometry::Pose2& world_from_body, double distance_m,
                      double angle_rad) const {
  for (std::size_t i = 0; i < keyframes_.size(); ++i) {
    if (!IsChosen(i)) continue;
    const geometry::Pose2 moved = geometry::Between(keyframes_[i].world_from_body, world_from_body);
    if (std::hypot(moved.x_m, moved.y_m) <= distance_m && std::abs(moved.theta_rad) <= angle_rad) {
      return true;
    }
  }
  return false;
}

scan_matching::Points2 LocalMap::Reference() const { return ReferenceOf(chosen_); }

std::vector<const Keyframe*> LocalMap::ReferenceKeyframes() const { return KeyframesOf(chosen_); }

std::vector<const Keyframe*> LocalMap::KeyframesOf(const std::vector<std::int64_t>& chosen) const {
  std::vector<const Keyframe*> used;
  for (std::size_t i = 0; i < keyframes_.size(); ++i) {
    if (std::binary_search(chosen.begin(), chosen.end(), ids_[i])) used.push_back(&keyframes_[i]);
  }
  return used;
}

scan_matching::Points2 LocalMap::ReferenceOf(const std::vector<std::int64_t>& chosen) const {
  const std::vector<const Keyframe*> used = KeyframesOf(chosen);
  scan_matching::Points2 reference;
  if (!require_confirmed_ || used.size() < 2) {
    for (const Keyframe* keyframe : used) {
      reference.insert(reference.end(), keyframe->points_world.begin(),
                       keyframe->points_world.end());
    }
    return reference;
  }
  // One hit grid per keyframe answers "did this keyframe see something here?" in O(1).
  std::vector<scan_matching::HitGrid> seen;
  seen.reserve(used.size());
  for (const Keyframe* keyframe : used) {
    seen.emplace_back(keyframe->points_world, confirm_distance_m_ / 2.0, confirm_distance_m_);
  }
  for (std::size_t k = 0; k < used.size(); ++k) {
    for (const auto& point : used[k]->points_world) {
      for (std::size_t other = 0; other < used.size(); ++other) {
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
