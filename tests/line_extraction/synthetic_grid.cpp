#include "synthetic_grid.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace pena::line_map::testing {

namespace {

constexpr int kShift = 4;  // cv::line sub-pixel bits

// Pixel coordinates (col, row of cell centres) in cv::line's fixed point.
cv::Point ToFixedPixel(const grid::GridImage& grid, const Eigen::Vector2d& point_m) {
  const double col = (point_m.x() - grid.origin_m.x()) / grid.resolution_m - 0.5;
  const double row =
      grid.occupancy.rows - 0.5 - (point_m.y() - grid.origin_m.y()) / grid.resolution_m;
  return {static_cast<int>(std::lround(col * (1 << kShift))),
          static_cast<int>(std::lround(row * (1 << kShift)))};
}

}  // namespace

grid::GridImage BlankGrid(const Eigen::Vector2d& origin_m, const Eigen::Vector2d& size_m,
                          double resolution_m, std::uint8_t value) {
  grid::GridImage grid;
  grid.origin_m = origin_m;
  grid.resolution_m = resolution_m;
  grid.occupancy =
      cv::Mat(static_cast<int>(std::ceil(size_m.y() / resolution_m)),
              static_cast<int>(std::ceil(size_m.x() / resolution_m)), CV_8UC1, cv::Scalar(value));
  return grid;
}

void DrawSegment(grid::GridImage& grid, const geometry::Segment2& segment, std::uint8_t value,
                 int thickness_cells) {
  cv::line(grid.occupancy, ToFixedPixel(grid, segment.start_m), ToFixedPixel(grid, segment.end_m),
           cv::Scalar(value), thickness_cells, cv::LINE_8, kShift);
}

void FillRect(grid::GridImage& grid, const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
              std::uint8_t value) {
  const cv::Point a = ToFixedPixel(grid, min_m);
  const cv::Point b = ToFixedPixel(grid, max_m);
  cv::rectangle(grid.occupancy, a, b, cv::Scalar(value), cv::FILLED, cv::LINE_8, kShift);
}

std::vector<geometry::Segment2> WallWithDoor(const Eigen::Vector2d& from_m,
                                             const Eigen::Vector2d& to_m, double door_m) {
  if (door_m <= 0.0) return {{from_m, to_m}};
  const Eigen::Vector2d middle_m = 0.5 * (from_m + to_m);
  const Eigen::Vector2d half_door_m = 0.5 * door_m * (to_m - from_m).normalized();
  return {{from_m, middle_m - half_door_m}, {middle_m + half_door_m, to_m}};
}

grid::GridImage Building(int rooms_x, int rooms_y, double room_m, double door_m,
                         double resolution_m, int thickness_cells,
                         std::vector<geometry::Segment2>* walls) {
  const double margin_m = 1.0;
  const Eigen::Vector2d size_m(rooms_x * room_m, rooms_y * room_m);
  grid::GridImage grid = BlankGrid(
      {-margin_m, -margin_m}, size_m + Eigen::Vector2d(2 * margin_m, 2 * margin_m), resolution_m);
  FillRect(grid, {0.0, 0.0}, size_m, 0);
  // Each room draws its bottom and left wall, each with a door; the top and right outer walls
  // are closed. So every wall is drawn once.
  std::vector<geometry::Segment2> drawn = WallWithDoor({0.0, size_m.y()}, size_m, 0.0);
  drawn.push_back({{size_m.x(), 0.0}, size_m});
  for (int i = 0; i < rooms_x; ++i) {
    for (int j = 0; j < rooms_y; ++j) {
      const Eigen::Vector2d corner_m(i * room_m, j * room_m);
      for (const auto& wall :
           WallWithDoor(corner_m, corner_m + Eigen::Vector2d(room_m, 0.0), door_m)) {
        drawn.push_back(wall);
      }
      for (const auto& wall :
           WallWithDoor(corner_m, corner_m + Eigen::Vector2d(0.0, room_m), i == 0 ? 0.0 : door_m)) {
        drawn.push_back(wall);
      }
    }
  }
  for (const geometry::Segment2& wall : drawn) DrawSegment(grid, wall, 255, thickness_cells);
  if (walls != nullptr) walls->insert(walls->end(), drawn.begin(), drawn.end());
  return grid;
}

}  // namespace pena::line_map::testing
