#include "max_grids.hpp"

#include <algorithm>

namespace pena::scan_matching::internal {
namespace {

// out[i] = max(a[i], b[i]) for i < count: contiguous, so the compiler vectorises it.
void MaxOf(const std::uint8_t* __restrict a, const std::uint8_t* __restrict b,
           std::uint8_t* __restrict out, int count) {
  for (int i = 0; i < count; ++i) out[i] = std::max(a[i], b[i]);
}

}  // namespace

// L_2h(q) = max of L_h at q, q + (s, 0), q + (0, s) and q + (s, s) with s = h * step: separable,
// so one pass along the rows (x and x + s) and one along the columns (rows y and y + s), each
// over whole rows. Cells beyond the grid read as 0, as Get() does.
MaxGrids::MaxGrids(const HitGrid& hits, int step_cells, int top_h)
    : pad_((top_h - 1) * step_cells), width_(hits.width() + pad_), height_(hits.height() + pad_) {
  const std::size_t size = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  std::vector<std::uint8_t> level(size, 0);
  for (int y = pad_; y < height_; ++y) {
    std::copy_n(hits.Row(y - pad_), hits.width(), level.data() + Index(pad_, y));
  }
  levels_.push_back(std::move(level));
  std::vector<std::uint8_t> along_x(size);
  for (int h = 1; h < top_h; h *= 2) {
    const int shift = h * step_cells;
    const std::vector<std::uint8_t>& from = levels_.back();
    const int paired_x = std::max(0, width_ - shift);  // cells whose x + shift lies in the grid
    for (int y = 0; y < height_; ++y) {
      const std::uint8_t* row = from.data() + Index(0, y);
      std::uint8_t* out = along_x.data() + Index(0, y);
      if (paired_x > 0) MaxOf(row, row + shift, out, paired_x);
      std::copy(row + paired_x, row + width_, out + paired_x);
    }
    std::vector<std::uint8_t> next(size);
    for (int y = 0; y < height_; ++y) {
      const std::uint8_t* row = along_x.data() + Index(0, y);
      std::uint8_t* out = next.data() + Index(0, y);
      if (y + shift < height_) {
        MaxOf(row, along_x.data() + Index(0, y + shift), out, width_);
      } else {
        std::copy_n(row, width_, out);
      }
    }
    levels_.push_back(std::move(next));
  }
}

}  // namespace pena::scan_matching::internal
