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

// The tilt model (paper eq. 1, Fig. 2b): a laser h above the floor, pitched by at most
// max_pitch, first meets the floor at horizontal range h / tan(max_pitch) and a ceiling c above
// the floor at (c - h) / tan(max_pitch). Nearer returns are walls whatever the pitch.
// 0 when max_pitch_rad <= 0 (no model: any return may be a floor or ceiling hit).
double WallOnlyRangeM(double laser_height_m, double ceiling_height_m, double max_pitch_rad);

// A sliding window of keyframes.
class LocalMap {
 public:
  // With require_confirmed, points farther than confirm_beyond_m from their keyframe's pose
  // (the tilt model's wall-only range; 0: all points) are kept only if confirmed.
  LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed,
           double confirm_beyond_m);

  void Add(Keyframe keyframe);
  void Clear() { keyframes_.clear(); }
  bool empty() const { return keyframes_.empty(); }
  const Keyframe& latest() const { return keyframes_.back(); }

  // The reference points: all points of the keyframes, or with require_confirmed (and at least
  // two keyframes) those within confirm_beyond_m of their keyframe's pose and those within
  // confirm_distance_m of a point of another keyframe.
  scan_matching::Points2 Reference() const;

 private:
  int max_keyframes_;
  double confirm_distance_m_;
  bool require_confirmed_;
  double confirm_beyond_m_;
  std::deque<Keyframe> keyframes_;
};

}  // namespace pena::odometry::internal
