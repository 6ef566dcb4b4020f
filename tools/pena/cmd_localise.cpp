// pena localise: localisation on an a priori plan (paper section 4): the laser odometry with
// virtual scan matching against the plan, optionally starting from a global localisation. Writes
// DIR/trajectory.tum, status.csv, summary.json and localisation.png. Options, outputs and the
// measured figures: docs/localisation.md.
#include <algorithm>
#include <cmath>
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
#include <string_view>
#include <vector>

#include "cli_support.hpp"
#include "odometry_settings.hpp"
#include "commands.hpp"
#include "pena/eval/stamp_matching.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/plan_reader.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/localisation/localisation_chain.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::cli {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct LocaliseArgs {
  std::string log, map, out, start, map_transform;
  double map_scale = 1.0;
  bool global = false;
  bool every_scan = false;
  bool quiet = false;
  io::ReadOptions read;
  std::vector<std::string> settings;  // --set NAME=VALUE (numeric plan-matching options, for sweeps)
};

// "X,Y,THETA_DEG" -> pose (metres, metres, radians); anything else is a usage error naming `option`.
geometry::Pose2 ParsePose(const std::string& text, const std::string& option) {
  const auto fail = [&] {
    return std::runtime_error(option + ": expected X,Y,THETA_DEG (metres, metres, degrees), got '" +
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
  return {values[0], values[1], values[2] * kDeg};
}

// Applies --set NAME=VALUE to the plan-matching options (names as in MapLocaliserOptions) and,
// prefixed "odometry.", to the odometry underneath (the names of `pena odometry --set`);
// integer options are rounded; unknown names are errors. The options are validated by
// MapLocaliser's constructor as usual.
void ApplySettings(const std::vector<std::string>& settings, localisation::MapLocaliserOptions& o,
                   odometry::LaserOdometryOptions& odometry) {
  constexpr std::string_view kOdometry = "odometry.";
  std::vector<std::string> odometry_settings;
  const std::map<std::string, double*> doubles = {
      {"min_score", &o.min_score},
      {"reacquire_min_score", &o.reacquire_min_score},
      {"window_growth", &o.window_growth},
      {"max_range_m", &o.max_range_m},
      {"degenerate_eigen_ratio", &o.degenerate_eigen_ratio},
      {"along_probe_m", &o.along_probe_m},
      {"along_min_drop", &o.along_min_drop},
      {"recast_min_m", &o.recast_min_m},
      {"recast_min_rad", &o.recast_min_rad},
      {"along_search_m", &o.along_search_m},
      {"along_search_step_m", &o.along_search_step_m},
      {"matcher.threshold_m", &o.matcher.threshold_m}};
  const std::map<std::string, int*> ints = {{"min_hits", &o.min_hits},
                                            {"outside_after_failures", &o.outside_after_failures},
                                            {"oversample", &o.oversample}};
  for (const std::string& setting : settings) {
    if (setting.starts_with(kOdometry)) {
      odometry_settings.push_back(setting.substr(kOdometry.size()));
      continue;
    }
    const auto [name, value] = ParseSetting(setting);
    if (name == "window.size_xy_m") {
      o.window.size_x_m = o.window.size_y_m = value;
    } else if (name == "max_window.size_xy_m") {
      o.max_window.size_x_m = o.max_window.size_y_m = value;
    } else if (const auto d = doubles.find(name); d != doubles.end()) {
      *d->second = value;
    } else if (const auto i = ints.find(name); i != ints.end()) {
      *i->second = static_cast<int>(std::lround(value));
    } else {
      throw std::runtime_error("--set: unknown option '" + name + "' (see docs/localisation.md)");
    }
  }
  ApplyOdometrySettings(odometry_settings, odometry);
}

// The plan in the mission frame: read (CSV, SVG or DXF), scaled to metres, then moved by
// --map-transform.
std::vector<geometry::Segment2> LoadPlan(const LocaliseArgs& args) {
  io::PlanOptions options;
  options.unit_scale_m = args.map_scale;
  if (!args.map_transform.empty()) {
    options.mission_from_plan = ParsePose(args.map_transform, "--map-transform");
  }
  std::vector<geometry::Segment2> plan = io::ReadPlan(args.map, options);
  if (plan.empty()) throw std::runtime_error(args.map + ": the plan has no segments");
  return plan;
}

// Everything the run produced.
struct Run {
  std::vector<localisation::LocalisedPose> poses;
  std::vector<localisation::MapCorrection> rounds;
  std::optional<localisation::GlobalResult> global;  // the one that anchored the start
  double global_stamp_s = 0.0;
  int global_attempts = 0;
  std::string start_source;
  long records = 0;
  double wall_s = 0.0;
};

Run RunChain(const LocaliseArgs& args, io::LogSource& source, std::vector<geometry::Segment2> plan) {
  const auto started = Clock::now();
  std::vector<sensors::SensorRecord> read_ahead;
  while (auto record = source.Next()) {
    read_ahead.push_back(std::move(*record));
    if (std::holds_alternative<sensors::GroundTruth>(read_ahead.back()) ||
        std::holds_alternative<sensors::LaserScan>(read_ahead.back())) break;
  }
  Run run;
  const StartPose rule = StartPoseOf(read_ahead, source);
  const geometry::Pose2 start = args.start.empty() ? rule.world_from_body : ParsePose(args.start, "--start");
  run.start_source = args.global ? "global" : args.start.empty() ? rule.source : "--start";
  localisation::LocalisationChainOptions options;
  options.global_start = args.global;
  options.map.every_scan = args.every_scan;
  ApplySettings(args.settings, options.map, options.odometry);
  const double start_stamp_s = read_ahead.empty() ? 0.0 : sensors::StampOf(read_ahead.front());
  localisation::LocalisationChain chain(options, source.description().kind.value_or(sensors::EntityKind::kRobot),
                                        std::move(plan), start, start_stamp_s);
  ProgressLine progress(!args.quiet);
  const auto feed = [&](const sensors::SensorRecord& record) {
    ++run.records;
    std::optional<localisation::LocalisedPose> pose = chain.Add(record);
    if (!pose) return;
    if (pose->correction) run.rounds.push_back(*pose->correction);
    if (pose->global) {
      ++run.global_attempts;
      if (pose->anchored) run.global = pose->global, run.global_stamp_s = pose->stamp_s;
    }
    run.poses.push_back(std::move(*pose));
    if (progress.Due(SecondsSince(started))) {
      progress.Show(SecondsSince(started), "pena localise: " + std::to_string(run.poses.size()) + " scans");
    }
  };
  for (const sensors::SensorRecord& record : read_ahead) feed(record);
  while (const auto record = source.Next()) feed(*record);
  run.wall_s = SecondsSince(started);
  return run;
}

geometry::Trajectory Trajectory(const Run& run) {
  geometry::Trajectory out;
  for (const auto& p : run.poses) {
    if (p.anchored) out.push_back({p.stamp_s, p.map_from_body});
  }
  return out;
}

void WriteStatusCsv(const std::filesystem::path& path, const Run& run) {
  std::ofstream out(path);
  out << "stamp,status,accepted,confidence,score,hits,points,virtual_points,constraint_ratio,"
         "degenerate,along_drop,window_xy_m,window_theta_deg,correction_x,correction_y,correction_theta_deg,"
         "x,y,theta,recast,first_score\n";
  for (const localisation::MapCorrection& r : run.rounds) {
    const geometry::Pose2& c = r.correction;
    const geometry::Pose2& p = r.map_from_body_after;
    out << Fixed(r.stamp_s, 6) << ',' << localisation::ToString(r.status) << ',' << (r.accepted ? 1 : 0)
        << ',' << Fixed(r.confidence, 3) << ',' << Fixed(r.score, 3) << ',' << r.hits << ',' << r.points
        << ',' << r.virtual_points << ',' << Fixed(r.constraint_ratio, 4) << ',' << (r.degenerate ? 1 : 0)
        << ',' << Fixed(r.along_drop, 3) << ',' << Fixed(r.window_xy_m, 3) << ',' << Fixed(r.window_theta_rad / kDeg, 2) << ','
        << Fixed(c.x_m, 4) << ',' << Fixed(c.y_m, 4) << ',' << Fixed(c.theta_rad / kDeg, 3) << ','
        << Fixed(p.x_m, 4) << ',' << Fixed(p.y_m, 4) << ',' << Fixed(p.theta_rad, 5) << ','
        << (r.recast ? 1 : 0) << ',' << Fixed(r.first_score, 3) << '\n';
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

// Errors against a simulated mission's truth.tum: inside the plan's box (the mapped part) and
// the recovery after each re-entry from outside it.
struct TruthErrors {
  long in_map = 0, outside = 0;
  double in_map_rms_m = 0.0, in_map_heading_rms_deg = 0.0;  // excluding 5 m after re-entries
  double all_in_map_rms_m = 0.0;                            // including them
  std::vector<double> recovery_m;  // per re-entry: walked metres until the error is < 0.15 m
};

bool InBox(const geometry::Pose2& p, const std::vector<geometry::Segment2>& plan) {
  Eigen::Vector2d lo = plan.front().start_m, hi = lo;
  for (const auto& s : plan) lo = lo.cwiseMin(s.start_m).cwiseMin(s.end_m), hi = hi.cwiseMax(s.start_m).cwiseMax(s.end_m);
  return p.x_m >= lo.x() && p.x_m <= hi.x() && p.y_m >= lo.y() && p.y_m <= hi.y();
}

TruthErrors CompareWithTruth(const geometry::Trajectory& estimate, const geometry::Trajectory& truth,
                             const std::vector<geometry::Segment2>& plan) {
  TruthErrors e;
  double sum_sq = 0.0, sum_all_sq = 0.0, heading_sq = 0.0;
  long all = 0;
  bool was_in = true;
  double since_entry_m = 1e9;
  std::optional<geometry::Pose2> last_truth;
  std::optional<double> recovering;
  for (const auto& est : estimate) {
    const auto index = eval::FindStamp(truth, est.stamp_s);
    if (!index) continue;
    const geometry::Pose2& t = truth[*index].pose;
    if (last_truth) since_entry_m += std::hypot(t.x_m - last_truth->x_m, t.y_m - last_truth->y_m);
    last_truth = t;
    const bool in = InBox(t, plan);
    if (in && !was_in) since_entry_m = 0.0, recovering = 0.0;
    was_in = in;
    const double err = std::hypot(est.pose.x_m - t.x_m, est.pose.y_m - t.y_m);
    if (!in) { ++e.outside; continue; }
    if (recovering && err < 0.15) e.recovery_m.push_back(since_entry_m), recovering.reset();
    sum_all_sq += err * err, ++all;
    if (since_entry_m < 5.0) continue;
    const double dh = geometry::NormalizeAngle(est.pose.theta_rad - t.theta_rad) / kDeg;
    sum_sq += err * err, heading_sq += dh * dh, ++e.in_map;
  }
  if (recovering) e.recovery_m.push_back(-1.0);  // never recovered
  const double n = static_cast<double>(e.in_map);
  if (e.in_map > 0) e.in_map_rms_m = std::sqrt(sum_sq / n), e.in_map_heading_rms_deg = std::sqrt(heading_sq / n);
  if (all > 0) e.all_in_map_rms_m = std::sqrt(sum_all_sq / static_cast<double>(all));
  return e;
}

// Like the paper's Fig. 9: the plan, the path on it, stretches judged outside the plan in another
// colour, re-acquisitions ringed; the true path (simulation) underneath.
cv::Mat Picture(const Run& run, const std::vector<geometry::Segment2>& plan, const geometry::Trajectory& truth,
                const std::string& title) {
  Eigen::Vector2d lo = plan.front().start_m, hi = lo;
  for (const auto& s : plan) lo = lo.cwiseMin(s.start_m).cwiseMin(s.end_m), hi = hi.cwiseMax(s.start_m).cwiseMax(s.end_m);
  for (const auto& p : run.poses) {
    if (p.anchored) lo = lo.cwiseMin(Eigen::Vector2d(p.map_from_body.x_m, p.map_from_body.y_m)),
                    hi = hi.cwiseMax(Eigen::Vector2d(p.map_from_body.x_m, p.map_from_body.y_m));
  }
  viz::MapCanvasOptions options;
  options.legend_panel_px = 230;
  viz::MapCanvas canvas(lo.array() - 1.0, hi.array() + 1.0, options);
  canvas.DrawSegments(plan, viz::colors::kBlack, 2);
  std::vector<Eigen::Vector2d> truth_m;
  for (const auto& t : truth) truth_m.emplace_back(t.pose.x_m, t.pose.y_m);
  if (!truth_m.empty()) canvas.DrawPolyline(truth_m, viz::colors::kGreen, 1);
  for (std::size_t i = 1; i < run.poses.size(); ++i) {
    const auto& a = run.poses[i - 1];
    const auto& b = run.poses[i];
    if (!a.anchored || !b.anchored) continue;
    const bool outside = b.status == localisation::MapStatus::kOutsideMap;
    canvas.DrawSegment({{a.map_from_body.x_m, a.map_from_body.y_m}, {b.map_from_body.x_m, b.map_from_body.y_m}},
                       outside ? viz::colors::kRed : viz::colors::kBlue, 2);
  }
  for (const auto& r : run.rounds) {
    if (r.status == localisation::MapStatus::kReacquired) {
      canvas.DrawCircle({r.map_from_body_after.x_m, r.map_from_body_after.y_m}, 0.4, viz::colors::kPurple, 2);
    }
  }
  const auto first = std::find_if(run.poses.begin(), run.poses.end(), [](const auto& p) { return p.anchored; });
  if (first != run.poses.end()) canvas.DrawCircle({first->map_from_body.x_m, first->map_from_body.y_m}, 0.5, viz::colors::kBlack, 2);
  canvas.DrawText(hi + Eigen::Vector2d(-0.5 * (hi.x() - lo.x()), 0.7), title, viz::colors::kBlack);
  canvas.AddLegendEntry("a priori plan", viz::colors::kBlack);
  canvas.AddLegendEntry("path, matched on the plan", viz::colors::kBlue);
  canvas.AddLegendEntry("path, outside the plan", viz::colors::kRed);
  canvas.AddLegendEntry("re-acquired", viz::colors::kPurple);
  if (!truth_m.empty()) canvas.AddLegendEntry("true path", viz::colors::kGreen);
  canvas.DrawScaleBar();
  canvas.DrawLegend();
  return canvas.image();
}

struct Counts {
  long rounds = 0, accepted = 0, reacquired = 0, outside_rounds = 0, outside_scans = 0;
  double mean_confidence = 0.0;  // over accepted rounds
};

Counts CountRun(const Run& run) {
  Counts c;
  for (const auto& r : run.rounds) {
    ++c.rounds;
    if (r.accepted) ++c.accepted, c.mean_confidence += r.confidence;
    if (r.status == localisation::MapStatus::kReacquired) ++c.reacquired;
    if (r.status == localisation::MapStatus::kOutsideMap) ++c.outside_rounds;
  }
  for (const auto& p : run.poses) c.outside_scans += p.status == localisation::MapStatus::kOutsideMap ? 1 : 0;
  if (c.accepted > 0) c.mean_confidence /= static_cast<double>(c.accepted);
  return c;
}

std::string GlobalJson(const Run& run) {
  if (!run.global) return "null";
  std::string out = "{\"stamp\": " + Fixed(run.global_stamp_s, 6) + ", \"attempts\": " +
                    std::to_string(run.global_attempts) + ", \"margin\": " + Fixed(run.global->margin, 3) +
                    ", \"hypotheses\": [";
  for (std::size_t i = 0; i < run.global->hypotheses.size(); ++i) {
    const auto& h = run.global->hypotheses[i];
    out += (i ? ", " : "") + std::string("{\"x\": ") + Fixed(h.map_from_body.x_m, 3) + ", \"y\": " +
           Fixed(h.map_from_body.y_m, 3) + ", \"theta_deg\": " + Fixed(h.map_from_body.theta_rad / kDeg, 2) +
           ", \"score\": " + Fixed(h.score, 3) + "}";
  }
  return out + "]}";
}

std::string TruthJson(const std::optional<TruthErrors>& e) {
  if (!e) return "null";
  std::string recovery = "[";
  for (std::size_t i = 0; i < e->recovery_m.size(); ++i) recovery += (i ? ", " : "") + Fixed(e->recovery_m[i], 2);
  return "{\"in_map_scans\": " + std::to_string(e->in_map) + ", \"outside_scans\": " + std::to_string(e->outside) +
         ", \"in_map_rms_m\": " + Fixed(e->in_map_rms_m, 4) + ", \"in_map_heading_rms_deg\": " +
         Fixed(e->in_map_heading_rms_deg, 3) + ", \"all_in_map_rms_m\": " + Fixed(e->all_in_map_rms_m, 4) +
         ", \"recovery_walk_m\": " + recovery + "]}";
}

void WriteSummary(const std::filesystem::path& path, const LocaliseArgs& args, const Run& run,
                  const std::optional<TruthErrors>& truth) {
  const Counts c = CountRun(run);
  std::ofstream out(path);
  out << "{\"log\": " << JsonString(args.log) << ", \"map\": " << JsonString(args.map)
      << ", \"start_pose_source\": " << JsonString(run.start_source) << ", \"records\": " << run.records
      << ", \"scans\": " << run.poses.size() << ", \"rounds\": " << c.rounds << ", \"accepted\": " << c.accepted
      << ", \"reacquired\": " << c.reacquired << ", \"outside_rounds\": " << c.outside_rounds
      << ", \"outside_scans\": " << c.outside_scans << ", \"mean_confidence\": " << Fixed(c.mean_confidence, 3)
      << ", \"global\": " << GlobalJson(run) << ", \"truth\": " << TruthJson(truth)
      << ", \"processing_wall_s\": " << Fixed(run.wall_s, 3) << "}\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

// truth.tum next to a simulated entity's native log, if there is one.
geometry::Trajectory TruthNextTo(const io::LogSource& source) {
  const std::filesystem::path truth = source.description().path.parent_path() / "truth.tum";
  if (source.description().format != "pena-log" || !std::filesystem::exists(truth)) return {};
  return io::ReadTum(truth);
}

void RunLocalise(const LocaliseArgs& args) {
  const std::vector<geometry::Segment2> plan = LoadPlan(args);
  const std::unique_ptr<io::LogSource> source = io::OpenLog(args.log, args.read);
  const std::filesystem::path out_dir(args.out);
  std::filesystem::create_directories(out_dir);
  const Run run = RunChain(args, *source, plan);
  const geometry::Trajectory estimate = Trajectory(run);
  io::WriteTum(out_dir / "trajectory.tum", estimate);
  WriteStatusCsv(out_dir / "status.csv", run);
  const geometry::Trajectory truth = TruthNextTo(*source);
  std::optional<TruthErrors> errors;
  if (!truth.empty() && !estimate.empty()) errors = CompareWithTruth(estimate, truth, plan);
  const std::string picture = (out_dir / "localisation.png").string();
  const std::string title = std::filesystem::path(args.log).filename().string() + " on " +
                            std::filesystem::path(args.map).filename().string();
  if (!cv::imwrite(picture, Picture(run, plan, truth, title))) throw std::runtime_error(picture + ": cannot write the PNG");
  WriteSummary(out_dir / "summary.json", args, run, errors);
  const Counts c = CountRun(run);
  std::cout << run.poses.size() << " scans, " << c.rounds << " plan rounds: " << c.accepted << " accepted, "
            << c.outside_rounds << " outside the plan, " << c.reacquired << " re-acquired; "
            << Fixed(run.wall_s, 2) << " s wall\n";
  if (errors) {
    std::cout << "against truth.tum: in-map RMS " << Fixed(errors->in_map_rms_m, 3) << " m, heading "
              << Fixed(errors->in_map_heading_rms_deg, 2) << " deg (" << errors->in_map << " scans)\n";
  }
  std::cout << "wrote " << (out_dir / "trajectory.tum").string() << ", status.csv, summary.json, localisation.png\n";
}

}  // namespace

void AddLocaliseCommand(CLI::App& app) {
  auto args = std::make_shared<LocaliseArgs>();
  CLI::App* command = app.add_subcommand(
      "localise", "Localise a log on an a priori plan (virtual scan matching, global start)");
  command->add_option("--log", args->log, "Input log: CARMEN (.clf, plain or gzip) or PeNa log")->required();
  command->add_option("--map", args->map, "A priori plan: line CSV, SVG or DXF (docs/io-formats.md, Plans)")->required();
  command->add_option("--out", args->out, "Output directory (created if missing)")->required();
  command->add_flag("--global", args->global, "Unknown start: localise the first scans on the whole plan");
  command->add_flag("--every-scan", args->every_scan,
                    "Match every scan against the plan, not only at reference changes (paper)");
  command->add_option("--start", args->start, "Start pose X,Y,THETA_DEG on the plan (m, m, deg)");
  command->add_option("--map-scale", args->map_scale, "Plan units to metres (e.g. 0.001 for mm)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--map-transform", args->map_transform,
                      "Mission frame from plan frame X,Y,THETA_DEG, applied after scaling");
  command->add_flag("--skip-malformed", args->read.skip_malformed, "Skip malformed log lines");
  command->add_option("--max-range", args->read.carmen_max_range_m, "CARMEN maximum range, metres")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  command->add_flag("--quiet", args->quiet, "No progress line on stderr");
  command->add_option("--set", args->settings,
                      "NAME=VALUE: change a numeric plan-matching option (for sweeps; names in "
                      "docs/localisation.md); repeatable");
  command->callback([args] {
    if (args->global && !args->start.empty()) throw std::runtime_error("--global and --start exclude each other");
    RunLocalise(*args);
  });
}

}  // namespace pena::cli
