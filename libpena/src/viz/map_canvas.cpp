#include "pena/viz/map_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace pena::viz {
namespace {

// Sub-pixel drawing: OpenCV takes fixed-point coordinates with this many fractional bits.
constexpr int kShift = 4;
constexpr double kScale = 1 << kShift;

cv::Point Fixed(const cv::Point2d& pixel) {
  return {static_cast<int>(std::lround(pixel.x * kScale)),
          static_cast<int>(std::lround(pixel.y * kScale))};
}

}  // namespace

MapCanvas::MapCanvas(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
                     const MapCanvasOptions& options)
    : min_m_(min_m),
      max_m_(max_m),
      resolution_m_(options.resolution_m),
      margin_px_(options.margin_px),
      legend_panel_px_(options.legend_panel_px) {
  if (!(max_m.x() > min_m.x() && max_m.y() > min_m.y())) {
    throw std::invalid_argument("map_canvas: the world box must have max_m > min_m in x and y");
  }
  if (!(options.resolution_m > 0.0))
    throw std::invalid_argument("map_canvas.resolution_m must be > 0 m");
  if (options.margin_px < 0) throw std::invalid_argument("map_canvas.margin_px must be >= 0 px");
  if (options.legend_panel_px < 0)
    throw std::invalid_argument("map_canvas.legend_panel_px must be >= 0 px");
  if (options.max_size_px <= 2 * options.margin_px) {
    throw std::invalid_argument("map_canvas.max_size_px must exceed twice margin_px");
  }
  const Eigen::Vector2d extent = max_m - min_m;
  // Coarsen the resolution so the larger side fits max_size_px.
  const double usable = static_cast<double>(options.max_size_px - 2 * margin_px_);
  resolution_m_ = std::max(resolution_m_, extent.maxCoeff() / usable);
  const int width =
      static_cast<int>(std::ceil(extent.x() / resolution_m_)) + 2 * margin_px_ + legend_panel_px_;
  const int height = static_cast<int>(std::ceil(extent.y() / resolution_m_)) + 2 * margin_px_;
  image_ = cv::Mat(height, width, CV_8UC3, options.background);
}

cv::Point2d MapCanvas::ToPixel(const Eigen::Vector2d& point_m) const {
  return {static_cast<double>(margin_px_) + (point_m.x() - min_m_.x()) / resolution_m_,
          static_cast<double>(margin_px_) + (max_m_.y() - point_m.y()) / resolution_m_};
}

void MapCanvas::DrawSegment(const geometry::Segment2& segment, const cv::Scalar& color,
                            int thickness_px) {
  cv::line(image_, Fixed(ToPixel(segment.start_m)), Fixed(ToPixel(segment.end_m)), color,
           thickness_px, cv::LINE_AA, kShift);
}

void MapCanvas::DrawSegments(const std::vector<geometry::Segment2>& segments,
                             const cv::Scalar& color, int thickness_px) {
  for (const geometry::Segment2& segment : segments) DrawSegment(segment, color, thickness_px);
}

void MapCanvas::DrawPolyline(const std::vector<Eigen::Vector2d>& points_m, const cv::Scalar& color,
                             int thickness_px) {
  if (points_m.size() < 2) return;
  std::vector<cv::Point> pixels;
  pixels.reserve(points_m.size());
  for (const Eigen::Vector2d& point : points_m) pixels.push_back(Fixed(ToPixel(point)));
  cv::polylines(image_, pixels, false, color, thickness_px, cv::LINE_AA, kShift);
}

void MapCanvas::DrawPoints(const std::vector<Eigen::Vector2d>& points_m, const cv::Scalar& color,
                           int radius_px) {
  for (const Eigen::Vector2d& point : points_m) {
    cv::circle(image_, Fixed(ToPixel(point)), radius_px << kShift, color, cv::FILLED, cv::LINE_AA,
               kShift);
  }
}

void MapCanvas::DrawPixels(const std::vector<Eigen::Vector2d>& points_m,
                           const cv::Scalar& color) {
  // Direct writes: an anti-aliased circle per point is far slower, and runs have millions.
  const cv::Vec3b bgr(cv::saturate_cast<uchar>(color[0]), cv::saturate_cast<uchar>(color[1]),
                      cv::saturate_cast<uchar>(color[2]));
  const auto map_cols = static_cast<double>(image_.cols - legend_panel_px_);
  const auto rows = static_cast<double>(image_.rows);
  for (const Eigen::Vector2d& point : points_m) {
    const cv::Point2d pixel = ToPixel(point);
    // Compared as doubles first: NaN and far-away points never reach the int conversion.
    if (!(pixel.x >= 0.0 && pixel.x < map_cols && pixel.y >= 0.0 && pixel.y < rows)) continue;
    image_.at<cv::Vec3b>(static_cast<int>(pixel.y), static_cast<int>(pixel.x)) = bgr;
  }
}

void MapCanvas::DrawBox(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
                        const cv::Scalar& color, bool filled) {
  cv::rectangle(image_, Fixed(ToPixel({min_m.x(), max_m.y()})),
                Fixed(ToPixel({max_m.x(), min_m.y()})), color, filled ? cv::FILLED : 1, cv::LINE_AA,
                kShift);
}

void MapCanvas::DrawCircle(const Eigen::Vector2d& center_m, double radius_m,
                           const cv::Scalar& color, int thickness_px) {
  const int radius = static_cast<int>(std::lround(radius_m / resolution_m_ * kScale));
  cv::circle(image_, Fixed(ToPixel(center_m)), radius, color, thickness_px, cv::LINE_AA, kShift);
}

void MapCanvas::DrawText(const Eigen::Vector2d& anchor_m, const std::string& text,
                         const cv::Scalar& color, double scale) {
  const cv::Point2d pixel = ToPixel(anchor_m);
  cv::putText(image_, text,
              {static_cast<int>(std::lround(pixel.x)), static_cast<int>(std::lround(pixel.y))},
              cv::FONT_HERSHEY_SIMPLEX, scale, color, 1, cv::LINE_AA);
}

double MapCanvas::ScaleBarLength() const {
  const double target_m = 0.2 * static_cast<double>(image_.cols - legend_panel_px_) * resolution_m_;
  const double decade = std::pow(10.0, std::floor(std::log10(target_m)));
  for (const double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= target_m) return step * decade;
  }
  return decade;
}

void MapCanvas::DrawScaleBar() {
  const double length_m = ScaleBarLength();
  const int length_px = static_cast<int>(std::lround(length_m / resolution_m_));
  const int x0 = 10;
  const int y0 = image_.rows - 12;
  cv::rectangle(image_, {x0, y0 - 4}, {x0 + length_px, y0}, colors::kBlack, cv::FILLED);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", length_m);
  cv::putText(image_, label, {x0 + length_px + 6, y0 + 1}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              colors::kBlack, 1, cv::LINE_AA);
}

void MapCanvas::AddLegendEntry(const std::string& label, const cv::Scalar& color) {
  legend_.emplace_back(label, color);
}

void MapCanvas::DrawLegend() {
  if (legend_.empty()) return;
  constexpr int kLine = 18;
  int width = 0;
  for (const auto& [label, color] : legend_) {
    int baseline = 0;
    width =
        std::max(width, cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline).width);
  }
  const int rows = static_cast<int>(legend_.size());
  const int left = legend_panel_px_ > 0 ? image_.cols - legend_panel_px_ : 6;
  const cv::Rect box(left, 6, width + 44, rows * kLine + 8);
  cv::rectangle(image_, box, colors::kWhite, cv::FILLED);
  cv::rectangle(image_, box, colors::kGray, 1);
  for (int row = 0; row < rows; ++row) {
    const auto& [label, color] = legend_[static_cast<std::size_t>(row)];
    const int y = box.y + 4 + row * kLine + kLine / 2;
    cv::line(image_, {box.x + 6, y}, {box.x + 30, y}, color, 3, cv::LINE_AA);
    cv::putText(image_, label, {box.x + 36, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, colors::kBlack,
                1, cv::LINE_AA);
  }
}

}  // namespace pena::viz
