#pragma once
// An occupancy grid as an image: the contract between the grid (which builds it) and the line
// extraction and the map pictures (which read it).

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace pena::grid {

// Row 0 is the grid's top (largest y); column 0 its left (smallest x). Pixel (col, row) covers
// x in [origin.x + col * res, +res) and y in [origin.y + (rows - 1 - row) * res, +res).
struct GridImage {
  cv::Mat occupancy;           // CV_8UC1: 0 = surely free, 255 = surely occupied, 128 = unknown
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // world position of the bottom-left corner
  double resolution_m = 0.05;  // cell size
  // Optional, same size as `occupancy` (empty when the source has no such record, e.g. a map read
  // from a file): laser hits per cell (CV_16UC1, saturating at 65535) and the numbers of the first
  // and the last scan that hit each cell (CV_32SC1, scans counted from 1 by the grid; 0 = never).
  cv::Mat hit_counts;
  cv::Mat first_hit_scans;
  cv::Mat last_hit_scans;
};

}  // namespace pena::grid
