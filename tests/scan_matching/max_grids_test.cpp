// The branch-and-bound max-grids against their definition: L_h(q) = max over i, j < h of
// hits(q + (i, j) * step), cells outside the hit grid being 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "pena/scan_matching/hit_grid.hpp"
#include "pena/scan_matching/internal/max_grids.hpp"

namespace pena::scan_matching {
namespace {

std::uint8_t MaxByDefinition(const HitGrid& hits, int h, int step, int x, int y) {
  std::uint8_t best = 0;
  for (int i = 0; i < h; ++i) {
    for (int j = 0; j < h; ++j) best = std::max(best, hits.At(x + i * step, y + j * step));
  }
  return best;
}

TEST(MaxGrids, EveryLevelIsTheMaximumOverItsBlockOfCandidates) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate_m(-0.6, 0.6);
  Points2 reference;
  for (int i = 0; i < 60; ++i) reference.emplace_back(coordinate_m(random), coordinate_m(random));
  const HitGrid hits(reference, 0.02, 0.06, /*graded=*/true);
  for (const int step : {1, 3}) {
    const int top_h = 8;
    const internal::MaxGrids grids(hits, step, top_h);
    ASSERT_EQ(grids.levels(), 4);
    const int pad = (top_h - 1) * step;
    for (int k = 0; k < grids.levels(); ++k) {
      const int h = 1 << k;
      for (int y = -pad - 2; y < hits.height() + 2; ++y) {
        for (int x = -pad - 2; x < hits.width() + 2; ++x) {
          ASSERT_EQ(grids.At(k, x, y), MaxByDefinition(hits, h, step, x, y))
              << "level " << k << " step " << step << " cell " << x << "," << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace pena::scan_matching
