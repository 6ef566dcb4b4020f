// pena eval: scores an estimated trajectory against ground-truth relations (Kuemmerle et al. 2009)
// and/or a truth trajectory, and/or a line map against the walls the laser saw. Metric definitions
// are in docs/evaluation.md and docs/line-extraction.md.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "commands.hpp"
#include "pena/eval/line_map_error.hpp"
#include "pena/eval/relation_error.hpp"
#include "pena/eval/trajectory_error.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/trajectory_io.hpp"

namespace pena::cli {

namespace {

// What the user asked for; each reference given adds one section to the report.
struct EvalArgs {
  std::string trajectory;
  std::string relations;
  std::string truth;
  std::string lines;
  std::string walls;
  bool align = false;
  bool json = false;
  double stamp_tolerance_s = eval::kDefaultStampTolerance_s;
  // The line map's tolerances (the targets are judged at 10 cm and 10 deg; wider ones show how far
  // off a map from drifting poses is).
  double distance_tolerance_m = eval::LineMapErrorOptions{}.distance_m;
  double angle_tolerance_deg = eval::LineMapErrorOptions{}.angle_rad * 180.0 / std::numbers::pi;
};

eval::LineMapErrorOptions LineTolerances(const EvalArgs& args) {
  eval::LineMapErrorOptions options;
  options.distance_m = args.distance_tolerance_m;
  options.angle_rad = args.angle_tolerance_deg * std::numbers::pi / 180.0;
  return options;
}

// The results of every section that ran, for one report.
struct EvalReport {
  std::size_t poses = 0;
  std::optional<eval::RelationErrorSummary> relations;
  std::optional<eval::TrajectoryErrorSummary> truth;
  std::optional<eval::LineMapErrorSummary> lines;
};

// Full double precision: JSON is for scripts, which round for themselves.
std::string JsonNumber(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

std::string JsonMeanStd(const eval::MeanStd& value) {
  return "{\"mean\": " + JsonNumber(value.mean) + ", \"std\": " + JsonNumber(value.std) + "}";
}

void PrintRelationRow(const char* label, const eval::MeanStd& value, int decimals) {
  std::printf("  %-22s %14s %14s\n", label, Fixed(value.mean, decimals).c_str(),
              Fixed(value.std, decimals).c_str());
}

void PrintRelationTable(const EvalArgs& args, const eval::RelationErrorSummary& summary) {
  std::printf("relations %s: %zu used, %zu skipped (a stamp not within %s ms of a pose)\n",
              args.relations.c_str(), summary.relations_used, summary.relations_skipped,
              Fixed(args.stamp_tolerance_s * 1e3, 3).c_str());
  std::printf("  %-22s %14s %14s\n", "", "mean", "std");
  PrintRelationRow("translation [m]", summary.translation_m, 4);
  PrintRelationRow("translation^2 [m^2]", summary.translation_sq_m2, 4);
  PrintRelationRow("rotation [deg]", summary.rotation_deg, 3);
  PrintRelationRow("rotation^2 [deg^2]", summary.rotation_sq_deg2, 3);
  std::printf("  %-22s %14s %14s %14s\n", "", "median", "95th pct", "max");
  const auto spread_row = [](const char* label, const eval::Spread& value, int decimals) {
    std::printf("  %-22s %14s %14s %14s\n", label, Fixed(value.median, decimals).c_str(),
                Fixed(value.p95, decimals).c_str(), Fixed(value.max, decimals).c_str());
  };
  spread_row("translation [m]", summary.translation_spread_m, 4);
  spread_row("rotation [deg]", summary.rotation_spread_deg, 3);
}

void PrintTruthTable(const EvalArgs& args, const eval::TrajectoryErrorSummary& summary) {
  std::printf("truth %s: %zu poses matched, %zu skipped (no truth within %s ms)\n",
              args.truth.c_str(), summary.poses_matched, summary.poses_skipped,
              Fixed(args.stamp_tolerance_s * 1e3, 3).c_str());
  if (args.align) {
    const geometry::Pose2& t = summary.truth_from_estimate;
    std::printf("  aligned: truth_from_estimate x %s m, y %s m, theta %s deg\n",
                Fixed(t.x_m, 3).c_str(), Fixed(t.y_m, 3).c_str(),
                Fixed(t.theta_rad * 180.0 / std::numbers::pi, 3).c_str());
  }
  std::printf("  %-28s %12s\n", "translation RMSE [m]",
              Fixed(summary.translation_rmse_m, 4).c_str());
  std::printf("  %-28s %12s\n", "heading RMSE [deg]", Fixed(summary.heading_rmse_deg, 3).c_str());
  std::printf("  %-28s %12s\n", "max translation error [m]",
              Fixed(summary.max_translation_error_m, 4).c_str());
  std::printf("  %-28s %12s\n", "final position error [m]",
              Fixed(summary.final_position_error_m, 4).c_str());
  std::printf("  %-28s %12s\n", "max heading error [deg]",
              Fixed(summary.max_heading_error_deg, 3).c_str());
  std::printf("  %-28s %12s\n", "final heading error [deg]",
              Fixed(summary.final_heading_error_deg, 3).c_str());
  std::printf("  %-28s %12s\n", "truth path length [m]",
              Fixed(summary.truth_path_length_m, 3).c_str());
  std::printf("  %-28s %12s\n", "final error [% of path]",
              Fixed(summary.final_error_percent_of_path, 3).c_str());
}

// The number `value` holds, whole, or NaN.
double ParsedNumber(const std::string& value) {
  try {
    std::size_t used = 0;
    const double number = std::stod(value, &used);
    if (used == value.size()) return number;
  } catch (const std::exception&) {
    // not a number: NaN
  }
  return std::nan("");
}

// CLI11 checks of the line tolerances, with the unit in their messages (CLI11's own PositiveNumber
// names DBL_MAX, and its Range lets NaN through).
std::string PositiveMetres(const std::string& value) {
  const double metres = ParsedNumber(value);
  if (std::isfinite(metres) && metres > 0.0) return {};
  return "must be a distance > 0 m, got '" + value + "'";
}

std::string DegreesUpTo90(const std::string& value) {
  const double degrees = ParsedNumber(value);
  if (degrees >= 0.0 && degrees <= 90.0) return {};  // false for NaN
  return "must be an angle in [0, 90] deg, got '" + value + "'";
}

// A tolerance as the user would write it: 10, not 10.0; 2.5, not 3.
std::string Compact(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", value);
  return buffer;
}

void PrintLineTable(const EvalArgs& args, const eval::LineMapErrorSummary& summary) {
  std::printf("line map %s: %zu segments, %s m; walls %s: %zu, %s m\n", args.lines.c_str(),
              summary.map_segments, Fixed(summary.map_length_m, 2).c_str(), args.walls.c_str(),
              summary.walls, Fixed(summary.wall_length_m, 2).c_str());
  std::printf("  %-46s %8s %%\n",
              ("coverage (wall within " + Compact(args.distance_tolerance_m * 100) + " cm and " +
               Compact(args.angle_tolerance_deg) + " deg)")
                  .c_str(),
              Fixed(summary.coverage * 100.0, 2).c_str());
  std::printf("  %-46s %8s %%\n",
              ("precision (map within " + Compact(args.distance_tolerance_m * 100) + " cm of a wall)")
                  .c_str(),
              Fixed(summary.precision * 100.0, 2).c_str());
  std::printf("  %-46s %8s\n", "fragmentation (map segments per wall)",
              Fixed(summary.fragmentation, 3).c_str());
}

std::string LinesJson(const EvalArgs& args, const eval::LineMapErrorSummary& summary) {
  return "{\"file\": " + JsonString(args.lines) + ", \"walls_file\": " + JsonString(args.walls) +
         ", \"segments\": " + std::to_string(summary.map_segments) +
         ", \"walls\": " + std::to_string(summary.walls) +
         ", \"map_length_m\": " + JsonNumber(summary.map_length_m) +
         ", \"wall_length_m\": " + JsonNumber(summary.wall_length_m) +
         ", \"coverage\": " + JsonNumber(summary.coverage) +
         ", \"precision\": " + JsonNumber(summary.precision) +
         ", \"fragmentation\": " + JsonNumber(summary.fragmentation) +
         ", \"walls_matched\": " + std::to_string(summary.walls_matched) +
         ", \"distance_tolerance_m\": " + JsonNumber(args.distance_tolerance_m) +
         ", \"angle_tolerance_deg\": " + JsonNumber(args.angle_tolerance_deg) + "}";
}

std::string JsonSpread(const eval::Spread& value) {
  return "{\"median\": " + JsonNumber(value.median) + ", \"p95\": " + JsonNumber(value.p95) +
         ", \"max\": " + JsonNumber(value.max) + "}";
}

std::string RelationJson(const EvalArgs& args, const eval::RelationErrorSummary& summary) {
  return "{\"file\": " + JsonString(args.relations) +
         ", \"used\": " + std::to_string(summary.relations_used) +
         ", \"skipped\": " + std::to_string(summary.relations_skipped) +
         ", \"translational_error_m\": " + JsonMeanStd(summary.translation_m) +
         ", \"translational_error_sq_m2\": " + JsonMeanStd(summary.translation_sq_m2) +
         ", \"rotational_error_deg\": " + JsonMeanStd(summary.rotation_deg) +
         ", \"rotational_error_sq_deg2\": " + JsonMeanStd(summary.rotation_sq_deg2) +
         ", \"translational_error_spread_m\": " + JsonSpread(summary.translation_spread_m) +
         ", \"rotational_error_spread_deg\": " + JsonSpread(summary.rotation_spread_deg) + "}";
}

std::string TruthJson(const EvalArgs& args, const eval::TrajectoryErrorSummary& summary) {
  const geometry::Pose2& t = summary.truth_from_estimate;
  return "{\"file\": " + JsonString(args.truth) +
         ", \"matched\": " + std::to_string(summary.poses_matched) +
         ", \"skipped\": " + std::to_string(summary.poses_skipped) +
         ", \"aligned\": " + (args.align ? "true" : "false") +
         ", \"truth_from_estimate\": {\"x_m\": " + JsonNumber(t.x_m) +
         ", \"y_m\": " + JsonNumber(t.y_m) + ", \"theta_rad\": " + JsonNumber(t.theta_rad) + "}" +
         ", \"translation_rmse_m\": " + JsonNumber(summary.translation_rmse_m) +
         ", \"heading_rmse_deg\": " + JsonNumber(summary.heading_rmse_deg) +
         ", \"max_translation_error_m\": " + JsonNumber(summary.max_translation_error_m) +
         ", \"final_position_error_m\": " + JsonNumber(summary.final_position_error_m) +
         ", \"max_heading_error_deg\": " + JsonNumber(summary.max_heading_error_deg) +
         ", \"final_heading_error_deg\": " + JsonNumber(summary.final_heading_error_deg) +
         ", \"truth_path_length_m\": " + JsonNumber(summary.truth_path_length_m) +
         ", \"final_error_percent_of_path\": " + JsonNumber(summary.final_error_percent_of_path) +
         "}";
}

void PrintJson(const EvalArgs& args, const EvalReport& report) {
  std::string json;
  if (!args.trajectory.empty()) {
    json = "\"trajectory\": " + JsonString(args.trajectory) +
           ", \"poses\": " + std::to_string(report.poses) +
           ", \"stamp_tolerance_s\": " + JsonNumber(args.stamp_tolerance_s);
  }
  if (report.relations) json += ", \"relations\": " + RelationJson(args, *report.relations);
  if (report.truth) json += ", \"truth\": " + TruthJson(args, *report.truth);
  if (report.lines) {
    if (!json.empty()) json += ", ";
    json += "\"lines\": " + LinesJson(args, *report.lines);
  }
  std::cout << "{" << json << "}\n";
}

std::vector<geometry::Segment2> ReadSegments(const std::string& path) {
  std::vector<geometry::Segment2> segments;
  for (const io::LineRow& row : io::ReadLineCsv(path)) segments.push_back(row.segment);
  return segments;
}

void EvaluateTrajectory(const EvalArgs& args, EvalReport& report) {
  if (args.relations.empty() && args.truth.empty()) {
    throw CLI::RequiredError("--relations R or --truth T (or both) with --trajectory");
  }
  const geometry::Trajectory estimate = io::ReadTum(args.trajectory);
  report.poses = estimate.size();
  if (!args.relations.empty()) {
    report.relations = eval::EvaluateRelations(estimate, io::ReadRelations(args.relations),
                                               {.stamp_tolerance_s = args.stamp_tolerance_s});
  }
  if (!args.truth.empty()) {
    report.truth = eval::EvaluateAgainstTruth(
        estimate, io::ReadTum(args.truth),
        {.stamp_tolerance_s = args.stamp_tolerance_s, .align = args.align});
  }
}

// Dispatches on the inputs given: a trajectory with its references, a line map with its walls.
void RunEval(const EvalArgs& args) {
  if (args.trajectory.empty() && args.lines.empty()) {
    throw CLI::RequiredError("--trajectory T or --lines L (or both)");
  }
  EvalReport report;
  if (!args.trajectory.empty()) EvaluateTrajectory(args, report);
  if (!args.lines.empty()) {
    report.lines = eval::EvaluateLineMap(ReadSegments(args.lines), ReadSegments(args.walls),
                                         LineTolerances(args));
  }
  if (args.json) return PrintJson(args, report);
  if (!args.trajectory.empty()) {
    std::printf("trajectory %s: %zu poses\n", args.trajectory.c_str(), report.poses);
  }
  if (report.relations) PrintRelationTable(args, *report.relations);
  if (report.truth) PrintTruthTable(args, *report.truth);
  if (report.lines) PrintLineTable(args, *report.lines);
}

}  // namespace

void AddEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* command = app.add_subcommand(
      "eval",
      "Score a trajectory against ground-truth relations and/or a truth trajectory, and/or a "
      "line map against the walls the laser saw");
  CLI::Option* trajectory =
      command->add_option("--trajectory", args->trajectory, "Estimated trajectory (TUM text)");
  command
      ->add_option("--relations", args->relations,
                   "Ground-truth relations (Freiburg .relations): Kuemmerle relation errors")
      ->needs(trajectory);
  CLI::Option* truth =
      command
          ->add_option("--truth", args->truth,
                       "Truth trajectory (TUM text): absolute errors, final-position %")
          ->needs(trajectory);
  CLI::Option* walls = command->add_option(
      "--walls", args->walls, "True walls (line CSV, e.g. a simulated mission's observed.csv)");
  CLI::Option* lines =
      command
          ->add_option("--lines", args->lines,
                       "Line map (line CSV): coverage, precision, fragmentation against --walls")
          ->needs(walls);
  walls->needs(lines);
  command
      ->add_flag("--align", args->align,
                 "Rigidly align the estimate to the truth (least squares) before comparing")
      ->needs(truth);
  command
      ->add_option("--distance-tolerance", args->distance_tolerance_m,
                   "Metres: a wall point within this of a map segment is covered, a map point "
                   "within this of a wall is precise")
      ->capture_default_str()
      ->check(CLI::Validator(PositiveMetres, "METRES > 0"))
      ->needs(lines);
  command
      ->add_option("--angle-tolerance", args->angle_tolerance_deg,
                   "Degrees: coverage also needs the segment's direction within this of the wall's")
      ->capture_default_str()
      ->check(CLI::Validator(DegreesUpTo90, "DEGREES 0-90"))
      ->needs(lines);
  command->add_flag("--json", args->json, "Print one JSON object instead of tables");
  command
      ->add_option("--stamp-tolerance", args->stamp_tolerance_s,
                   "Seconds within which two stamps are the same instant")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->callback([args] { RunEval(*args); });
}

}  // namespace pena::cli
