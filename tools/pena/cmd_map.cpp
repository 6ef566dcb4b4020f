// pena map: mapping with known (or estimated) poses. Inserts every scan of a log into one global
// occupancy grid, extracts the line map (paper section 3), merges it in a LineMap, and writes
// DIR/lines.csv, lines.svg, lines.dxf, grid.pgm + grid.yaml (ROS map_server) and map.png. With
// --online the line map is built as an entity does: from a local grid that moves with it,
// extracted at each recentre and merged. Options and outputs: docs/line-map.md.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "commands.hpp"
#include "pena/grid/local_grid.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/dxf_writer.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/line_map_codec.hpp"
#include "pena/io/line_svg.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/ros_map.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/line_map/line_extractor.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::cli {
namespace {

// A TUM pose matches a scan when their stamps differ by at most this (TUM keeps 6 decimals).
constexpr double kStampTolerance_s = 1e-3;

struct MapArgs {
  std::string log;
  std::string trajectory;
  std::string out;
  double resolution_m = 0.05;
  bool online = false;
  bool quiet = false;
  io::ReadOptions read;
};

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

// What the pass over the log produced.
struct MapRun {
  explicit MapRun(const grid::GridOptions& options) : grid(options) {}
  grid::OccupancyGrid grid;
  std::optional<grid::LocalGrid> local;  // --online: the window that moves with the entity
  line_map::LineMap map;                 // the merged line map
  std::string source = "map";            // provenance of its segments: the log's entity id
  long extractions = 0;
  std::string pose_source;  // "trajectory", "logged poses", "odometry"
  long scans = 0;
  long used = 0;
  long skipped_no_pose = 0;
  long refused = 0;  // Insert said no: pose not finite or grid too large
  double wall_s = 0.0;
};

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
        logged = scan->logged_pose.has_value();
        break;
      }
    }
    run_.pose_source = !args_.trajectory.empty() ? "trajectory" : logged ? "logged poses"
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
    run_.wall_s = SecondsSince(started);
  }

 private:
  void StartChain(const std::vector<sensors::SensorRecord>& read_ahead) {
    const double stamp_s = read_ahead.empty() ? 0.0 : sensors::StampOf(read_ahead.front());
    const sensors::EntityKind kind =
        source_.description().kind.value_or(sensors::EntityKind::kRobot);
    chain_.emplace(odometry::LaserOdometryOptions{}, kind, StartPoseOf(read_ahead, source_).world_from_body,
                   stamp_s);
  }

  // The laser sits at the body origin, so world_from_laser is the body pose.
  void Feed(const sensors::SensorRecord& record) {
    std::optional<geometry::Pose2> pose;
    if (chain_) {
      if (const auto estimate = chain_->Add(record)) pose = estimate->world_from_body;
    }
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (scan == nullptr) return;
    ++run_.scans;
    if (!args_.trajectory.empty()) {
      pose = PoseAt(trajectory_, scan->stamp_s);
    } else if (!chain_) {
      pose = scan->logged_pose;
    }
    if (!pose) {
      ++run_.skipped_no_pose;
      return;
    }
    if (run_.grid.Insert(*scan, *pose)) {
      ++run_.used;
    } else {
      ++run_.refused;
    }
    if (args_.online) FeedLocal(*scan, *pose);
  }

  // The paper's online mode: the local grid is segmented into lines when the entity nears its
  // edge, and the lines merge into the map (so revisits do not grow it).
  void FeedLocal(const sensors::LaserScan& scan, const geometry::Pose2& pose) {
    if (!run_.local) {
      grid::LocalGridOptions options;
      options.grid = run_.grid.options();
      run_.local.emplace(options, Eigen::Vector2d(pose.x_m, pose.y_m));
    }
    if (run_.local->NeedsRecentre(pose)) {
      run_.map.Integrate(line_map::ExtractLines(run_.local->Recentre(pose)), run_.source);
      ++run_.extractions;
    }
    run_.local->Insert(scan, pose);
  }

  const MapArgs& args_;
  const geometry::Trajectory& trajectory_;
  io::LogSource& source_;
  MapRun& run_;
  std::optional<odometry::LaserOdometry> chain_;
};

std::vector<geometry::Segment2> Segments(const std::vector<line_map::LineSegment>& lines) {
  std::vector<geometry::Segment2> segments;
  segments.reserve(lines.size());
  for (const line_map::LineSegment& line : lines) segments.push_back(line.segment);
  return segments;
}

void WriteLines(const std::filesystem::path& out_dir,
                const std::vector<line_map::LineSegment>& lines) {
  std::vector<io::LineRow> rows;
  rows.reserve(lines.size());
  for (const line_map::LineSegment& line : lines) {
    rows.push_back({line.id, line.segment,
                    Fixed(line.support_cells, 0) + "," + Fixed(line.rms_error_m, 4)});
  }
  io::WriteLineCsv(out_dir / "lines.csv", rows, ",support_cells,rms_error_m");
  io::WriteLineSvg(out_dir / "lines.svg", {{"lines", "#d62728", 0.05, Segments(lines)}});
  io::WriteLineDxf(out_dir / "lines.dxf", Segments(lines), "PENA_LINES");
}

// The grid in grey levels (occupied dark, free near white, unknown mid grey) with the lines drawn
// over it in red and a scale bar, like the paper's Figs. 4 and 5.
cv::Mat RenderMap(const grid::GridImage& image, const std::vector<line_map::LineSegment>& lines) {
  const cv::Mat& occupancy = image.occupancy;
  const double res_m = image.resolution_m;
  const Eigen::Vector2d max_m =
      image.origin_m + res_m * Eigen::Vector2d(occupancy.cols, occupancy.rows);
  viz::MapCanvasOptions options;
  options.resolution_m = res_m;
  options.background = cv::Scalar(185, 185, 185);  // unknown: darker than free (>= 221)
  viz::MapCanvas canvas(image.origin_m, max_m, options);
  // DrawPixels takes one colour per call: group the cells into 16 grey levels.
  std::array<std::vector<Eigen::Vector2d>, 16> levels;
  for (int row = 0; row < occupancy.rows; ++row) {
    for (int col = 0; col < occupancy.cols; ++col) {
      const int value = occupancy.at<unsigned char>(row, col);
      if (value == 128) continue;  // unknown: the background
      const double x_m = image.origin_m.x() + (col + 0.5) * res_m;
      const double y_m = image.origin_m.y() + (occupancy.rows - 1 - row + 0.5) * res_m;
      levels[static_cast<std::size_t>(value / 16)].emplace_back(x_m, y_m);
    }
  }
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const double grey = 255.0 - 17.0 * static_cast<double>(level);
    canvas.DrawPixels(levels[level], cv::Scalar(grey, grey, grey));
  }
  canvas.DrawSegments(Segments(lines), viz::colors::kRed, 2);
  canvas.DrawScaleBar();
  canvas.AddLegendEntry("line map (" + std::to_string(lines.size()) + " segments)",
                        viz::colors::kRed);
  canvas.AddLegendEntry("occupancy grid (dark = occupied)", viz::colors::kGray);
  canvas.DrawLegend();
  return canvas.image().clone();
}

std::size_t PngBytes(const cv::Mat& image) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw std::runtime_error("cannot PNG-encode the grid");
  return png.size();
}

double TotalLength(const std::vector<line_map::LineSegment>& lines) {
  double length_m = 0.0;
  for (const line_map::LineSegment& line : lines) length_m += geometry::Length(line.segment);
  return length_m;
}

// Sizes of the map in bytes: the CSV file, the line map as the services send it (a snapshot in
// the line-map codec), the grid as a PNG.
struct MapBytes {
  std::size_t csv = 0;
  std::size_t codec = 0;
  std::size_t png = 0;
};

void PrintSummary(const MapRun& run, const grid::GridImage& image,
                  const std::vector<line_map::LineSegment>& lines, const MapBytes& bytes,
                  double extract_s, double write_s) {
  std::cout << "poses: " << run.pose_source << "; " << run.scans << " scans, " << run.used
            << " used, " << run.skipped_no_pose << " skipped (no pose)";
  if (run.refused > 0) std::cout << ", " << run.refused << " refused by the grid";
  std::cout << "\ngrid " << image.occupancy.cols << " x " << image.occupancy.rows << " cells at "
            << Fixed(image.resolution_m, 3) << " m ("
            << Fixed(image.occupancy.cols * image.resolution_m, 1) << " x "
            << Fixed(image.occupancy.rows * image.resolution_m, 1) << " m)\n";
  std::cout << lines.size() << " segments, total length " << Fixed(TotalLength(lines), 1)
            << " m" << (run.local ? " (online: " + std::to_string(run.extractions) +
                                        " local-grid extractions merged)"
                                  : std::string())
            << "\n";
  std::cout << "line map " << bytes.codec << " bytes (line-map codec snapshot; lines.csv "
            << bytes.csv << ") vs grid PNG " << bytes.png << " bytes: "
            << Fixed(bytes.codec > 0 ? static_cast<double>(bytes.png) /
                                           static_cast<double>(bytes.codec)
                                     : 0.0,
                     1)
            << " times smaller\n";
  std::cout << "time: grid " << Fixed(run.wall_s, 2) << " s, extraction " << Fixed(extract_s, 3)
            << " s, writing " << Fixed(write_s, 2) << " s\n";
}

void RunMap(const MapArgs& args) {
  geometry::Trajectory trajectory;
  if (!args.trajectory.empty()) {
    trajectory = io::ReadTum(args.trajectory);
    if (trajectory.empty()) throw std::runtime_error(args.trajectory + ": no poses");
  }
  const std::unique_ptr<io::LogSource> source = io::OpenLog(args.log, args.read);
  grid::GridOptions grid_options;
  grid_options.resolution_m = args.resolution_m;
  MapRun run(grid_options);
  if (!source->description().entity_id.empty()) run.source = source->description().entity_id;
  PoseFeeder(args, trajectory, *source, run).Run();
  if (run.used == 0) throw std::runtime_error(args.log + ": no scan could be placed in the grid");
  const auto extract_start = Clock::now();
  const grid::GridImage image = run.grid.ToImage();
  // Offline: one extraction from the whole grid; online: the last window's. Either way through
  // the LineMap, which joins the pieces of one wall (docs/line-map.md).
  run.map.Integrate(line_map::ExtractLines(run.local ? run.local->ToImage() : image), run.source);
  const std::vector<line_map::LineSegment> lines = run.map.segments();
  const double extract_s = SecondsSince(extract_start);
  const auto write_start = Clock::now();
  const std::filesystem::path out_dir(args.out);
  std::filesystem::create_directories(out_dir);
  WriteLines(out_dir, lines);
  io::WriteRosMap(out_dir / "grid", image);
  const std::string picture = (out_dir / "map.png").string();
  if (!cv::imwrite(picture, RenderMap(image, lines))) {
    throw std::runtime_error(picture + ": cannot write the PNG");
  }
  const MapBytes bytes{std::filesystem::file_size(out_dir / "lines.csv"),
                       io::EncodeSnapshot(run.map.Snapshot()).size(), PngBytes(image.occupancy)};
  PrintSummary(run, image, lines, bytes, extract_s, SecondsSince(write_start));
}

}  // namespace

void AddMapCommand(CLI::App& app) {
  auto args = std::make_shared<MapArgs>();
  CLI::App* command = app.add_subcommand(
      "map",
      "Build the occupancy grid and line map of a log: lines.csv/svg/dxf, grid.pgm/yaml, PNG");
  command->add_option("--log", args->log, "Input log: CARMEN (.clf/.log, plain or gzip) or PeNa")
      ->required();
  command->add_option("--trajectory", args->trajectory,
                      "Poses (TUM) matched to scan stamps within 1 ms; default: the log's "
                      "logged poses, else laser odometry");
  command->add_option("--out", args->out, "Output directory (created if missing)")->required();
  command->add_option("--resolution", args->resolution_m, "Grid cell size, metres")
      ->check(CLI::Range(0.005, 5.0))
      ->capture_default_str();
  command->add_flag("--skip-malformed", args->read.skip_malformed,
                    "Skip malformed lines (and count them) instead of stopping at the first");
  command
      ->add_option("--max-range", args->read.carmen_max_range_m,
                   "CARMEN maximum range, metres: ranges at or above it are no-returns")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  command->add_flag("--online", args->online,
                    "Build the line map as an entity does: a 20 m local grid moving with it, "
                    "extracted at each recentre and merged (the paper's online mode)");
  command->add_flag("--quiet", args->quiet, "No progress line on stderr");
  command->callback([args] { RunMap(*args); });
}

}  // namespace pena::cli
