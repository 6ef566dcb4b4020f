#pragma once
// Wheel odometry that freezes in a turn and catches up (mit-csail: the logged pose repeats for
// three to four scans while the scans turn 10 deg each, then jumps by 50-85 deg). Predicted from
// the frozen pose, those scans are searched 10-35 deg from where they are, matched poorly over
// the grown window and gated; a keyframe taken there is paired with the frozen pose, so the
// catch-up is added on top of the motion the scans already showed (scans 321-327, 799-804).

#include <optional>

#include "pena/geometry/pose2.hpp"

namespace pena::odometry::internal {

// Recognises a freeze and stands in for the motion sensor while it lasts.
class FrozenOdometry {
 public:
  // A sensor pose repeated exactly at the next scan is a freeze when the chain's estimate moved
  // by at least min_turn_rad or min_move_m over the scan interval before. Both 0: off.
  FrozenOdometry(double min_turn_rad, double min_move_m);

  // Before matching a scan: `sensor_pose` is the motion sensor's pose now; `previous_estimate`
  // and `velocity` are the chain's pose at the previous scan and its motion over the interval
  // before that. `burst`: the scan came in a burst, or the log's stamps are delivery times
  // (BurstTiming); a repeated pose is then a scan delivered with the previous one (intel), not a
  // freeze. Returns the constant-velocity prediction while frozen, nullopt otherwise.
  std::optional<geometry::Pose2> Predict(const std::optional<geometry::Pose2>& sensor_pose,
                                         const geometry::Pose2& previous_estimate,
                                         const geometry::Pose2& velocity, bool burst);

  // The sensor pose to pair with the pose `world_from_body` estimated at this scan (to anchor
  // priors at a keyframe, or to measure the motion since one): the sensor's own unless frozen;
  // while frozen, the frozen pose moved on by the motion estimated since the last fresh scan,
  // so that the catch-up after the freeze adds only the motion the scans have not seen yet.
  std::optional<geometry::Pose2> PairedPose(const std::optional<geometry::Pose2>& sensor_pose,
                                            const geometry::Pose2& world_from_body) const;

  // After a scan: its final estimate (the last fresh scan's is remembered).
  void Estimated(const geometry::Pose2& world_from_body);

  bool frozen() const { return frozen_; }
  // Scans since the last frozen one (0 while frozen); nullopt before the first freeze.
  std::optional<int> scans_since_frozen() const { return scans_since_frozen_; }

 private:
  double min_turn_rad_;
  double min_move_m_;
  std::optional<geometry::Pose2> last_sensor_pose_;  // at the previous scan
  std::optional<geometry::Pose2> fresh_estimate_;    // the estimate at the last unfrozen scan
  bool frozen_ = false;
  std::optional<int> scans_since_frozen_;
};

}  // namespace pena::odometry::internal
