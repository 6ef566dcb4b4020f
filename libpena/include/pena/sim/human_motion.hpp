#pragma once
// A walking firefighter: follows a route at about 1 m/s with stops, speed changes, side and back
// steps; the torso (and the laser on it) sways in yaw, pitch and roll with every step and bends
// now and then (paper section 2: yaw rates of 20-40 deg/s, turns up to 200 deg/s).

#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/sim/random.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/true_motion.hpp"

namespace pena::sim {

// Parameters of the walking model; angles in radians, rates per second.
struct HumanMotionOptions {
  double rate_hz = 100.0;               // motion samples per second
  double waypoint_tolerance_m = 0.15;   // a waypoint is reached this close
  double lookahead_m = 1.0;             // walks towards the leg this far ahead (pure pursuit)
  double max_turn_rate_rad_s = 2.5;     // heading control limit (~145 deg/s; sway adds on top)
  double turn_gain_per_s = 5.0;         // heading rate per rad of heading error
  double max_turn_accel_rad_s2 = 25.0;  // how fast the turn rate itself changes
  double acceleration_m_s2 = 1.5;       // speeding up
  double deceleration_m_s2 = 3.0;       // slowing down
  double speed_variation = 0.12;        // relative sd of the slow speed changes
  double speed_change_time_s = 5.0;     // correlation time of those changes
  double stop_rate_per_s = 1.0 / 45.0;  // random stops (looking around)
  double stop_min_s = 1.0;              // a stop lasts uniformly between min and max
  double stop_max_s = 3.0;
  double side_step_rate_per_s = 1.0 / 30.0;  // side steps (on straight stretches)
  double back_step_rate_per_s = 1.0 / 60.0;  // backward steps
  double side_step_m = 0.45;                 // lateral displacement of a side step
  double back_step_m = 0.4;                  // displacement of a backward step
  double dodge_speed_m_s = 0.6;              // speed of side and back steps
  double wall_clearance_m = 0.35;            // side/back steps keep this far from walls
  double step_length_base_m = 0.35;          // step length = base + per_speed * speed
  double step_length_per_speed_s = 0.2;      // (0.55 m at 1 m/s, ~1.8 steps/s)
  double yaw_sway_rad = 0.087;               // torso yaw amplitude per gait cycle (~5 deg)
  double sway_variation = 0.15;              // relative sd of the per-step sway amplitudes
  double pitch_lean_rad = 0.05;              // mean forward lean while walking (~3 deg)
  double pitch_sway_rad = 0.026;             // pitch bob per step (~1.5 deg)
  double roll_sway_rad = 0.044;              // roll sway per gait cycle (~2.5 deg)
  double tilt_drift_sd_rad = 0.035;          // slow random pitch and roll drift (~2 deg)
  double tilt_drift_time_s = 3.0;            // its correlation time
  double bend_rate_per_s = 1.0 / 12.0;       // occasional larger bends
  double bend_down_min_rad = 0.14;           // 8 deg
  double bend_down_max_rad = 0.35;           // 20 deg
  double bend_up_fraction = 0.3;             // share of bends that look up instead
  double bend_up_max_rad = 0.2;              // up to ~11 deg
  double bend_ramp_s = 0.6;                  // time to bend over (and back)
  double bend_hold_max_s = 2.0;              // a bend is held 0.3 s .. this long
  double finish_stand_s = 1.0;               // standing still after the last waypoint
};

// Generates the true motion of a human entity. Throws std::invalid_argument naming a bad option.
class HumanMotion {
 public:
  explicit HumanMotion(const HumanMotionOptions& options = {});

  // Walks `spec`'s route (laps unrolled) from its start pose; `walls` keep dodges out of walls.
  TrueMotion Generate(const EntitySpec& spec, const std::vector<geometry::Segment2>& walls,
                      Random& random) const;

 private:
  HumanMotionOptions options_;
};

}  // namespace pena::sim
