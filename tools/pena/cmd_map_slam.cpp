// pena map: the SLAM pass. Without a trajectory and without logged poses, the log is read once
// through the laser odometry chain (as `pena odometry` runs it, from the same start pose) and a
// keyframe SLAM (libpena slam, docs/slam.md) that closes loops; the map is then drawn from the
// SLAM's poses in a second pass. DIR/trajectory.tum holds those poses.
#include <filesystem>
#include <memory>

#include "cli_support.hpp"
#include "cmd_map.hpp"
#include "odometry_settings.hpp"
#include "spread_source.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/odometry/laser_odometry.hpp"

namespace pena::cli::map {

odometry::LaserOdometryOptions OdometryOptionsOf(const MapArgs& args) {
  odometry::LaserOdometryOptions options;
  ApplyOdometrySettings(args.odometry_settings, options);
  return options;
}

std::optional<geometry::Trajectory> RunSlamPass(const MapArgs& args, MapRun& run) {
  const auto started = Clock::now();
  const std::unique_ptr<io::LogSource> source =
      OpenChainLog(args.log, args.read, OdometryOptionsOf(args).dead_reckoning);
  std::vector<sensors::SensorRecord> read_ahead;
  while (auto record = source->Next()) {
    read_ahead.push_back(std::move(*record));
    if (const auto* scan = std::get_if<sensors::LaserScan>(&read_ahead.back())) {
      if (scan->logged_pose && !args.ignore_logged) return std::nullopt;
      break;
    }
  }
  const double stamp_s = read_ahead.empty() ? 0.0 : sensors::StampOf(read_ahead.front());
  odometry::LaserOdometry chain(OdometryOptionsOf(args),
                                source->description().kind.value_or(sensors::EntityKind::kRobot),
                                StartPoseOf(read_ahead, *source).world_from_body, stamp_s);
  slam::KeyframeSlam slam;
  ProgressLine progress(!args.quiet);
  auto feed = [&](const sensors::SensorRecord& record) {
    const auto estimate = chain.Add(record);
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (estimate && scan != nullptr) slam.Add(*scan, estimate->world_from_body);
  };
  for (const sensors::SensorRecord& record : read_ahead) feed(record);
  while (const auto record = source->Next()) {
    feed(*record);
    const double wall_s = SecondsSince(started);
    if (progress.Due(wall_s)) {
      progress.Show(wall_s, "pena map: SLAM, " + std::to_string(slam.counts().keyframes) +
                                " keyframes, " + std::to_string(slam.counts().loop_closures) +
                                " closures, " + Fixed(wall_s, 1) + " s");
    }
  }
  slam.Finish();
  geometry::Trajectory trajectory = slam.Trajectory();
  std::filesystem::create_directories(args.out);
  io::WriteTum(std::filesystem::path(args.out) / "trajectory.tum", trajectory);
  run.slam = slam.counts();
  run.slam_wall_s = SecondsSince(started);
  return trajectory;
}

}  // namespace pena::cli::map
