#pragma once
// The scans of a radish-corrected log with their logged (SLAM-corrected) laser poses.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pena/io/log_source.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "test_data.hpp"

namespace pena::grid::testing {

struct PosedScans {
  std::vector<sensors::LaserScan> scans;
  std::vector<geometry::Pose2> poses;  // world_from_laser, as the log gives it
};

// The log `name` ("seattle", "intel", ...) of data/radish-corrected (throws when unreadable).
inline PosedScans ReadRadish(const std::string& name) {
  const std::filesystem::path path =
      pena::testing::DataPath("radish-corrected/" + name + "-corrected.log.gz");
  PosedScans result;
  const std::unique_ptr<io::LogSource> log = io::OpenLog(path);
  while (std::optional<sensors::SensorRecord> record = log->Next()) {
    auto* scan = std::get_if<sensors::LaserScan>(&*record);
    if (scan == nullptr || !scan->logged_pose) continue;
    result.poses.push_back(*scan->logged_pose);
    result.scans.push_back(std::move(*scan));
  }
  return result;
}

}  // namespace pena::grid::testing
