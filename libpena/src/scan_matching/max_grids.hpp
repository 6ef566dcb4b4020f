#pragma once
// Max-grids for branch and bound: L_h(q) = max over i, j < h of hits(q + (i, j) * step), for
// h = 1, 2, 4, ..., top. Built once per reference and step, reused by every search.

#include <cstdint>
#include <vector>

#include "pena/scan_matching/hit_grid.hpp"

namespace pena::scan_matching::internal {

class MaxGrids {
 public:
  MaxGrids(const HitGrid& hits, int step_cells, int top_h);

  // Level index k holds h = 2^k; cell coordinates are those of the hit grid.
  std::uint8_t At(int k, int cell_x, int cell_y) const {
    return Get(levels_[static_cast<std::size_t>(k)], cell_x + pad_, cell_y + pad_);
  }
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  std::uint8_t Get(const std::vector<std::uint8_t>& level, int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return 0;
    return level[Index(x, y)];
  }

  int pad_;  // low-side pad: queries below the hit grid that can still reach it are valid
  int width_;
  int height_;
  std::vector<std::vector<std::uint8_t>> levels_;
};

}  // namespace pena::scan_matching::internal
