// pena odometry: runs the per-entity chain (pipeline::EntityPipeline, as pena-entity does, without
// its line map) over a CARMEN or native log and writes DIR/trajectory.tum, odometry.csv,
// odometry.png and summary.json. Options, outputs and formats: docs/odometry.md.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "commands.hpp"
#include "odometry_settings.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/scan_matching/point_set.hpp"
#include "pena/viz/trajectory_picture.hpp"

namespace pena::cli {
namespace {

struct OdometryArgs {
  std::string log;
  std::string out;
  std::string prior = "auto";
  std::string confirm = "auto";
  bool no_matching = false;
  std::string start;
  std::vector<std::string> settings;  // --set NAME=VALUE (numeric chain options, for sweeps)
  bool quiet = false;
  io::ReadOptions read;
};

const std::map<std::string, odometry::LaserOdometryOptions::Confirm> kConfirm = {
    {"auto", odometry::LaserOdometryOptions::Confirm::kAuto},
    {"always", odometry::LaserOdometryOptions::Confirm::kAlways},
    {"never", odometry::LaserOdometryOptions::Confirm::kNever}};

const std::map<std::string, odometry::MotionPrior> kPriors = {
    {"auto", odometry::MotionPrior::kAuto},
    {"dead-reckoning", odometry::MotionPrior::kDeadReckoning},
    {"stride-only", odometry::MotionPrior::kStrideOnly},
    {"odometry", odometry::MotionPrior::kOdometry},
    {"none", odometry::MotionPrior::kNone}};

double Percent(long part, long whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

// "X,Y,THETA_DEG" -> pose (metres, metres, radians); anything else is a usage error.
geometry::Pose2 ParseStart(const std::string& text) {
  const auto fail = [&] {
    return std::runtime_error("--start: expected X,Y,THETA_DEG (metres, metres, degrees), got '" +
                              text + "'");
  };
  double values[3];
  const char* cursor = text.c_str();
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    values[i] = std::strtod(cursor, &end);
    if (end == cursor || !std::isfinite(values[i])) throw fail();
    if (*end != (i < 2 ? ',' : '\0')) throw fail();
    cursor = end + 1;
  }
  return {values[0], values[1], values[2] * std::numbers::pi / 180.0};
}

// Where the run starts, and the records read from the log to find out.
struct Start {
  geometry::Pose2 world_from_body;
  std::string source;  // "--start", "ground truth", "odometry", "identity"
  double stamp_s = 0.0;
  std::vector<sensors::SensorRecord> read_ahead;
};

// Reads up to the first ground-truth record or scan (whichever comes first): the start pose is
// --start, else the native log's first ground truth (the mission's known start), else the first
// scan's odometry pose, else the identity. Truth is used for nothing else.
Start FindStart(io::LogSource& source, const std::optional<geometry::Pose2>& start_override) {
  Start start;
  while (auto record = source.Next()) {
    start.read_ahead.push_back(std::move(*record));
    const sensors::SensorRecord& last = start.read_ahead.back();
    if (std::holds_alternative<sensors::GroundTruth>(last) ||
        std::holds_alternative<sensors::LaserScan>(last)) {
      break;
    }
  }
  const StartPose rule = StartPoseOf(start.read_ahead, source);
  start.world_from_body = start_override.value_or(rule.world_from_body);
  start.source = start_override ? "--start" : rule.source;
  if (!start.read_ahead.empty()) start.stamp_s = sensors::StampOf(start.read_ahead.front());
  return start;
}

// Everything the run produced, for the output files.
struct RunResult {
  std::vector<odometry::OdometryEstimate> estimates;
  viz::TrajectoryPicture picture;
  geometry::Pose2 world_from_start;
  std::string start_source;
  odometry::OdometryCounts counts;
  // People only: what the dead reckoning refused (compass, strides) and how the strides were
  // spread over the scans (absent when spreading is off).
  std::optional<dead_reckoning::DeadReckoningCounts> dead_reckoning;
  std::optional<dead_reckoning::StrideInterpolationCounts> spreading;
  long prior_only = 0;  // scans with matching disabled (not in OdometryCounts)
  long records = 0;
  double first_stamp_s = 0.0;
  double last_stamp_s = 0.0;
  double wall_s = 0.0;  // reading the log and running the odometry
  // Where the time went: the pipeline's stages and, inside its odometry stage, the odometry's.
  pipeline::PipelineStageTimes pipeline_stages;
  odometry::OdometryStageTimes odometry_stages;
};

// One scan's estimate into the outputs.
void Place(const pipeline::ScanStep& step, RunResult& run) {
  const odometry::OdometryEstimate& estimate = step.odometry;
  const geometry::Pose2& pose = estimate.world_from_body;
  run.picture.scans_m.push_back(
      scan_matching::TransformPoints(pose, scan_matching::ScanToPoints(step.scan, 0.0)));
  run.picture.estimate.push_back({estimate.stamp_s, pose});
  if (estimate.reference_changed) run.picture.keyframes_m.emplace_back(pose.x_m, pose.y_m);
  if (estimate.status == odometry::MatchStatus::kFailed)
    run.picture.failed_m.emplace_back(pose.x_m, pose.y_m);
  if (estimate.status == odometry::MatchStatus::kPriorOnly) ++run.prior_only;
  run.estimates.push_back(estimate);
}

void Record(const sensors::SensorRecord& record, pipeline::EntityPipeline& chain, RunResult& run) {
  ++run.records;
  run.last_stamp_s = std::max(run.last_stamp_s, sensors::StampOf(record));
  chain.Push(record);
  while (const std::optional<pipeline::ScanStep> step = chain.Next()) Place(*step, run);
}

RunResult RunChain(io::LogSource& source, const OdometryArgs& args,
                   const std::optional<geometry::Pose2>& start_override) {
  const auto started = Clock::now();
  Start start = FindStart(source, start_override);
  pipeline::EntityPipelineOptions options;
  options.odometry.motion_prior = kPriors.at(args.prior);
  options.odometry.match_scans = !args.no_matching;
  options.odometry.confirm_reference = kConfirm.at(args.confirm);
  ApplyOdometrySettings(args.settings, options.odometry);
  options.build_line_map = false;  // the poses alone
  const io::LogDescription& description = source.description();
  const sensors::EntityKind kind = description.kind.value_or(sensors::EntityKind::kRobot);
  pipeline::EntityPipeline chain(options, kind,
                                 description.entity_id.empty() ? "entity" : description.entity_id,
                                 start.world_from_body, start.stamp_s);
  RunResult run;
  run.first_stamp_s = run.last_stamp_s = start.stamp_s;
  run.world_from_start = start.world_from_body;
  run.start_source = start.source;
  ProgressLine progress(!args.quiet);
  for (const sensors::SensorRecord& record : start.read_ahead) Record(record, chain, run);
  start.read_ahead.clear();
  while (const auto record = source.Next()) {
    Record(*record, chain, run);
    const double wall_s = SecondsSince(started);
    const double log_s = run.last_stamp_s - run.first_stamp_s;
    if (run.estimates.size() > 500 && progress.Due(wall_s)) {
      progress.Show(wall_s, "pena odometry: " + std::to_string(run.estimates.size()) +
                                " scans, log time " + Fixed(log_s, 1) + " s, " +
                                Fixed(wall_s > 0.0 ? log_s / wall_s : 0.0, 1) + " x real time");
    }
  }
  // The records the stride spreading still holds.
  chain.EndOfInput();
  while (const std::optional<pipeline::ScanStep> step = chain.Next()) Place(*step, run);
  run.counts = chain.odometry_counts();
  if (kind == sensors::EntityKind::kHuman) {
    run.dead_reckoning = chain.odometry().dead_reckoning_counts();
  }
  run.spreading = chain.stride_spreading();
  run.pipeline_stages = chain.stage_times();
  run.odometry_stages = chain.odometry().stage_times();
  run.wall_s = SecondsSince(started);
  return run;
}

void WriteCsv(const std::filesystem::path& path, const RunResult& run) {
  std::ofstream out(path);
  out << "stamp,x,y,theta,status,score,points,reference_changed,wide_search,prior_x,prior_y,"
         "prior_theta,gated,stale,sd_x,sd_y,sd_theta,cov_xy,cov_xtheta,cov_ytheta,innovation_nees\n";
  char line[400];
  for (const odometry::OdometryEstimate& e : run.estimates) {
    const geometry::Pose2& p = e.world_from_body;
    const geometry::Pose2& q = e.world_from_prior;
    const Eigen::Vector3d sd = e.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    std::snprintf(line, sizeof(line),
                  "%.6f,%.6f,%.6f,%.6f,%s,%.4f,%d,%d,%d,%.6f,%.6f,%.6f,%d,%d,"
                  "%.4f,%.4f,%.5f,%.6g,%.6g,%.6g,%.4g\n",
                  e.stamp_s, p.x_m, p.y_m, p.theta_rad, odometry::ToString(e.status), e.score,
                  e.points, e.reference_changed ? 1 : 0, e.wide_search ? 1 : 0, q.x_m, q.y_m,
                  q.theta_rad, e.gated ? 1 : 0, e.stale ? 1 : 0, sd.x(), sd.y(), sd.z(),
                  e.covariance(0, 1), e.covariance(0, 2), e.covariance(1, 2), e.innovation_nees);
    out << line;
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

double Speed(const RunResult& run) {
  return run.wall_s > 0.0 ? (run.last_stamp_s - run.first_stamp_s) / run.wall_s : 0.0;
}

void WriteSummaryJson(const std::filesystem::path& path, const OdometryArgs& args,
                      const io::LogSource& source, const RunResult& run, double total_wall_s) {
  const odometry::OdometryCounts& c = run.counts;
  std::ofstream out(path);
  out << "{\"log\": " << JsonString(args.log)
      << ", \"format\": " << JsonString(source.description().format)
      << ", \"prior\": " << JsonString(args.prior)
      << ", \"start_pose_source\": " << JsonString(run.start_source)
      << ", \"matching\": " << (args.no_matching ? "false" : "true")
      << ", \"records\": " << run.records << ", \"skipped_lines\": " << source.skipped()
      << ", \"scans\": " << c.scans << ", \"matched\": " << c.matched
      << ", \"degenerate\": " << c.degenerate << ", \"failed\": " << c.failed
      << ", \"gated\": " << c.gated << ", \"stale\": " << c.stale;
  if (c.pace_held > 0) out << ", \"pace_held\": " << c.pace_held;
  if (c.refused > 0) out << ", \"refused\": " << c.refused;
  // Only for swept lasers (CARMEN logs): the simulated missions' summaries stay as they were.
  if (c.deskewed > 0) out << ", \"deskewed\": " << c.deskewed;
  if (c.laser_interlace > 0) out << ", \"laser_interlace\": " << c.laser_interlace;
  out << ", \"no_points\": " << c.no_points << ", \"prior_only\": " << run.prior_only
      << ", \"keyframes\": " << c.keyframes << ", \"wide_searches\": " << c.wide_searches
      << ", \"records_ignored\": " << c.records_ignored;
  if (const auto& d = run.dead_reckoning) {
    out << ", \"dead_reckoning\": {\"compass_rejected\": " << d->compass_rejected
        << ", \"gyro_gaps\": " << d->gyro_gaps << ", \"strides_rejected\": " << d->strides_rejected
        << ", \"out_of_order\": " << d->out_of_order << "}";
  }
  if (const auto& p = run.spreading) {
    out << ", \"stride_spreading\": {\"strides_spread\": " << p->strides_spread
        << ", \"pieces\": " << p->pieces << ", \"released_unspread\": " << p->released_unspread
        << "}";
  }
  out
      << ", \"log_duration_s\": " << Fixed(run.last_stamp_s - run.first_stamp_s, 6)
      << ", \"processing_wall_s\": " << Fixed(run.wall_s, 3)
      << ", \"total_wall_s\": " << Fixed(total_wall_s, 3)
      << ", \"speed_x_real_time\": " << Fixed(Speed(run), 2)
      << ", \"peak_rss_mb\": " << Fixed(PeakResidentMb(), 1)
      << ", \"stage_times\": {\"pipeline\": " << StageTimesJson(run.pipeline_stages)
      << ", \"odometry\": " << StageTimesJson(run.odometry_stages) << "}}\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

void PrintSummary(const RunResult& run, const std::filesystem::path& out_dir) {
  const odometry::OdometryCounts& c = run.counts;
  const geometry::Pose2& s = run.world_from_start;
  std::cout << "start pose (" << run.start_source << "): x " << Fixed(s.x_m, 3) << " m, y "
            << Fixed(s.y_m, 3) << " m, theta " << Fixed(s.theta_rad * 180.0 / std::numbers::pi, 2)
            << " deg at " << Fixed(run.first_stamp_s, 6) << " s\n";
  const auto part = [&](const char* name, long count) {
    std::cout << ", " << count << " " << name << " (" << Fixed(Percent(count, c.scans), 1) << "%)";
  };
  std::cout << c.scans << " scans";
  part("matched", c.matched);
  part("degenerate", c.degenerate);
  part("failed", c.failed);
  part("no points", c.no_points);
  if (run.prior_only > 0) part("prior only", run.prior_only);
  std::cout << ", " << c.keyframes << " keyframes\n";
  if (const auto& d = run.dead_reckoning) {
    std::cout << "dead reckoning: " << d->compass_rejected << " compass readings rejected, "
              << d->strides_rejected << " strides rejected, " << d->gyro_gaps << " gyro gaps, "
              << d->out_of_order << " records out of order";
    if (const auto& p = run.spreading) {
      std::cout << "; " << p->strides_spread << " strides spread over " << p->pieces
                << " scans, " << p->released_unspread << " records released unspread";
    } else {
      std::cout << "; strides not spread";
    }
    std::cout << "\n";
  }
  std::cout << "log " << Fixed(run.last_stamp_s - run.first_stamp_s, 1) << " s processed in "
            << Fixed(run.wall_s, 2) << " s wall: " << Fixed(Speed(run), 1) << " x real time\n";
  std::cout << "wrote " << (out_dir / "trajectory.tum").string() << ", odometry.csv, "
            << "odometry.png, summary.json\n";
}

// The true path of a simulated entity (truth.tum next to its native log), for the picture only.
geometry::Trajectory TruthNextTo(const io::LogSource& source) {
  const io::LogDescription& description = source.description();
  const std::filesystem::path truth = description.path.parent_path() / "truth.tum";
  if (description.format != "pena-log" || !std::filesystem::exists(truth)) return {};
  try {
    return io::ReadTum(truth);
  } catch (const std::exception& error) {
    std::cerr << "pena: warning: " << error.what() << " (picture drawn without the true path)\n";
    return {};
  }
}

void RunOdometry(const OdometryArgs& args) {
  const auto started = Clock::now();
  std::optional<geometry::Pose2> start_override;
  if (!args.start.empty()) start_override = ParseStart(args.start);
  const std::unique_ptr<io::LogSource> source = io::OpenLog(args.log, args.read);
  const std::filesystem::path out_dir(args.out);
  std::filesystem::create_directories(out_dir);
  RunResult run = RunChain(*source, args, start_override);
  io::WriteTum(out_dir / "trajectory.tum", run.picture.estimate);
  WriteCsv(out_dir / "odometry.csv", run);
  run.picture.truth = TruthNextTo(*source);
  run.picture.title = std::filesystem::path(args.log).filename().string() + ", prior " +
                      args.prior + (args.no_matching ? ", no matching" : "");
  const std::string picture = (out_dir / "odometry.png").string();
  if (!cv::imwrite(picture, viz::RenderTrajectory(run.picture))) {
    throw std::runtime_error(picture + ": cannot write the PNG");
  }
  const double total_wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  WriteSummaryJson(out_dir / "summary.json", args, *source, run, total_wall_s);
  PrintSummary(run, out_dir);
}

}  // namespace

void AddOdometryCommand(CLI::App& app) {
  auto args = std::make_shared<OdometryArgs>();
  CLI::App* command = app.add_subcommand(
      "odometry", "Run the per-entity laser odometry on a log: trajectory, per-scan CSV, picture");
  command->add_option("--log", args->log, "Input log: CARMEN (.clf, plain or gzip) or PeNa log")
      ->required();
  command->add_option("--out", args->out, "Output directory (created if missing)")->required();
  std::vector<std::string> prior_names;
  for (const auto& [name, prior] : kPriors) prior_names.push_back(name);
  command->add_option("--prior", args->prior, "Motion prior between scans")
      ->check(CLI::IsMember(prior_names))
      ->capture_default_str();
  command->add_option("--confirm", args->confirm,
                     "Keep only reference points a second keyframe saw again (tilt robustness "
                     "for body-worn lasers); auto = for people only")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->capture_default_str();
  command->add_flag("--no-matching", args->no_matching,
                    "Dead reckoning / odometry alone: no scan matching (for comparison)");
  command->add_flag("--skip-malformed", args->read.skip_malformed,
                    "Skip malformed lines (and count them) instead of stopping at the first");
  command
      ->add_option("--max-range", args->read.carmen_max_range_m,
                   "CARMEN maximum range, metres: ranges at or above it are no-returns")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  AddCarmenSweepOptions(*command, args->read);
  command->add_option("--start", args->start,
                      "Start pose X,Y,THETA_DEG (m, m, deg); default: see docs/odometry.md");
  command->add_option("--set", args->settings,
                      "NAME=VALUE: change a numeric chain option (for sweeps; names in "
                      "docs/odometry.md); repeatable");
  command->add_flag("--quiet", args->quiet, "No progress line on stderr");
  command->callback([args] { RunOdometry(*args); });
}

void AddCarmenSweepOptions(CLI::App& command, io::ReadOptions& read) {
  command
      .add_option("--carmen-sweep", read.carmen_sweep_s,
                  "CARMEN scans: seconds from the first beam to the last (SICK LMS 2xx: 1/150); "
                  "0: all beams at the stamp")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--carmen-interlace", read.carmen_interlace,
                  "CARMEN scans: sweeps interleaved into one scan, a mirror turn apart; 0: from "
                  "the beam spacing (SICK LMS 2xx: 2 at 0.5 deg, 4 at 0.25 deg)")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
}

}  // namespace pena::cli
