#include "pena/pipeline/start_pose.hpp"

#include <variant>

namespace pena::pipeline {

StartPose StartPoseOf(const std::vector<sensors::SensorRecord>& read_ahead, bool native_log) {
  for (const sensors::SensorRecord& record : read_ahead) {
    // Simulated missions state the known start as a ground-truth record before the first scan.
    if (const auto* truth = std::get_if<sensors::GroundTruth>(&record)) {
      if (native_log) return {truth->world_from_body, "ground truth"};
    }
    if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
      if (scan->odometry_pose) return {*scan->odometry_pose, "odometry"};
      break;
    }
  }
  return {{}, "identity"};
}

}  // namespace pena::pipeline
