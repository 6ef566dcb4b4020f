// pena map: what it writes (lines.csv/svg/dxf, map.png), the byte sizes of the map in its
// encodings and the summary on stdout. Formats: docs/line-extraction.md, docs/line-map.md.
#include <array>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "cli_support.hpp"
#include "cmd_map.hpp"
#include "pena/line_map/map_packing.hpp"
#include "pena/io/dxf_writer.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/line_map_codec.hpp"
#include "pena/io/line_svg.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::cli::map {
namespace {

std::vector<geometry::Segment2> Segments(const std::vector<line_map::LineSegment>& lines) {
  std::vector<geometry::Segment2> segments;
  segments.reserve(lines.size());
  for (const line_map::LineSegment& line : lines) segments.push_back(line.segment);
  return segments;
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

double Ratio(std::size_t big, std::size_t small) {
  return small > 0 ? static_cast<double>(big) / static_cast<double>(small) : 0.0;
}

void PrintSlam(const MapRun& run) {
  if (!run.slam) return;
  const slam::SlamCounts& c = *run.slam;
  std::cout << "slam: " << c.keyframes << " keyframes, " << c.loop_checks << " loop checks ("
            << c.wide_checks << " wide), "
            << c.loop_closures << " closures kept (" << c.loop_rejected << " dropped), "
            << Fixed(run.slam_wall_s, 2) << " s\n";
}

}  // namespace

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

void WriteMapPicture(const std::filesystem::path& path, const grid::GridImage& image,
                     const std::vector<line_map::LineSegment>& lines) {
  if (!cv::imwrite(path.string(), RenderMap(image, lines))) {
    throw std::runtime_error(path.string() + ": cannot write the PNG");
  }
}

MapBytes MeasureBytes(const std::filesystem::path& out_dir, const line_map::LineMap& map,
                      const grid::GridImage& image) {
  const line_map::MapSnapshot snapshot = map.Snapshot();
  return {std::filesystem::file_size(out_dir / "lines.csv"), io::EncodeSnapshot(snapshot).size(),
          line_map::PackSnapshot(snapshot).size(), PngBytes(image.occupancy)};
}

void WriteSummaryJson(const std::filesystem::path& path, const MapArgs& args, const MapRun& run,
                      const grid::GridImage& image, const std::vector<line_map::LineSegment>& lines,
                      double extract_s, double write_s, double total_wall_s) {
  const double log_s = run.first_stamp_s ? run.last_stamp_s - *run.first_stamp_s : 0.0;
  std::ofstream out(path);
  out << "{\"log\": " << JsonString(args.log) << ", \"pose_source\": " << JsonString(run.pose_source)
      << ", \"scans\": " << run.scans << ", \"used\": " << run.used
      << ", \"skipped_no_pose\": " << run.skipped_no_pose << ", \"refused\": " << run.refused;
  if (run.second_pass) out << ", \"bent_scans\": " << run.bent_scans;
  if (const auto& c = run.slam) {
    out << ", \"slam\": {\"keyframes\": " << c->keyframes << ", \"loop_checks\": " << c->loop_checks
        << ", \"wide_checks\": " << c->wide_checks << ", \"loop_matched\": " << c->loop_matched
        << ", \"loop_closures\": " << c->loop_closures
        << ", \"loop_rejected\": " << c->loop_rejected
        << ", \"optimisations\": " << c->optimisations << "}";
  }
  out << ", \"grid_cells\": [" << image.occupancy.cols << ", " << image.occupancy.rows << "]"
      << ", \"segments\": " << lines.size() << ", \"segments_length_m\": " << Fixed(TotalLength(lines), 1)
      << ", \"log_duration_s\": " << Fixed(log_s, 6)
      << ", \"slam_wall_s\": " << Fixed(run.slam_wall_s, 3)
      << ", \"grid_wall_s\": " << Fixed(run.wall_s, 3) << ", \"extract_s\": " << Fixed(extract_s, 3)
      << ", \"write_s\": " << Fixed(write_s, 3) << ", \"total_wall_s\": " << Fixed(total_wall_s, 3)
      << ", \"speed_x_real_time\": " << Fixed(total_wall_s > 0.0 ? log_s / total_wall_s : 0.0, 2)
      << ", \"peak_rss_mb\": " << Fixed(PeakResidentMb(), 1) << ", \"stage_times\": {";
  const char* separator = "";
  if (run.pipeline_stages) {
    out << "\"pipeline\": " << StageTimesJson(*run.pipeline_stages);
    separator = ", ";
  }
  if (run.odometry_stages) {
    out << separator << "\"odometry\": " << StageTimesJson(*run.odometry_stages);
    separator = ", ";
  }
  if (run.slam_stages) out << separator << "\"slam\": " << StageTimesJson(*run.slam_stages);
  out << "}}\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

void PrintSummary(const MapRun& run, const grid::GridImage& image,
                  const std::vector<line_map::LineSegment>& lines, const MapBytes& bytes,
                  double extract_s, double write_s) {
  std::cout << "poses: " << run.pose_source << "; " << run.scans << " scans, " << run.used
            << " used, " << run.skipped_no_pose << " skipped (no pose)";
  if (run.refused > 0) std::cout << ", " << run.refused << " refused by the grid";
  if (run.second_pass) std::cout << ", second pass: " << run.bent_scans << " bent";
  std::cout << "\n";
  PrintSlam(run);
  std::cout << "grid " << image.occupancy.cols << " x " << image.occupancy.rows << " cells at "
            << Fixed(image.resolution_m, 3) << " m ("
            << Fixed(image.occupancy.cols * image.resolution_m, 1) << " x "
            << Fixed(image.occupancy.rows * image.resolution_m, 1) << " m)\n";
  std::cout << lines.size() << " segments, total length " << Fixed(TotalLength(lines), 1)
            << " m" << (run.online ? " (online: " + std::to_string(run.extractions) +
                                        " local-grid extractions merged)"
                                  : std::string())
            << "\n";
  std::cout << "line map " << bytes.packed << " bytes (gateway packing; line-map codec "
            << bytes.codec << ", lines.csv " << bytes.csv << ") vs grid PNG " << bytes.png
            << " bytes: " << Fixed(Ratio(bytes.png, bytes.packed), 1) << " times smaller ("
            << Fixed(Ratio(bytes.png, bytes.codec), 1) << " against the codec)\n";
  std::cout << "time: grid " << Fixed(run.wall_s, 2) << " s, extraction " << Fixed(extract_s, 3)
            << " s, writing " << Fixed(write_s, 2) << " s\n";
}

}  // namespace pena::cli::map
