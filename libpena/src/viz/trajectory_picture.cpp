#include "pena/viz/trajectory_picture.hpp"

#include <algorithm>
#include <cmath>

namespace pena::viz {
namespace {

const cv::Scalar kScanColor{190, 170, 150};  // light grey-blue, one pixel per point: the map
const cv::Scalar kTruthColor = colors::kGreen;
const cv::Scalar kEstimateColor = colors::kBlue;
const cv::Scalar kKeyframeColor = colors::kOrange;
const cv::Scalar kFailedColor = colors::kRed;

std::vector<Eigen::Vector2d> Positions(const geometry::Trajectory& trajectory) {
  std::vector<Eigen::Vector2d> positions;
  positions.reserve(trajectory.size());
  for (const geometry::StampedPose2& stamped : trajectory)
    positions.emplace_back(stamped.pose.x_m, stamped.pose.y_m);
  return positions;
}

std::size_t PointsAtStride(const std::vector<std::vector<Eigen::Vector2d>>& scans_m,
                           std::size_t stride) {
  std::size_t points = 0;
  for (std::size_t i = 0; i < scans_m.size(); i += stride) points += scans_m[i].size();
  return points;
}

// The central `fraction` of the values: [lower, upper] quantiles (selection, not a full sort:
// a run has millions of points).
std::pair<double, double> CentralRange(std::vector<double> values, double fraction) {
  const double tail = 0.5 * (1.0 - std::clamp(fraction, 0.0, 1.0));
  const auto last = static_cast<double>(values.size() - 1);
  const auto lower = values.begin() + static_cast<std::ptrdiff_t>(std::floor(tail * last));
  const auto upper = values.begin() + static_cast<std::ptrdiff_t>(std::ceil((1.0 - tail) * last));
  std::nth_element(values.begin(), lower, values.end());
  const double low = *lower;
  std::nth_element(lower, upper, values.end());
  return {low, *upper};
}

// The world box: every pose of both paths and the central part of the drawn scan points, with
// half a metre around.
void Bounds(const TrajectoryPicture& picture, std::size_t stride, double scan_fraction,
            Eigen::Vector2d& min_m, Eigen::Vector2d& max_m) {
  min_m = Eigen::Vector2d::Constant(1e300);
  max_m = Eigen::Vector2d::Constant(-1e300);
  const auto grow = [&](const Eigen::Vector2d& point) {
    min_m = min_m.cwiseMin(point);
    max_m = max_m.cwiseMax(point);
  };
  for (const auto& point : Positions(picture.estimate)) grow(point);
  for (const auto& point : Positions(picture.truth)) grow(point);
  std::vector<double> xs, ys;
  for (std::size_t i = 0; i < picture.scans_m.size(); i += stride) {
    for (const Eigen::Vector2d& point : picture.scans_m[i]) {
      xs.push_back(point.x());
      ys.push_back(point.y());
    }
  }
  if (!xs.empty()) {
    const auto [x_low, x_high] = CentralRange(std::move(xs), scan_fraction);
    const auto [y_low, y_high] = CentralRange(std::move(ys), scan_fraction);
    grow({x_low, y_low});
    grow({x_high, y_high});
  }
  if (min_m.x() > max_m.x()) min_m = max_m = Eigen::Vector2d::Zero();
  min_m -= Eigen::Vector2d::Constant(0.5);
  max_m += Eigen::Vector2d::Constant(0.5);
}

void DrawScans(MapCanvas& canvas, const TrajectoryPicture& picture, std::size_t stride) {
  for (std::size_t i = 0; i < picture.scans_m.size(); i += stride) {
    canvas.DrawPixels(picture.scans_m[i], kScanColor);
  }
}

void DrawLegend(MapCanvas& canvas, const TrajectoryPicture& picture, std::size_t stride) {
  if (!picture.scans_m.empty()) {
    canvas.AddLegendEntry(stride == 1 ? "scans at estimated poses"
                                      : "every " + std::to_string(stride) + "th scan, estimated",
                          kScanColor);
  }
  if (!picture.truth.empty()) canvas.AddLegendEntry("true path", kTruthColor);
  canvas.AddLegendEntry("position estimates", kEstimateColor);
  if (!picture.keyframes_m.empty()) canvas.AddLegendEntry("reference changed", kKeyframeColor);
  if (!picture.failed_m.empty()) canvas.AddLegendEntry("failed match", kFailedColor);
  canvas.DrawLegend();
}

}  // namespace

std::size_t ScanDrawStride(const std::vector<std::vector<Eigen::Vector2d>>& scans_m,
                           std::size_t max_points) {
  const std::size_t total = PointsAtStride(scans_m, 1);
  if (total <= max_points) return 1;
  // Drawing every k-th scan keeps about total / k points: start there and step up until it fits.
  std::size_t stride = std::max<std::size_t>(1, total / std::max<std::size_t>(1, max_points));
  while (stride < scans_m.size() && PointsAtStride(scans_m, stride) > max_points) ++stride;
  return std::max<std::size_t>(1, std::min(stride, scans_m.size()));
}

cv::Mat RenderTrajectory(const TrajectoryPicture& picture,
                         const TrajectoryPictureOptions& options) {
  const std::size_t stride = ScanDrawStride(picture.scans_m, options.max_scan_points);
  Eigen::Vector2d min_m, max_m;
  Bounds(picture, stride, options.scan_bounds_fraction, min_m, max_m);
  MapCanvas canvas(min_m, max_m, options.canvas);
  if (options.max_scan_points > 0) DrawScans(canvas, picture, stride);
  if (!picture.truth.empty()) canvas.DrawPolyline(Positions(picture.truth), kTruthColor, 1);
  const std::vector<Eigen::Vector2d> path = Positions(picture.estimate);
  canvas.DrawPolyline(path, kEstimateColor, 1);
  // "Dots are the position estimates" (Fig. 3): one per scan, over the line.
  canvas.DrawPoints(path, kEstimateColor, 1);
  // Keyframes are every few scans: rings around the dots, not dots over them.
  for (const Eigen::Vector2d& keyframe : picture.keyframes_m)
    canvas.DrawCircle(keyframe, 2.5 * canvas.resolution_m(), kKeyframeColor, 1);
  canvas.DrawPoints(picture.failed_m, kFailedColor, 3);
  if (!path.empty())
    canvas.DrawCircle(path.front(), 4.0 * canvas.resolution_m(), colors::kBlack, 2);
  if (!picture.title.empty()) {
    const cv::Point2d top_left = canvas.ToPixel({min_m.x(), max_m.y()});
    canvas.DrawText({min_m.x(), max_m.y() + (top_left.y - 16.0) * canvas.resolution_m()},
                    picture.title, colors::kBlack);
  }
  canvas.DrawScaleBar();
  DrawLegend(canvas, picture, stride);
  return canvas.image().clone();
}

}  // namespace pena::viz
