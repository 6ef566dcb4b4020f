// pena map: mapping with known (or estimated) poses. Inserts every scan of a log into one global
// occupancy grid, extracts the line map (paper section 3), merges it in a LineMap, and writes
// DIR/lines.csv, lines.svg, lines.dxf, grid.pgm + grid.yaml (ROS map_server) and map.png. Each scan
// passes the entity pipeline's stages after the odometry (EntityPipeline::Place) first: with
// --bent-scans a second pass levels or leaves out the scans the first pass's grid shows bent;
// with --online the line map is built by the pipeline's map stages, as an entity builds it: from
// a local grid that moves with it, extracted at each recentre and merged. Without poses of its
// own the log is first run through the odometry and the keyframe SLAM (cmd_map_slam.cpp). Options
// and outputs: docs/line-map.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "cmd_map.hpp"
#include "commands.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/ros_map.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/line_map/line_extractor.hpp"
#include "pena/pipeline/entity_pipeline.hpp"

namespace pena::cli {
namespace map {
namespace {

// A TUM pose matches a scan when their stamps differ by at most this (TUM keeps 6 decimals).
constexpr double kStampTolerance_s = 1e-3;

// The trajectory pose within kStampTolerance_s of `stamp_s`, if any (trajectory sorted by stamp).
std::optional<geometry::Pose2> PoseAt(const geometry::Trajectory& trajectory, double stamp_s) {
  const auto it = std::lower_bound(
      trajectory.begin(), trajectory.end(), stamp_s,
      [](const geometry::StampedPose2& pose, double stamp) { return pose.stamp_s < stamp; });
  std::optional<geometry::Pose2> best;
  double best_gap_s = kStampTolerance_s;
  for (auto candidate : {it, it == trajectory.begin() ? it : it - 1}) {
    if (candidate == trajectory.end()) continue;
    const double gap_s = std::abs(candidate->stamp_s - stamp_s);
    if (gap_s <= best_gap_s) {
      best_gap_s = gap_s;
      best = candidate->pose;
    }
  }
  return best;
}

line_map::LineExtractionOptions Extraction(const MapArgs& args) {
  line_map::LineExtractionOptions options;
  options.min_length_m = args.min_length_m;
  return options;
}

line_map::LineMapOptions LineMapOptionsOf(const MapArgs& args) {
  line_map::LineMapOptions options;
  options.refit_band_m = args.refit_band_m;
  options.absorb_distance_m = args.absorb_distance_m;
  return options;
}

// The pipeline's stages after the odometry: the bent-scan stage as --bent-scans says; with
// --online the map stages with the map's grid cells, lines extracted at each recentre of the
// window only (the paper's online mode), else no line map (the whole-walk grid gives it).
pipeline::EntityPipelineOptions StagesOptionsOf(const MapArgs& args, const grid::GridOptions& grid) {
  pipeline::EntityPipelineOptions options;
  const std::optional<pipeline::BentScanMode> bent_scans = pipeline::BentScanModeOf(args.bent_scans);
  if (!bent_scans) {
    throw std::invalid_argument("--bent-scans must be off, level or drop, got " + args.bent_scans);
  }
  options.bent_scans.mode = *bent_scans;
  options.build_line_map = args.online;
  options.local_grid.grid = grid;
  options.extraction = Extraction(args);
  options.line_map = LineMapOptionsOf(args);
  options.map_update_distance_m = 0.0;
  return options;
}

// Feeds records to the grid with poses from the trajectory, the logged poses or the odometry.
class PoseFeeder {
 public:
  PoseFeeder(const MapArgs& args, const geometry::Trajectory& trajectory, io::LogSource& source,
             MapRun& run)
      : args_(args), trajectory_(trajectory), source_(source), run_(run) {}

  void Run() {
    const auto started = Clock::now();
    std::vector<sensors::SensorRecord> read_ahead;
    bool logged = false;
    while (auto record = source_.Next()) {
      read_ahead.push_back(std::move(*record));
      if (const auto* scan = std::get_if<sensors::LaserScan>(&read_ahead.back())) {
        logged = scan->logged_pose.has_value() && !args_.ignore_logged;
        break;
      }
    }
    run_.pose_source = run_.slam              ? "odometry + SLAM"
                       : !trajectory_.empty() ? "trajectory"
                       : logged               ? "logged poses"
                                              : "odometry";
    if (run_.pose_source == "odometry") StartChain(read_ahead);
    ProgressLine progress(!args_.quiet);
    for (const sensors::SensorRecord& record : read_ahead) Feed(record);
    read_ahead.clear();
    while (const auto record = source_.Next()) {
      Feed(*record);
      const double wall_s = SecondsSince(started);
      if (progress.Due(wall_s)) {
        progress.Show(wall_s, "pena map: " + std::to_string(run_.used) + " scans inserted, " +
                                  Fixed(wall_s, 1) + " s");
      }
    }
    if (chain_) {
      chain_->EndOfInput();  // the records the stride spreading still holds
      while (const std::optional<pipeline::ScanStep> step = chain_->Next()) PlaceStep(*step);
      // Scans the odometry gave no pose.
      run_.skipped_no_pose += run_.scans - placed_;
      run_.pipeline_stages = chain_->stage_times();
      run_.odometry_stages = chain_->odometry().stage_times();
    }
    run_.wall_s = SecondsSince(started);
  }

 private:
  // The odometry's poses come from the entity's chain, as `pena odometry` runs it.
  void StartChain(const std::vector<sensors::SensorRecord>& read_ahead) {
    const double stamp_s = read_ahead.empty() ? 0.0 : sensors::StampOf(read_ahead.front());
    const io::LogDescription& description = source_.description();
    chain_.emplace(ChainOptionsOf(args_), description.kind.value_or(sensors::EntityKind::kRobot),
                   description.entity_id.empty() ? "entity" : description.entity_id,
                   StartPoseOf(read_ahead, source_).world_from_body, stamp_s);
  }

  void Feed(const sensors::SensorRecord& record) {
    const double stamp_s = sensors::StampOf(record);
    if (!run_.first_stamp_s) run_.first_stamp_s = stamp_s;
    run_.last_stamp_s = std::max(run_.last_stamp_s, stamp_s);
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (scan != nullptr) ++run_.scans;
    if (chain_) {
      chain_->Push(record);
      while (const std::optional<pipeline::ScanStep> step = chain_->Next()) PlaceStep(*step);
      return;
    }
    if (scan == nullptr) return;
    const std::optional<geometry::Pose2> pose =
        trajectory_.empty() ? scan->logged_pose : PoseAt(trajectory_, scan->stamp_s);
    if (!pose) {
      ++run_.skipped_no_pose;
      return;
    }
    Place(*scan, *pose);
  }

  void PlaceStep(const pipeline::ScanStep& step) {
    ++placed_;
    Place(step.scan, step.odometry.world_from_body);
  }

  // The pipeline's stages take the scan first (levelled or left out when bent, the online line
  // map); the whole-walk grid then takes it as they placed it. The laser sits at the body origin,
  // so world_from_laser is the body pose.
  void Place(const sensors::LaserScan& scan, const geometry::Pose2& pose) {
    if (!run_.stages) StartStages(scan, pose);
    const pipeline::Placement placed = run_.stages->Place(scan, pose);
    if (!placed.scan) return;  // bent, --bent-scans drop
    if (run_.grid.Insert(*placed.scan, pose)) {
      ++run_.used;
    } else {
      ++run_.refused;
    }
  }

  // From the first scan placed on, as the entity pipeline runs them; the second pass judges
  // bent scans against the first pass's grid.
  void StartStages(const sensors::LaserScan& scan, const geometry::Pose2& pose) {
    run_.stages.emplace(StagesOptionsOf(args_, run_.grid.options()),
                        source_.description().kind.value_or(sensors::EntityKind::kRobot),
                        run_.source, pose, scan.stamp_s);
    if (run_.reference) {
      run_.stages->SetBentScanReference(std::move(*run_.reference));
      run_.reference.reset();
    }
  }

  const MapArgs& args_;
  const geometry::Trajectory& trajectory_;
  io::LogSource& source_;
  MapRun& run_;
  std::optional<pipeline::EntityPipeline> chain_;
  long placed_ = 0;  // scans the chain gave a pose
};

void RunMap(const MapArgs& args) {
  const auto started = Clock::now();
  geometry::Trajectory trajectory;
  grid::GridOptions grid_options;
  grid_options.resolution_m = args.resolution_m;
  MapRun run(grid_options);
  const line_map::LineMapOptions map_options = LineMapOptionsOf(args);
  run.map = line_map::LineMap(map_options);
  run.online = args.online;
  // A bad --set slam.* is an error whether or not the SLAM runs (a trajectory, logged poses).
  (void)SlamOptionsOf(args);
  if (!args.trajectory.empty()) {
    trajectory = io::ReadTum(args.trajectory);
    if (trajectory.empty()) throw std::runtime_error(args.trajectory + ": no poses");
  } else if (args.slam) {
    if (auto slam_poses = RunSlamPass(args, run)) trajectory = std::move(*slam_poses);
  }
  const std::unique_ptr<io::LogSource> source = io::OpenLog(args.log, args.read);
  if (!source->description().entity_id.empty()) run.source = source->description().entity_id;
  PoseFeeder(args, trajectory, *source, run).Run();
  if (args.bent_scans != "off" && run.used > 0) {
    // Second pass: the same scans, those that the first pass's grid shows bent levelled or left
    // out (docs/grid.md, "Bent scans").
    run.reference.emplace(std::move(run.grid));
    run.second_pass = true;
    run.grid = grid::OccupancyGrid(grid_options);
    run.scans = run.used = run.skipped_no_pose = run.refused = 0;
    run.stages.reset();
    run.map = line_map::LineMap(map_options);
    run.extractions = 0;
    const std::unique_ptr<io::LogSource> again = io::OpenLog(args.log, args.read);
    PoseFeeder(args, trajectory, *again, run).Run();
    if (run.stages) run.bent_scans = run.stages->counts().bent_scans;
  }
  if (run.used == 0) throw std::runtime_error(args.log + ": no scan could be placed in the grid");
  const auto extract_start = Clock::now();
  const grid::GridImage image = run.grid.ToImage();
  // Offline: one extraction from the whole grid; online: the last window's. Either way through
  // the LineMap, which joins the pieces of one wall (docs/line-map.md).
  if (run.online) {
    run.extractions = run.stages->counts().extractions;
    run.stages->Flush();
    run.map = run.stages->local_map();
  } else {
    run.map.Integrate(line_map::ExtractLines(image, Extraction(args)), run.source);
  }
  const std::vector<line_map::LineSegment> lines = run.map.segments();
  const double extract_s = SecondsSince(extract_start);
  const auto write_start = Clock::now();
  const std::filesystem::path out_dir(args.out);
  std::filesystem::create_directories(out_dir);
  WriteLines(out_dir, lines);
  io::WriteRosMap(out_dir / "grid", image);
  WriteMapPicture(out_dir / "map.png", image, lines);
  const MapBytes bytes = MeasureBytes(out_dir, run.map, image);
  const double write_s = SecondsSince(write_start);
  WriteSummaryJson(out_dir / "summary.json", args, run, image, lines, extract_s, write_s,
                   SecondsSince(started));
  PrintSummary(run, image, lines, bytes, extract_s, write_s);
}

}  // namespace
}  // namespace map

void AddMapCommand(CLI::App& app) {
  using map::MapArgs;
  auto args = std::make_shared<MapArgs>();
  CLI::App* command = app.add_subcommand(
      "map",
      "Build the occupancy grid and line map of a log: lines.csv/svg/dxf, grid.pgm/yaml, PNG");
  command->add_option("--log", args->log, "Input log: CARMEN (.clf/.log, plain or gzip) or PeNa")
      ->required();
  command->add_option("--trajectory", args->trajectory,
                      "Poses (TUM) matched to scan stamps within 1 ms; default: the log's "
                      "logged poses, else laser odometry (+ SLAM, see --no-slam)");
  command->add_option("--out", args->out, "Output directory (created if missing)")->required();
  command->add_option("--resolution", args->resolution_m, "Grid cell size, metres")
      ->check(CLI::Range(0.005, 5.0))
      ->capture_default_str();
  command
      ->add_option("--min-length", args->min_length_m,
                   "Shortest line segment kept, metres (line extraction min_length_m)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  command
      ->add_option("--refit-band", args->refit_band_m,
                   "Bounded merge drift, metres: a piece farther than this from a wall's line "
                   "only extends it (LineMap refit_band_m; 0 = off)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command
      ->add_option("--absorb-distance", args->absorb_distance_m,
                   "With --refit-band: pieces this close to a wall's line are absorbed "
                   "(span only) instead of becoming duplicates (LineMap absorb_distance_m)")
      ->check(CLI::Range(0.0, 0.29))
      ->capture_default_str();
  command
      ->add_option("--bent-scans", args->bent_scans,
                   "Two passes: scans that the first pass's grid shows bent (floor hits along one "
                   "line) are levelled (ranges cut to their horizontal part) or left out of the "
                   "second (docs/grid.md, \"Bent scans\")")
      ->check(CLI::IsMember({"off", "level", "drop"}))
      ->capture_default_str();
  command->add_flag("--skip-malformed", args->read.skip_malformed,
                    "Skip malformed lines (and count them) instead of stopping at the first");
  command
      ->add_option("--max-range", args->read.carmen_max_range_m,
                   "CARMEN maximum range, metres: ranges at or above it are no-returns")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  AddCarmenSweepOptions(*command, args->read);
  command->add_flag("--online", args->online,
                    "Build the line map as an entity does: a 20 m local grid moving with it, "
                    "extracted at each recentre and merged (the paper's online mode)");
  command->add_flag("--slam,!--no-slam", args->slam,
                    "Without --trajectory or logged poses: correct the odometry with the keyframe "
                    "SLAM (loop closures, docs/slam.md; writes DIR/trajectory.tum). Default on");
  command->add_flag("--ignore-logged-poses", args->ignore_logged,
                    "Run the odometry (and SLAM) even when the log's scans carry poses (e.g. the "
                    "Freiburg logs' FLASER poses)");
  command->add_option("--set", args->odometry_settings,
                      "NAME=VALUE: change an odometry option, as `pena odometry --set` (repeatable)");
  command->add_flag("--quiet", args->quiet, "No progress line on stderr");
  command->callback([args] { map::RunMap(*args); });
}

}  // namespace pena::cli
