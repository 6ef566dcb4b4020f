#include "max_grids.hpp"

#include <algorithm>

namespace pena::scan_matching::internal {

MaxGrids::MaxGrids(const HitGrid& hits, int step_cells, int top_h)
    : pad_((top_h - 1) * step_cells), width_(hits.width() + pad_), height_(hits.height() + pad_) {
  std::vector<std::uint8_t> level(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) level[Index(x, y)] = hits.At(x - pad_, y - pad_);
  }
  levels_.push_back(level);
  for (int h = 1; h < top_h; h *= 2) {
    const int shift = h * step_cells;  // L_2h(q) = max of L_h at q and three shifted copies
    std::vector<std::uint8_t> next(level.size());
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) {
        next[Index(x, y)] = std::max({Get(level, x, y), Get(level, x + shift, y),
                                      Get(level, x, y + shift), Get(level, x + shift, y + shift)});
      }
    }
    levels_.push_back(next);
    level = std::move(next);
  }
}

}  // namespace pena::scan_matching::internal
