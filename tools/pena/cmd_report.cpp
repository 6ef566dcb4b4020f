// pena report: the team demo's report (docs/demo.md). Reads a simulated mission (truth, observed
// walls, plan) and a run directory written by deploy/demo/run-team.sh (each entity's
// trajectory.tum and line_map.csv, the fusion's global_map.csv, traffic.csv, pose_latency.csv and
// the poses it received), and writes global_map.{csv,svg,png}, report.md and report.json.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "commands.hpp"
#include "report_breakdown.hpp"
#include "pena/eval/line_map_error.hpp"
#include "pena/eval/trajectory_error.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/line_svg.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::cli {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::string mission, run, out;
};

// One entity: its paths and their errors against its truth (mission frame, no alignment).
struct EntityReport {
  std::string id;
  geometry::Trajectory truth, corrected, uncorrected;
  std::optional<eval::TrajectoryErrorSummary> with, without;
  double duration_s = 0.0;  // mission seconds of its truth
};

// One row of a CSV file split at commas (the files here hold no quoted commas).
std::vector<std::vector<std::string>> ReadCsvRows(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path, 0, "cannot open");
  std::vector<std::vector<std::string>> rows;
  std::string line;
  for (std::getline(in, line); std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
    if (!fields.empty()) rows.push_back(fields);
  }
  return rows;
}

std::vector<geometry::Segment2> Segments(const std::vector<io::LineRow>& rows) {
  std::vector<geometry::Segment2> out;
  for (const io::LineRow& row : rows) out.push_back(row.segment);
  return out;
}

std::optional<eval::TrajectoryErrorSummary> Score(const geometry::Trajectory& estimate,
                                                  const geometry::Trajectory& truth) {
  if (estimate.empty()) return std::nullopt;
  try {
    return eval::EvaluateAgainstTruth(estimate, truth);
  } catch (const std::invalid_argument& error) {
    std::cerr << "pena report: warning: " << error.what() << '\n';
    return std::nullopt;
  }
}

std::vector<EntityReport> LoadEntities(const ReportArgs& args) {
  std::vector<EntityReport> entities;
  std::vector<fs::path> dirs;
  for (const fs::directory_entry& entry : fs::directory_iterator(args.mission)) {
    if (fs::exists(entry.path() / "truth.tum")) dirs.push_back(entry.path());
  }
  std::sort(dirs.begin(), dirs.end());
  for (const fs::path& dir : dirs) {
    EntityReport e;
    e.id = dir.filename().string();
    e.truth = io::ReadTum(dir / "truth.tum");
    e.duration_s = e.truth.empty() ? 0.0 : e.truth.back().stamp_s - e.truth.front().stamp_s;
    const fs::path corrected = fs::path(args.run) / e.id / "trajectory.tum";
    const fs::path uncorrected = fs::path(args.run) / "fusion" / "poses" / (e.id + "_odom.tum");
    if (fs::exists(corrected)) e.corrected = io::ReadTum(corrected);
    if (fs::exists(uncorrected)) e.uncorrected = io::ReadTum(uncorrected);
    e.with = Score(e.corrected, e.truth);
    e.without = Score(e.uncorrected, e.truth);
    entities.push_back(std::move(e));
  }
  return entities;
}

// The path as segments at least 0.2 m long (pictures stay small).
std::vector<geometry::Segment2> PathSegments(const geometry::Trajectory& path) {
  std::vector<geometry::Segment2> out;
  if (path.empty()) return out;
  Eigen::Vector2d last(path.front().pose.x_m, path.front().pose.y_m);
  for (const geometry::StampedPose2& p : path) {
    const Eigen::Vector2d point(p.pose.x_m, p.pose.y_m);
    if ((point - last).norm() < 0.2) continue;
    out.push_back({last, point});
    last = point;
  }
  return out;
}

const std::vector<std::pair<std::string, cv::Scalar>>& Palette() {
  static const std::vector<std::pair<std::string, cv::Scalar>> palette{
      {"#1f77b4", viz::colors::kBlue}, {"#d62728", viz::colors::kRed},
      {"#9467bd", viz::colors::kPurple}, {"#17becf", viz::colors::kTeal}};
  return palette;
}

struct Layers {
  std::vector<geometry::Segment2> plan, observed, plan_only;
};

void WritePictures(const fs::path& out, const Layers& layers,
                   const std::vector<EntityReport>& entities) {
  std::vector<io::SvgLayer> svg{{"a priori plan", "#c8c8c8", 0.15, layers.plan},
                                {"global map (observed)", "#000000", 0.06, layers.observed},
                                {"global map (plan only)", "#ff8c00", 0.06, layers.plan_only}};
  Eigen::Vector2d min_m(1e9, 1e9), max_m(-1e9, -1e9);
  auto grow = [&](const std::vector<geometry::Segment2>& segments) {
    for (const geometry::Segment2& s : segments) {
      min_m = min_m.cwiseMin(s.start_m).cwiseMin(s.end_m);
      max_m = max_m.cwiseMax(s.start_m).cwiseMax(s.end_m);
    }
  };
  grow(layers.plan);
  grow(layers.observed);
  for (std::size_t i = 0; i < entities.size(); ++i) {
    const std::string& colour = Palette()[i % Palette().size()].first;
    svg.push_back({"true path " + entities[i].id, "#2ca02c", 0.03, PathSegments(entities[i].truth)});
    svg.push_back({"estimated path " + entities[i].id, colour, 0.05,
                   PathSegments(entities[i].corrected)});
    grow(svg.back().segments);
  }
  io::WriteLineSvg(out / "global_map.svg", svg);
  viz::MapCanvasOptions options;
  options.legend_panel_px = 260;
  viz::MapCanvas canvas(min_m - Eigen::Vector2d(1, 1), max_m + Eigen::Vector2d(1, 1), options);
  canvas.DrawSegments(layers.plan, viz::colors::kLightGray, 4);
  canvas.DrawSegments(layers.plan_only, viz::colors::kOrange, 2);
  canvas.DrawSegments(layers.observed, viz::colors::kBlack, 2);
  canvas.AddLegendEntry("a priori plan", viz::colors::kLightGray);
  canvas.AddLegendEntry("global map (observed)", viz::colors::kBlack);
  canvas.AddLegendEntry("global map (plan only)", viz::colors::kOrange);
  canvas.AddLegendEntry("true paths", viz::colors::kGreen);
  for (std::size_t i = 0; i < entities.size(); ++i) {
    canvas.DrawSegments(PathSegments(entities[i].truth), viz::colors::kGreen, 1);
    const cv::Scalar& colour = Palette()[i % Palette().size()].second;
    canvas.DrawSegments(PathSegments(entities[i].corrected), colour, 1);
    canvas.AddLegendEntry(entities[i].id + " estimated", colour);
  }
  canvas.DrawScaleBar();
  canvas.DrawLegend();
  const std::string png = (out / "global_map.png").string();
  if (!cv::imwrite(png, canvas.image())) throw std::runtime_error(png + ": cannot write the PNG");
}

std::string ErrorJson(const std::optional<eval::TrajectoryErrorSummary>& s) {
  if (!s) return "null";
  return "{\"rmse_m\": " + Fixed(s->translation_rmse_m, 4) + ", \"max_m\": " +
         Fixed(s->max_translation_error_m, 4) + ", \"final_m\": " +
         Fixed(s->final_position_error_m, 4) + ", \"heading_rmse_deg\": " +
         Fixed(s->heading_rmse_deg, 3) + ", \"poses\": " + std::to_string(s->poses_matched) + "}";
}

std::string Cell(const std::optional<eval::TrajectoryErrorSummary>& s) {
  return s ? Fixed(s->translation_rmse_m, 3) + " / " + Fixed(s->max_translation_error_m, 3) +
                 " / " + Fixed(s->heading_rmse_deg, 2)
           : "n/a";
}

void WriteReports(const ReportArgs& args, const std::vector<EntityReport>& entities,
                  const std::vector<MapScore>& maps, const std::vector<MapScore>& breakdown) {
  const fs::path out(args.out);
  const fs::path fusion = fs::path(args.run) / "fusion";
  const auto traffic = ReadCsvRows(fusion / "traffic.csv");
  const auto latency = ReadCsvRows(fusion / "pose_latency.csv");
  std::ostringstream md, json;
  md << "# PeNa team demo report\n\nMission: `" << args.mission << "`; run: `" << args.run
     << "`.\n\n## Accuracy per entity\n\nTranslation RMSE / max error (m) / heading RMSE (deg) "
        "against truth, mission frame, no alignment. *With* = the entity's published "
        "world_from_body (fusion corrections applied); *without* = its own laser odometry "
        "(odom_from_body of the same poses).\n\n| entity | with corrections | without | poses |\n"
        "|---|---|---|---|\n";
  json << "{\n  \"entities\": [";
  for (std::size_t i = 0; i < entities.size(); ++i) {
    const EntityReport& e = entities[i];
    md << "| " << e.id << " | " << Cell(e.with) << " | " << Cell(e.without) << " | "
       << e.corrected.size() << " |\n";
    json << (i ? ",\n" : "\n") << "    {\"id\": " << JsonString(e.id) << ", \"with_corrections\": "
         << ErrorJson(e.with) << ", \"without_corrections\": " << ErrorJson(e.without)
         << ", \"mission_s\": " << Fixed(e.duration_s, 2) << "}";
  }
  md << "\n## Global map against the union of observed walls (`observed.csv`)\n\n"
        "| map | segments | coverage | precision | segments per wall |\n|---|---|---|---|---|\n";
  json << "\n  ],\n  \"maps\": [";
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const eval::LineMapErrorSummary& s = maps[i].summary;
    md << "| " << maps[i].name << " | " << s.map_segments << " | " << Fixed(100 * s.coverage, 1)
       << "% | " << Fixed(100 * s.precision, 1) << "% | " << Fixed(s.fragmentation, 2) << " |\n";
    json << (i ? ",\n" : "\n") << "    {\"name\": " << JsonString(maps[i].name)
         << ", \"segments\": " << s.map_segments << ", \"coverage\": " << Fixed(s.coverage, 4)
         << ", \"precision\": " << Fixed(s.precision, 4)
         << ", \"fragmentation\": " << Fixed(s.fragmentation, 3) << "}";
  }
  md << BreakdownTable(breakdown, maps[0].summary.map_length_m - maps[0].summary.precise_length_m);
  md << "\n## Bytes per topic and entity (as counted by pena-fusion: serialised CDR payload)\n\n"
        "| direction | topic | entity | samples | bytes | bytes/s (mission) |\n"
        "|---|---|---|---|---|---|\n";
  json << "\n  ],\n  \"traffic\": [";
  for (std::size_t i = 0; i < traffic.size(); ++i) {
    const auto& row = traffic[i];
    if (row.size() < 5) throw io::InputError(fusion / "traffic.csv", i + 2, "expected 5 fields");
    double duration_s = 0.0;
    for (const EntityReport& e : entities) {
      if (e.id == row[2]) duration_s = e.duration_s;
    }
    for (const EntityReport& e : entities) {
      if (row[2].empty()) duration_s = std::max(duration_s, e.duration_s);
    }
    const double rate = duration_s > 0 ? std::stod(row[4]) / duration_s : 0.0;
    md << "| " << row[0] << " | " << row[1] << " | " << (row[2].empty() ? "(all)" : row[2])
       << " | " << row[3] << " | " << row[4] << " | " << Fixed(rate, 0) << " |\n";
    json << (i ? ",\n" : "\n") << "    {\"direction\": " << JsonString(row[0]) << ", \"topic\": "
         << JsonString(row[1]) << ", \"entity\": " << JsonString(row[2]) << ", \"samples\": "
         << row[3] << ", \"bytes\": " << row[4] << ", \"bytes_per_s\": " << Fixed(rate, 1) << "}";
  }
  md << "\n## Pose latency, entity to pena-fusion (DDS source timestamp to take)\n\n"
        "| entity | samples | p50 ms | p99 ms |\n|---|---|---|---|\n";
  json << "\n  ],\n  \"pose_latency\": [";
  for (std::size_t i = 0; i < latency.size(); ++i) {
    const auto& row = latency[i];
    if (row.size() < 4) throw io::InputError(fusion / "pose_latency.csv", i + 2, "expected 4 fields");
    md << "| " << row[0] << " | " << row[1] << " | " << row[2] << " | " << row[3] << " |\n";
    json << (i ? ",\n" : "\n") << "    {\"entity\": " << JsonString(row[0]) << ", \"samples\": "
         << row[1] << ", \"p50_ms\": " << row[2] << ", \"p99_ms\": " << row[3] << "}";
  }
  json << "\n  ]\n}\n";
  md << "\nFigures: `global_map.png`, `global_map.svg` (plan grey, merged map black, plan-only "
        "pieces orange, true paths green, estimated paths coloured).\n";
  std::ofstream(out / "report.md") << md.str();
  std::ofstream(out / "report.json") << json.str();
}

void RunReport(const ReportArgs& args) {
  const fs::path mission(args.mission), run(args.run), out(args.out);
  fs::create_directories(out);
  const std::vector<io::LineRow> global = io::ReadLineCsv(run / "fusion" / "global_map.csv");
  Layers layers;
  layers.plan = Segments(io::ReadLineCsv(mission / "apriori.csv"));
  for (const io::LineRow& row : global) {
    (ObservedRow(row) ? layers.observed : layers.plan_only).push_back(row.segment);
  }
  const auto observed_walls = Segments(io::ReadLineCsv(mission / "observed.csv"));
  std::vector<geometry::Segment2> all = layers.observed;
  all.insert(all.end(), layers.plan_only.begin(), layers.plan_only.end());
  std::vector<MapScore> maps{
      {"global map, segments some entity saw", eval::EvaluateLineMap(layers.observed, observed_walls)},
      {"global map incl. plan-only pieces", eval::EvaluateLineMap(all, observed_walls)}};
  const std::vector<EntityReport> entities = LoadEntities(args);
  for (const EntityReport& e : entities) {
    const fs::path local = run / e.id / "line_map.csv";
    if (!fs::exists(local)) continue;
    maps.push_back({e.id + "'s local map alone",
                    eval::EvaluateLineMap(Segments(io::ReadLineCsv(local)), observed_walls)});
    if (out != run) fs::create_directories(out / e.id);
    const fs::path tum = run / e.id / "trajectory.tum";
    if (out != run && fs::exists(tum)) {
      fs::copy_file(tum, out / e.id / "trajectory.tum", fs::copy_options::overwrite_existing);
    }
  }
  io::WriteLineCsv(out / "global_map.csv", global,
                   ",observations,support_cells,rms_error_m,provenance");
  WritePictures(out, layers, entities);
  const std::vector<MapScore> breakdown = ProvenanceBreakdown(global, observed_walls);
  WriteReports(args, entities, maps, breakdown);
  for (const MapScore& m : breakdown) {
    std::printf("  %-40s %3zu segments, %6.1f m, imprecise %5.1f m (precision %.1f%%)\n",
                m.name.c_str(), m.summary.map_segments, m.summary.map_length_m,
                std::max(0.0, m.summary.map_length_m - m.summary.precise_length_m), 100 * m.summary.precision);
  }
  std::printf("global map: %zu segments (%zu observed); coverage %.1f%%, precision %.1f%%, "
              "%.2f segments per wall\n",
              global.size(), layers.observed.size(), 100 * maps[0].summary.coverage,
              100 * maps[0].summary.precision, maps[0].summary.fragmentation);
  for (const EntityReport& e : entities) {
    std::printf("%-8s RMSE with corrections %s m, without %s m\n", e.id.c_str(),
                e.with ? Fixed(e.with->translation_rmse_m, 3).c_str() : "n/a",
                e.without ? Fixed(e.without->translation_rmse_m, 3).c_str() : "n/a");
  }
  std::printf("wrote %s/report.md, report.json, global_map.{csv,svg,png}\n", args.out.c_str());
}

}  // namespace

void AddReportCommand(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand("report", "Report of a team demo run (docs/demo.md)");
  cmd->add_option("--mission", args->mission, "Simulated mission directory (pena simulate)")
      ->required();
  cmd->add_option("--run", args->run, "Run directory (deploy/demo/run-team.sh)")->required();
  cmd->add_option("--out", args->out, "Output directory (default: the run directory)");
  cmd->callback([args] {
    if (args->out.empty()) args->out = args->run;
    RunReport(*args);
  });
}

}  // namespace pena::cli
