#pragma once
// Where an entity's run starts when nobody says: the one rule of pena-entity, pena-sensor-replay,
// the benchmarks and the `pena` subcommands (tools/pena/cli_support).

#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/sensors/record.hpp"

namespace pena::pipeline {

// The start pose and where it came from: "ground truth", "odometry" or "identity".
struct StartPose {
  geometry::Pose2 world_from_body;
  std::string source;
};

// A native (simulated) log's ground truth if it comes before the first scan (the mission's
// known start; truth is used for nothing else), else the first scan's odometry pose, else the
// identity. `read_ahead` holds the log's first records up to and including the first scan.
StartPose StartPoseOf(const std::vector<sensors::SensorRecord>& read_ahead, bool native_log);

}  // namespace pena::pipeline
