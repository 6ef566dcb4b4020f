#pragma once
// The reference of the laser odometry: a few keyframe scans in the world frame. Points that no
// other keyframe saw again are left out: walls stay put in the world, while floor and ceiling
// hits of a tilting body-worn laser move with the person (paper Fig. 2b). By default the
// keyframes are the last few; with a place choice they are picked from a short pool by where
// they were taken, so that turning on the spot or going back and forth matches the same earlier
// keyframes again instead of chaining a new heading increment every keyframe.

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pena/geometry/pose2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::odometry::internal {

// One keyframe: the scan's points in the world frame at its estimated pose.
struct Keyframe {
  geometry::Pose2 world_from_body;
  scan_matching::Points2 points_world;
  double stamp_s = 0.0;  // when the scan was taken (the place choice's age limit)
  // Of world_from_body (x_m, y_m, theta_rad; PoseCovarianceOptions): matches against the
  // reference inherit it.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// How the reference keyframes are chosen by place. pool_keyframes = 0: off (the last ones).
struct PlaceChoice {
  int pool_keyframes = 0;      // the last this many keyframes are kept to choose from
  double pool_age_s = 60.0;    // older pool keyframes are not chosen (a local window, no loops)
  int recent_keyframes = 3;    // the latest this many are always chosen
  double radius_m = 2.0;       // the others only if taken within this distance of the pose
  // Ranking of the others: distance / distance_scale_m + heading difference / angle_scale_rad.
  double distance_scale_m = 0.5;
  double angle_scale_rad = 0.2617993877991494;
};

// The keyframes and the reference built from max_keyframes of them.
class LocalMap {
 public:
  // With require_confirmed, reference points are kept only if another keyframe saw them too.
  LocalMap(int max_keyframes, double confirm_distance_m, bool require_confirmed,
           PlaceChoice place = {});

  // Adds the keyframe; with a place choice, chooses the reference around its pose.
  void Add(Keyframe keyframe);
  void Clear();
  bool empty() const { return keyframes_.empty(); }
  const Keyframe& latest() const { return keyframes_.back(); }
  // The latest keyframe's covariance is known only once its scan's match has been judged.
  void SetLatestCovariance(const Eigen::Matrix3d& covariance) {
    keyframes_.back().covariance = covariance;
  }
  // The keyframes the reference is built from, oldest first.
  std::vector<const Keyframe*> ReferenceKeyframes() const;
  bool place_choice() const { return place_.pool_keyframes > 0; }

  // Place choice only: when the pool keyframe ranked best for world_from_body at stamp_s is not
  // in the reference, chooses the reference around that pose. True when the reference changed.
  bool ChooseAgain(const geometry::Pose2& world_from_body, double stamp_s);

  // Place choice only: the reference points with the slots the choice left free given to the
  // next latest keyframes; nullopt when no slot is free.
  std::optional<scan_matching::Points2> FilledReference() const;
  // Gives the free slots to the latest keyframes until the reference is next chosen (the next
  // keyframe or ChooseAgain). True when the reference changed.
  bool FillFreeSlots();

  // True when a keyframe of the reference lies within distance_m and angle_rad of the pose.
  bool Covers(const geometry::Pose2& world_from_body, double distance_m, double angle_rad) const;

  // The reference points: all points of the chosen keyframes, or with require_confirmed (and at
  // least two keyframes) those within confirm_distance_m of a point of another chosen keyframe.
  scan_matching::Points2 Reference() const;

 private:
  double Cost(const Keyframe& keyframe, const geometry::Pose2& world_from_body) const;
  bool Candidate(std::size_t index, const geometry::Pose2& world_from_body, double stamp_s) const;
  std::vector<std::int64_t> ChosenFor(const geometry::Pose2& world_from_body, double stamp_s) const;
  void FillWithRecent(std::vector<std::int64_t>& chosen) const;
  bool IsChosen(std::size_t index) const;
  // The keyframes whose ids are in `chosen` (sorted), oldest first.
  std::vector<const Keyframe*> KeyframesOf(const std::vector<std::int64_t>& chosen) const;
  scan_matching::Points2 ReferenceOf(const std::vector<std::int64_t>& chosen) const;

  int max_keyframes_;
  double confirm_distance_m_;
  bool require_confirmed_;
  PlaceChoice place_;
  std::deque<Keyframe> keyframes_;    // the pool, oldest first
  std::deque<std::int64_t> ids_;      // keyframes_[i]'s id: the count of keyframes before it
  std::int64_t next_id_ = 0;
  std::vector<std::int64_t> chosen_;  // the reference's keyframe ids, ascending
};

}  // namespace pena::odometry::internal
