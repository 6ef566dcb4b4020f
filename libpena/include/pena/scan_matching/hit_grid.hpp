#pragma once
// The precomputed lookup of the correlation criterion (paper eq. 2): a cell is a hit when a
// reference point lies within the threshold of the cell's centre, so scoring a transformed scan
// point is one array read instead of a nearest-neighbour search.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pena/scan_matching/point_set.hpp"

namespace pena::scan_matching {

// A dense grid over the reference points' bounding box (plus the threshold). Each cell holds a
// weight: kFullWeight for a hit in the paper's binary criterion, or, graded, how close the
// nearest reference point is: kFullWeight * (1 - (d / threshold)^2); 0 beyond the threshold.
class HitGrid {
 public:
  static constexpr std::uint8_t kFullWeight = 255;

  // Throws std::invalid_argument if resolution_m or threshold_m is not > 0.
  HitGrid(const Points2& reference_m, double resolution_m, double threshold_m, bool graded = false);

  // Cell containing a point (may be outside the grid).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& point_m) const {
    return {static_cast<int>(std::floor((point_m.x() - origin_m_.x()) / resolution_m_)),
            static_cast<int>(std::floor((point_m.y() - origin_m_.y()) / resolution_m_))};
  }
  // The cell's weight: > 0 for a hit (eq. 2), 0 otherwise and outside the grid.
  std::uint8_t At(int cell_x, int cell_y) const {
    if (cell_x < 0 || cell_y < 0 || cell_x >= width_ || cell_y >= height_) return 0;
    return cells_[static_cast<std::size_t>(cell_y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(cell_x)];
  }
  // Row cell_y's weights, width() of them (0 <= cell_y < height()).
  const std::uint8_t* Row(int cell_y) const {
    return cells_.data() + static_cast<std::size_t>(cell_y) * static_cast<std::size_t>(width_);
  }
  int width() const { return width_; }
  int height() const { return height_; }
  double resolution_m() const { return resolution_m_; }

 private:
  Eigen::Vector2d origin_m_;
  double resolution_m_;
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> cells_;
};

}  // namespace pena::scan_matching
