// pena map: the SLAM pass. Without a trajectory and without logged poses, the log is read once
// through the entity's chain (pipeline::EntityPipeline, as `pena odometry` runs it, from the same
// start pose) and a
// keyframe SLAM (libpena slam, docs/slam.md) that closes loops; the map is then drawn from the
// SLAM's poses in a second pass. DIR/trajectory.tum holds those poses, DIR/closures.csv the
// loop-closure matches that reached the graph.
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "cmd_map.hpp"
#include "odometry_settings.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/pipeline/entity_pipeline.hpp"

namespace pena::cli::map {

namespace {

constexpr const char* kSlamPrefix = "slam.";

bool IsSlamSetting(const std::string& text) { return text.rfind(kSlamPrefix, 0) == 0; }

// The SLAM options `--set slam.NAME=VALUE` may change (names as in SlamOptions).
SettingTargets SlamTargets(slam::SlamOptions& o) {
  SettingTargets targets;
  targets.doubles = {{"keyframe_distance_m", &o.keyframe_distance_m},
                     {"keyframe_angle_rad", &o.keyframe_angle_rad},
                     {"loop_min_path_m", &o.loop_min_path_m},
                     {"submap_radius_m", &o.submap_radius_m},
                     {"loop_window_m", &o.loop_window_m},
                     {"loop_window_per_m", &o.loop_window_per_m},
                     {"loop_window_max_m", &o.loop_window_max_m},
                     {"loop_min_score", &o.loop_min_score},
                     {"loop_wide_window_m", &o.loop_wide_window_m},
                     {"loop_wide_min_path_m", &o.loop_wide_min_path_m},
                     {"degenerate_eigen_ratio", &o.degenerate_eigen_ratio},
                     {"odometry_sigma_m", &o.odometry_sigma_m},
                     {"odometry_sigma_per_m", &o.odometry_sigma_per_m},
                     {"odometry_sigma_rad", &o.odometry_sigma_rad},
                     {"odometry_sigma_rad_per_m", &o.odometry_sigma_rad_per_m},
                     {"loop_sigma_m", &o.loop_sigma_m},
                     {"loop_sigma_rad", &o.loop_sigma_rad},
                     {"loop_weak_sigma_max_m", &o.loop_weak_sigma_max_m},
                     {"max_loop_chi2", &o.max_loop_chi2}};
  targets.ints = {{"submap_keyframes", &o.submap_keyframes},
                  {"loop_check_every", &o.loop_check_every},
                  {"loop_wide_check_every", &o.loop_wide_check_every}};
  return targets;
}


}  // namespace

odometry::LaserOdometryOptions OdometryOptionsOf(const MapArgs& args) {
  std::vector<std::string> settings;
  for (const std::string& text : args.odometry_settings) {
    if (!IsSlamSetting(text)) settings.push_back(text);
  }
  odometry::LaserOdometryOptions options;
  // A map is built offline, without a plan to correct the odometry: people's runs take the long
  // reference, which drifts less along corridors (docs/odometry.md).
  options.local_map_keyframes = odometry::LaserOdometryOptions::kAutoLocalMapKeyframes;
  ApplyOdometrySettings(settings, options);
  return options;
}

pipeline::EntityPipelineOptions ChainOptionsOf(const MapArgs& args) {
  pipeline::EntityPipelineOptions options;
  options.odometry = OdometryOptionsOf(args);
  options.build_line_map = false;  // pena map draws its own, from the poses
  return options;
}

slam::SlamOptions SlamOptionsOf(const MapArgs& args) {
  slam::SlamOptions options;
  const SettingTargets targets = SlamTargets(options);
  for (const std::string& text : args.odometry_settings) {
    if (!IsSlamSetting(text)) continue;
    Setting setting = ParseSetting(text);
    setting.name.erase(0, std::string(kSlamPrefix).size());
    if (!ApplySetting(targets, setting)) {
      throw std::runtime_error("--set: unknown option 'slam." + setting.name +
                               "' (see docs/slam.md)");
    }
  }
  slam::ValidateSlamOptions(options);
  return options;
}

namespace {

// One row per closure match that reached the graph (docs/slam.md, "Closures").
void WriteClosures(const std::filesystem::path& path, const std::vector<slam::LoopClosureRecord>& closures) {
  std::ofstream out(path);
  out << "older_stamp,stamp,x,y,theta,prior_x,prior_y,prior_theta,score,window_m,kept\n";
  for (const slam::LoopClosureRecord& c : closures) {
    out << Fixed(c.older_stamp_s, 6) << ',' << Fixed(c.stamp_s, 6) << ',' << Fixed(c.older_from_new.x_m, 4) << ','
        << Fixed(c.older_from_new.y_m, 4) << ',' << Fixed(c.older_from_new.theta_rad, 5) << ','
        << Fixed(c.older_from_new_prior.x_m, 4) << ',' << Fixed(c.older_from_new_prior.y_m, 4) << ','
        << Fixed(c.older_from_new_prior.theta_rad, 5) << ',' << Fixed(c.score, 3) << ','
        << Fixed(c.window_half_m, 3) << ',' << (c.kept ? 1 : 0) << '\n';
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

std::optional<geometry::Trajectory> RunSlamPass(const MapArgs& args, MapRun& run) {
  const auto started = Clock::now();
  const std::unique_ptr<io::LogSource> source = io::OpenLog(args.log, args.read);
  std::vector<sensors::SensorRecord> read_ahead;
  while (auto record = source->Next()) {
    read_ahead.push_back(std::move(*record));
    if (const auto* scan = std::get_if<sensors::LaserScan>(&read_ahead.back())) {
      if (scan->logged_pose && !args.ignore_logged) return std::nullopt;
      break;
    }
  }
  const double stamp_s = read_ahead.empty() ? 0.0 : sensors::StampOf(read_ahead.front());
  const io::LogDescription& description = source->description();
  const sensors::EntityKind kind = description.kind.value_or(sensors::EntityKind::kRobot);
  pipeline::EntityPipelineOptions options = ChainOptionsOf(args);
  options.slam.enabled = true;
  options.slam.graph = SlamOptionsOf(args);
  pipeline::EntityPipeline chain(options, kind,
                                 description.entity_id.empty() ? "entity" : description.entity_id,
                                 StartPoseOf(read_ahead, *source).world_from_body, stamp_s);
  slam::KeyframeSlam& slam = *chain.slam();
  ProgressLine progress(!args.quiet);
  auto feed = [&](const sensors::SensorRecord& record) {
    chain.Push(record);
    while (chain.Next()) {
    }
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
  chain.EndOfInput();  // the records the stride spreading still holds
  while (chain.Next()) {
  }
  slam.Finish();
  geometry::Trajectory trajectory = slam.Trajectory();
  std::filesystem::create_directories(args.out);
  io::WriteTum(std::filesystem::path(args.out) / "trajectory.tum", trajectory);
  WriteClosures(std::filesystem::path(args.out) / "closures.csv", slam.closures());
  run.slam = slam.counts();
  run.pipeline_stages = chain.stage_times();
  run.odometry_stages = chain.odometry().stage_times();
  run.slam_stages = slam.stage_times();
  run.slam_wall_s = SecondsSince(started);
  return trajectory;
}

}  // namespace pena::cli::map
