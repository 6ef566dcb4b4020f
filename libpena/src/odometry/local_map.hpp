#pragma once
// The reference of the laser odometry: the last few keyframe scans in the world frame. Points
// that no other keyframe saw again are left out: walls stay put in the world, while floor and
// ceiling hits of a tilting body-worn laser move with the person (paper Fig. 2b).

#include <deque>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::odometry::internal {

// One keyframe: the scan's points in the world frame at its estimated pose.
struct Keyframe {
  geometry::Pose2 world_from_body;
  scan_matching::Points2 points_world;
};

// A sliding window of keyframes.
class LocalMap {
 public:
  LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed);

  void Add(Keyframe keyframe);
  void Clear() { keyframes_.clear(); }
  bool empty() const { return keyframes_.empty(); }
  const Keyframe& latest() const { return keyframes_.back(); }

  // The reference points: all points of the keyframes, or with require_confirmed (and at least
  // two keyframes) only those within confirm_distance_m of a point of another keyframe.
  scan_matching::Points2 Reference() const;

 private:
  int max_keyframes_;
  double confirm_distance_m_;
  bool require_confirmed_;
  std::deque<Keyframe> keyframes_;
};

}  // namespace pena::odometry::internal
