#include "pena/grid/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "grid_test_util.hpp"

namespace pena::grid {
namespace {

// Log-odds are stored as float.
constexpr double kFloatTolerance = 1e-6;

using testing::CellCentre;
using testing::MakeScan;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Every cell of the grid and its log-odds, for checks over the whole grid.
template <typename Check>
void ForEachCell(const OccupancyGrid& grid, Check check) {
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const Eigen::Vector2i cell = grid.min_cell() + Eigen::Vector2i(i, j);
      check(cell, grid.LogOdds(cell));
    }
  }
}

TEST(OccupancyGrid, BeamFreesCellsUpToTheHitAndMarksTheHitOccupied) {
  const GridOptions options;
  OccupancyGrid grid(options);
  // From the centre of cell (0, 0) along +x, 1 m: the hit lies at x = 1.025 m, in cell 20.
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(0, 0)));
  for (int i = 0; i < 20; ++i) {
    EXPECT_NEAR(grid.LogOdds({i, 0}), options.miss_log_odds, kFloatTolerance) << "cell " << i;
  }
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.hit_log_odds, kFloatTolerance);
  EXPECT_EQ(grid.LogOdds({21, 0}), 0.0);
  EXPECT_EQ(grid.LogOdds({10, 1}), 0.0);
  EXPECT_EQ(grid.LogOdds({-1, 0}), 0.0);
  EXPECT_NEAR(grid.Probability({20, 0}), 0.70, 0.001);
  EXPECT_NEAR(grid.Probability({5, 0}), 0.40, 0.002);  // -0.4 is logit(0.401)
  EXPECT_DOUBLE_EQ(grid.Probability({21, 0}), 0.5);
}

TEST(OccupancyGrid, DiagonalBeamVisitsTheDiagonalCells) {
  OccupancyGrid grid;
  // 45 deg from the centre of (0, 0) to the centre of (10, 10).
  const float range = static_cast<float>(0.5 * std::numbers::sqrt2);
  ASSERT_TRUE(grid.Insert(MakeScan({range}), CellCentre(0, 0, std::numbers::pi / 4)));
  for (int k = 0; k < 10; ++k) EXPECT_LT(grid.LogOdds({k, k}), 0.0) << "cell " << k;
  EXPECT_GT(grid.LogOdds({10, 10}), 0.0);
  int touched = 0;
  ForEachCell(grid, [&](const Eigen::Vector2i&, double value) { touched += value != 0.0; });
  EXPECT_EQ(touched, 11);
}

TEST(OccupancyGrid, RaysStayWithinHalfACellOfTheBeamAtAnyAngle) {
  for (int degrees = 0; degrees < 360; degrees += 7) {
    OccupancyGrid grid;
    const double angle_rad = degrees * std::numbers::pi / 180.0;
    ASSERT_TRUE(grid.Insert(MakeScan({2.0f}), CellCentre(0, 0, angle_rad)));
    const Eigen::Vector2d start(0.025, 0.025);
    const Eigen::Vector2i end =
        grid.CellOf(start + 2.0 * Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad)));
    // Bresenham joins the centres of the laser's cell and the hit's cell, never straying more
    // than half a cell off that line.
    const Eigen::Vector2d line = end.cast<double>().normalized();
    int free_cells = 0;
    ForEachCell(grid, [&](const Eigen::Vector2i& cell, double value) {
      if (value >= 0.0) return;
      ++free_cells;
      const Eigen::Vector2d offset = cell.cast<double>();
      EXPECT_LE(std::abs(offset.x() * line.y() - offset.y() * line.x()), 0.5 + 1e-9)
          << degrees << " deg, cell " << cell.transpose();
    });
    // Bresenham visits one cell per step along the major axis, the hit cell excluded.
    EXPECT_EQ(free_cells, std::max(std::abs(end.x()), std::abs(end.y()))) << degrees << " deg";
    EXPECT_GT(grid.LogOdds(end), 0.0) << degrees << " deg";
  }
}

TEST(OccupancyGrid, ClampsLogOddsAfterRepeatedEvidence) {
  const GridOptions options;
  OccupancyGrid grid(options);
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(0, 0)));
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.max_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds({3, 0}), options.min_log_odds, kFloatTolerance);
  // A clamped cell still turns: the wall moved 0.5 m further, so cell 20 now lies on free space.
  const int scans_to_flip =
      static_cast<int>(std::ceil(options.max_log_odds / -options.miss_log_odds)) + 1;
  for (int k = 0; k < scans_to_flip; ++k)
    ASSERT_TRUE(grid.Insert(MakeScan({1.5f}), CellCentre(0, 0)));
  EXPECT_LT(grid.LogOdds({20, 0}), 0.0);
}

TEST(OccupancyGrid, UpdatesEachCellOncePerScanWithHitsWinning) {
  GridOptions options;
  // All beams share one bearing, so each "surface" runs along the beams (a fully grazing hit):
  // switch the grazing skip off to see the plain once-per-scan rule.
  options.surface_band_m = 0.0;
  OccupancyGrid grid(options);
  // Three beams on one cell, and a fourth along the same bearing passing through it to 2 m.
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f, 1.0f, 1.0f, 2.0f}), CellCentre(0, 0)));
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.hit_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds({10, 0}), options.miss_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds({30, 0}), options.miss_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds({40, 0}), options.hit_log_odds, kFloatTolerance);
}

TEST(OccupancyGrid, NoReturnClearsOnlyUpToTheLimit) {
  GridOptions options;
  options.no_return_clear_m = 1.0;
  OccupancyGrid grid(options);
  // +inf and a range at the sensor's maximum are both no-returns; a third beam (along -x) returns
  // at 5 m, so the scan demonstrably saw beyond the 1 m limit.
  ASSERT_TRUE(
      grid.Insert(MakeScan({kInf, 30.0f, 5.0f}, 0.0, std::numbers::pi / 2), CellCentre(0, 0)));
  for (int i = 0; i <= 20; ++i)
    EXPECT_NEAR(grid.LogOdds({i, 0}), options.miss_log_odds, kFloatTolerance) << i;
  EXPECT_EQ(grid.LogOdds({21, 0}), 0.0);
  EXPECT_NEAR(grid.LogOdds({0, 20}), options.miss_log_odds, kFloatTolerance);
  EXPECT_EQ(grid.LogOdds({0, 21}), 0.0);
  const Eigen::Vector2i hit = grid.CellOf({0.025 - 5.0, 0.025});
  ForEachCell(grid, [&hit](const Eigen::Vector2i& cell, double value) {
    if (cell != hit) {
      EXPECT_LE(value, 0.0) << cell.transpose();
    }
  });
}

TEST(OccupancyGrid, NoReturnsClearOnlyAsFarAsTheScanSaw) {
  // In smoke the laser sees 2.5 m and reports no-returns beyond: those must not clear the wall
  // 3.5 m away that the entity saw before from outside the smoke.
  const GridOptions options;  // no_return_clear_m = 5 m
  OccupancyGrid grid(options);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(grid.Insert(MakeScan({3.5f}), CellCentre(0, 0)));
  const Eigen::Vector2i wall = grid.CellOf({0.025 + 3.5, 0.025});
  ASSERT_GT(grid.Probability(wall), 0.8);
  // Smoke: the farthest return of each scan is 2 m (beam at 90 deg), the beam along +x is empty.
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(grid.Insert(MakeScan({kInf, 2.0f}, 0.0, std::numbers::pi / 2), CellCentre(0, 0)));
  }
  EXPECT_GT(grid.Probability(wall), 0.8);
  EXPECT_LT(grid.Probability({39, 0}), 0.2);  // within the 2 m reach: cleared further
  EXPECT_NEAR(grid.LogOdds({50, 0}), 3 * options.miss_log_odds, kFloatTolerance);  // untouched
}

TEST(OccupancyGrid, WallSeenAtAGrazingAngleIsNotClearedByItsOwnBeams) {
  // A wall along y = 0.025 (the middle of cell row 0) seen from 1 m beside it while walking
  // along it: beams hit it at 4-15 deg and each runs inside row 0 for 0.1-0.36 m before its hit.
  const auto occupied_fraction = [](double surface_band_m) {
    GridOptions options;
    options.surface_band_m = surface_band_m;
    OccupancyGrid grid(options);
    constexpr double kDeg = std::numbers::pi / 180.0;
    for (int step = 0; step < 40; ++step) {
      std::vector<float> ranges;
      for (double angle_deg = 4.0; angle_deg <= 15.0; angle_deg += 0.5) {
        ranges.push_back(static_cast<float>(1.0 / std::sin(angle_deg * kDeg)));
      }
      const geometry::Pose2 pose{0.1 * step, 1.025, -4.0 * kDeg};
      EXPECT_TRUE(grid.Insert(MakeScan(ranges, 0.0, -0.5 * kDeg), pose));
    }
    int occupied = 0, cells = 0;
    for (int i = 120; i < 160; ++i, ++cells) occupied += grid.Probability({i, 0}) > 0.65 ? 1 : 0;
    return static_cast<double>(occupied) / cells;
  };
  EXPECT_GT(occupied_fraction(0.05), 0.9);
  EXPECT_LT(occupied_fraction(0.0), 0.5);  // without the skip the misses erase the wall
}

TEST(OccupancyGrid, ZeroClearingLimitLeavesNoReturnsUnused) {
  GridOptions options;
  options.no_return_clear_m = 0.0;
  OccupancyGrid grid(options);
  ASSERT_TRUE(grid.Insert(MakeScan({kInf}), CellCentre(0, 0)));
  ForEachCell(grid, [](const Eigen::Vector2i&, double value) { EXPECT_EQ(value, 0.0); });
}

TEST(OccupancyGrid, ReturnsBeyondMaxRangeAreUsedAsNoReturns) {
  GridOptions options;
  options.max_range_m = 2.0;
  options.no_return_clear_m = 1.0;
  OccupancyGrid grid(options);
  ASSERT_TRUE(grid.Insert(MakeScan({3.0f}), CellCentre(0, 0)));
  EXPECT_LT(grid.LogOdds({20, 0}), 0.0);
  EXPECT_EQ(grid.LogOdds({21, 0}), 0.0);
  EXPECT_EQ(grid.LogOdds({60, 0}), 0.0);
}

TEST(OccupancyGrid, IgnoresNanNegativeAndZeroRanges) {
  OccupancyGrid grid;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ASSERT_TRUE(grid.Insert(MakeScan({nan, -1.0f, 0.0f, -kInf}, 0.0, 0.5), CellCentre(0, 0)));
  ForEachCell(grid, [](const Eigen::Vector2i&, double value) { EXPECT_EQ(value, 0.0); });
  EXPECT_EQ(grid.scans_inserted(), 1u);
}

TEST(OccupancyGrid, GrowsToNewGroundAndKeepsWhatItHad) {
  const GridOptions options;
  OccupancyGrid grid(options);
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(0, 0)));
  const int first_width = grid.width();
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}, std::numbers::pi), {-40.0, 25.0, 0.0}));
  EXPECT_GT(grid.width(), first_width);
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.hit_log_odds, kFloatTolerance);
  EXPECT_NEAR(grid.LogOdds(grid.CellOf({-41.0, 25.0})), options.hit_log_odds, kFloatTolerance);
  EXPECT_LE(grid.min_cell().x(), grid.CellOf({-41.0, 0.0}).x());
  EXPECT_GE(grid.min_cell().y() + grid.height(), grid.CellOf({0.0, 25.0}).y() + 1);
}

TEST(OccupancyGrid, RefusesNonFinitePosesAndGrowthBeyondMaxSize) {
  GridOptions options;
  options.max_size_m = 20.0;
  OccupancyGrid grid(options);
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(0, 0)));
  EXPECT_FALSE(grid.Insert(MakeScan({1.0f}), {std::nan(""), 0.0, 0.0}));
  EXPECT_FALSE(grid.Insert(MakeScan({1.0f}), {0.0, 0.0, kInf}));
  EXPECT_FALSE(grid.Insert(MakeScan({1.0f}), {100.0, 0.0, 0.0}));
  EXPECT_FALSE(grid.Insert(MakeScan({1.0f}), {1e300, 0.0, 0.0}));
  EXPECT_EQ(grid.scans_inserted(), 1u);
  EXPECT_NEAR(grid.LogOdds({20, 0}), options.hit_log_odds, kFloatTolerance);
}

TEST(OccupancyGrid, ImageRowZeroIsTheTopAndOriginIsTheBottomLeftCorner) {
  OccupancyGrid grid;
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}, std::numbers::pi / 2), CellCentre(3, -7)));
  const GridImage image = grid.ToImage();
  ASSERT_EQ(image.occupancy.rows, grid.height());
  ASSERT_EQ(image.occupancy.cols, grid.width());
  EXPECT_DOUBLE_EQ(image.origin_m.x(), grid.min_cell().x() * 0.05);
  EXPECT_DOUBLE_EQ(image.origin_m.y(), grid.min_cell().y() * 0.05);
  // The hit is cell (3, 13); free cells below it in y, so below it in the image.
  const int col = 3 - grid.min_cell().x();
  const int hit_row = grid.height() - 1 - (13 - grid.min_cell().y());
  EXPECT_GT(image.occupancy.at<std::uint8_t>(hit_row, col), 128);
  EXPECT_LT(image.occupancy.at<std::uint8_t>(hit_row + 1, col), 128);
  EXPECT_EQ(image.occupancy.at<std::uint8_t>(hit_row - 1, col), 128);
  EXPECT_EQ(image.occupancy.at<std::uint8_t>(hit_row, col + 1), 128);
}

TEST(OccupancyGrid, RejectsInvalidOptionsNamingTheField) {
  GridOptions options;
  options.resolution_m = -1.0;
  try {
    OccupancyGrid grid(options);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("grid.resolution_m must be"), std::string::npos);
  }
  options = {};
  options.miss_log_odds = 0.4;
  EXPECT_THROW(OccupancyGrid{options}, std::invalid_argument);
  options = {};
  options.no_return_clear_m = std::nan("");
  EXPECT_THROW(OccupancyGrid{options}, std::invalid_argument);
  options = {};
  options.surface_band_m = -0.01;
  EXPECT_THROW(OccupancyGrid{options}, std::invalid_argument);
  options = {};
  options.max_surface_skip_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW(OccupancyGrid{options}, std::invalid_argument);
}

TEST(OccupancyGrid, ImageRecordsHitCountsAndFirstAndLastHittingScans) {
  OccupancyGrid grid;
  ASSERT_TRUE(grid.Insert(MakeScan({2.0f}), CellCentre(0, 0)));  // scan 1: a miss at cell 20
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(0, 0)));
  const GridImage image = grid.ToImage();
  const auto pixel = [&](int i, int j) {
    return cv::Point(i - grid.min_cell().x(), grid.height() - 1 - (j - grid.min_cell().y()));
  };
  EXPECT_EQ(image.hit_counts.at<std::uint16_t>(pixel(20, 0)), 3);
  EXPECT_EQ(image.first_hit_scans.at<std::int32_t>(pixel(20, 0)), 2);
  EXPECT_EQ(image.last_hit_scans.at<std::int32_t>(pixel(20, 0)), 4);
  EXPECT_EQ(image.hit_counts.at<std::uint16_t>(pixel(40, 0)), 1);   // scan 1's hit
  EXPECT_EQ(image.first_hit_scans.at<std::int32_t>(pixel(40, 0)), 1);
  EXPECT_EQ(image.hit_counts.at<std::uint16_t>(pixel(10, 0)), 0);   // only crossed
  EXPECT_EQ(image.last_hit_scans.at<std::int32_t>(pixel(10, 0)), 0);
  // Growing the grid keeps the records.
  ASSERT_TRUE(grid.Insert(MakeScan({1.0f}), CellCentre(-200, -200)));
  const GridImage grown = grid.ToImage();
  EXPECT_EQ(grown.hit_counts.at<std::uint16_t>(pixel(20, 0)), 3);
  EXPECT_EQ(grown.last_hit_scans.at<std::int32_t>(pixel(20, 0)), 4);
}

}  // namespace
}  // namespace pena::grid
