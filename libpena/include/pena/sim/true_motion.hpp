#pragma once
// The dense true trajectory of one entity, as the motion models produce it and the sensor models
// read it.

#include <cstddef>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/sim/scenario.hpp"

namespace pena::sim {

// The true state at one motion sample (mission frame). The laser sits at the body origin.
struct TrueState {
  double stamp_s = 0.0;
  geometry::Pose2 world_from_body;
  double pitch_rad = 0.0;       // sensors::GroundTruth convention: positive = beams ahead down
  double roll_rad = 0.0;        // positive = left side (+y) up
  double yaw_rate_rad_s = 0.0;  // mean body yaw rate over the interval ending at stamp_s
  double forward_velocity_m_s = 0.0;  // mean velocity along the body heading over that interval
  double speed_m_s = 0.0;             // mean ground speed over that interval (any direction)
};

// Samples at a fixed rate from the entity's start time until its route is done.
struct TrueMotion {
  double rate_hz = 0.0;
  std::vector<TrueState> states;
  // Humans: indices into `states` where a step ends (the stride sensor fires there).
  std::vector<std::size_t> step_end_indices;
};

// The entity's route with every lap unrolled: the positions to visit in order, with pauses.
std::vector<Waypoint> UnrollRoute(const EntitySpec& spec);

// Stamp of motion sample `index`: start + index / rate, computed so that multiples of the laser
// period land exactly on the same doubles in every entity.
double SampleStamp(double start_time_s, std::size_t index, double rate_hz);

}  // namespace pena::sim
