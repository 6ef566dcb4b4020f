#pragma once
// The picture of an odometry run (the paper's Fig. 3): the position estimates as dots along the
// path, every scan (or an even subsample of them) drawn at its estimated pose so the map shows
// how well the scans agree, keyframes, failed matches and, in simulation, the true path.
// Encoding (PNG) is left to the caller.

#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "pena/geometry/trajectory.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::viz {

// What the picture shows; everything in the mission (world) frame, metres.
struct TrajectoryPicture {
  geometry::Trajectory estimate;  // estimated body poses, one per scan, in stamp order
  geometry::Trajectory truth;     // true path (simulation); empty when unknown
  // Returns of each scan placed at its estimated pose, one entry per scan in stamp order.
  std::vector<std::vector<Eigen::Vector2d>> scans_m;
  std::vector<Eigen::Vector2d> keyframes_m;  // positions where the reference scan changed
  std::vector<Eigen::Vector2d> failed_m;     // positions where scan matching failed
  std::string title;                         // one line drawn at the top left; may be empty
};

// Picture layout and budget.
struct TrajectoryPictureOptions {
  MapCanvasOptions canvas = DefaultCanvas();  // 5 cm/px, <= 2000 px, legend panel right
  // Cap on scan points drawn (one pixel each): above it every k-th scan, k the smallest that fits.
  std::size_t max_scan_points = 3000000;
  // The box is fitted to the path plus this central fraction of the scan points in x and y,
  // so a few stray long returns do not shrink the map.
  double scan_bounds_fraction = 0.998;

  static MapCanvasOptions DefaultCanvas() {
    MapCanvasOptions canvas;
    canvas.legend_panel_px = 230;
    return canvas;
  }
};

// The stride k such that drawing scans 0, k, 2k, ... keeps the point count within max_points
// (1 when everything fits; never 0).
std::size_t ScanDrawStride(const std::vector<std::vector<Eigen::Vector2d>>& scans_m,
                           std::size_t max_points);

// Renders the run as a BGR image; deterministic for a given input. An empty picture (no poses,
// no points) gives a small blank canvas around the origin.
cv::Mat RenderTrajectory(const TrajectoryPicture& picture,
                         const TrajectoryPictureOptions& options = {});

}  // namespace pena::viz
