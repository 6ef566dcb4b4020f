#pragma once
// A differential-drive robot: drives its route at cruise speed, turning with limited yaw rate;
// the laser stays level.

#include "pena/sim/scenario.hpp"
#include "pena/sim/true_motion.hpp"

namespace pena::sim {

// Parameters of the driving model.
struct RobotMotionOptions {
  double rate_hz = 100.0;             // motion samples per second
  double waypoint_tolerance_m = 0.1;  // a waypoint is reached this close
  double max_yaw_rate_rad_s = 1.0;    // ~57 deg/s
  double turn_gain_per_s = 2.5;       // yaw rate per rad of heading error
  double acceleration_m_s2 = 0.5;
  double finish_stand_s = 1.0;  // standing still after the last waypoint
};

// Generates the true motion of a robot entity. Throws std::invalid_argument naming a bad option.
class RobotMotion {
 public:
  explicit RobotMotion(const RobotMotionOptions& options = {});

  // Drives `spec`'s route (laps unrolled) from its start pose; the robot drives exactly (its
  // errors are in the wheel odometry model).
  TrueMotion Generate(const EntitySpec& spec) const;

 private:
  RobotMotionOptions options_;
};

}  // namespace pena::sim
