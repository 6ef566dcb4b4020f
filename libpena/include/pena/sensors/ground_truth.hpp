#pragma once
// The true state of an entity, known only in simulation.

#include "pena/geometry/pose2.hpp"

namespace pena::sensors {

// True planar pose of the body (mission frame) plus the laser's tilt at stamp_s.
struct GroundTruth {
  double stamp_s = 0.0;
  geometry::Pose2 world_from_body;
  double laser_height_m = 0.0;  // laser above the floor
  double pitch_rad = 0.0;       // positive pitches the beam plane down, towards the floor ahead
  double roll_rad = 0.0;        // positive rolls the left side (+y) up
};

}  // namespace pena::sensors
