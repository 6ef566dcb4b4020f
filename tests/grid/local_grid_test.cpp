#include "pena/grid/local_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "grid_test_util.hpp"

namespace pena::grid {
namespace {

// Log-odds are stored as float.
constexpr double kFloatTolerance = 1e-6;

using testing::CellCentre;
using testing::MakeScan;

LocalGridOptions TenMetreWindow() {
  LocalGridOptions options;
  options.size_m = 10.0;
  options.edge_margin_m = 2.0;
  return options;
}

TEST(LocalGrid, AsksForRecentreOnlyNearOrBeyondTheEdge) {
  const LocalGrid grid(TenMetreWindow(), {0.0, 0.0});
  EXPECT_EQ(grid.size_cells(), 200);
  EXPECT_FALSE(grid.NeedsRecentre({0.0, 0.0, 0.0}));
  EXPECT_FALSE(grid.NeedsRecentre({2.8, -2.8, 1.0}));  // edges at +-5 m, margin 2 m
  EXPECT_TRUE(grid.NeedsRecentre({3.2, 0.0, 0.0}));
  EXPECT_TRUE(grid.NeedsRecentre({0.0, -3.2, 0.0}));
  EXPECT_TRUE(grid.NeedsRecentre({40.0, 0.0, 0.0}));
  EXPECT_TRUE(grid.NeedsRecentre({std::nan(""), 0.0, 0.0}));
}

TEST(LocalGrid, RecentreReturnsTheOldWindowAndKeepsTheOverlap) {
  const LocalGridOptions options = TenMetreWindow();
  LocalGrid grid(options, {0.0, 0.0});
  // A wall 1 m ahead (+x, cell 20) and one 2 m behind (-x, cell -40).
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f, 2.0f}, 0.0, std::numbers::pi), CellCentre(0, 0)));
  const GridImage expected = grid.ToImage();
  const Eigen::Vector2i old_min = grid.min_cell();
  ASSERT_NEAR(grid.LogOdds({-40, 0}), options.grid.hit_log_odds, kFloatTolerance);

  const GridImage before = grid.Recentre({4.0, 0.0, 0.0});
  EXPECT_EQ(cv::countNonZero(before.occupancy != expected.occupancy), 0);
  EXPECT_EQ(before.origin_m, expected.origin_m);
  // Now x in [-1, 9) m: the wall ahead and the free cells behind down to -1 m stay.
  EXPECT_EQ(grid.min_cell(), old_min + Eigen::Vector2i(80, 0));
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.grid.hit_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds({-10, 0}), options.grid.miss_log_odds, kFloatTolerance);
  EXPECT_EQ(grid.LogOdds({-40, 0}), 0.0);
  // Cells that left the window are dropped, not kept aside: back at the start they are unknown.
  grid.Recentre({0.0, 0.0, 0.0});
  EXPECT_EQ(grid.LogOdds({-40, 0}), 0.0);
  EXPECT_EQ(grid.LogOdds({-30, 0}), 0.0);
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.grid.hit_log_odds, kFloatTolerance);
}

TEST(LocalGrid, CutsBeamsAtTheWindowEdge) {
  const LocalGridOptions options = TenMetreWindow();
  LocalGrid grid(options, {0.0, 0.0});
  ASSERT_TRUE(grid.Insert(MakeScan({8.0f}), CellCentre(0, 0)));
  const int last = grid.min_cell().x() + grid.size_cells() - 1;
  EXPECT_NEAR(grid.LogOdds({last, 0}), options.grid.miss_log_odds, kFloatTolerance);
  EXPECT_EQ(grid.LogOdds({160, 0}), 0.0);  // the hit, outside
  const GridImage image = grid.ToImage();
  EXPECT_EQ(cv::countNonZero(image.occupancy > 128), 0);
}

TEST(LocalGrid, RejectsAMarginOfHalfTheWindow) {
  LocalGridOptions options = TenMetreWindow();
  options.edge_margin_m = 5.0;
  try {
    LocalGrid grid(options, {0.0, 0.0});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("local_grid.edge_margin_m"), std::string::npos);
  }
  EXPECT_THROW(LocalGrid(TenMetreWindow(), {std::nan(""), 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::grid
