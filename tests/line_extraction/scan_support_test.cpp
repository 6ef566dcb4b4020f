// Line extraction with the grid's hit records: floor reflections of one scan dropped, laser hits
// counted as observations; and fitted ends extended over the cells that continue a wall.
#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "pena/line_map/internal/extract_steps.hpp"
#include "pena/line_map/line_extractor.hpp"
#include "synthetic_grid.hpp"

namespace pena::line_map {
namespace {

using testing::BlankGrid;
using testing::DrawSegment;

// A free grid with two walls; the hit layers say who hit them: the wall along y = 1 m was hit by
// scans `first`..`last`, the one along y = 3 m by scans 10..20, each cell `hits` times.
grid::GridImage TwoWalls(std::int32_t first, std::int32_t last, std::uint16_t hits) {
  grid::GridImage grid = BlankGrid({0.0, 0.0}, {5.0, 4.0}, 0.05, 0);
  const geometry::Segment2 low{{0.5, 1.0}, {4.5, 1.0}}, high{{0.5, 3.0}, {4.5, 3.0}};
  DrawSegment(grid, low, 255, 1);
  grid::GridImage low_only = BlankGrid({0.0, 0.0}, {5.0, 4.0}, 0.05, 0);
  DrawSegment(low_only, low, 255, 1);
  DrawSegment(grid, high, 255, 1);
  grid.hit_counts = cv::Mat::zeros(grid.occupancy.size(), CV_16UC1);
  grid.first_hit_scans = cv::Mat::zeros(grid.occupancy.size(), CV_32SC1);
  grid.last_hit_scans = cv::Mat::zeros(grid.occupancy.size(), CV_32SC1);
  grid.hit_counts.setTo(hits, grid.occupancy);
  grid.first_hit_scans.setTo(10, grid.occupancy);
  grid.last_hit_scans.setTo(20, grid.occupancy);
  grid.first_hit_scans.setTo(first, low_only.occupancy);
  grid.last_hit_scans.setTo(last, low_only.occupancy);
  return grid;
}

TEST(ScanSupport, DropsALineOfHitsFromOneScanOnly) {
  // One tilted scan's floor hits: every cell first and last hit by scan 7.
  const std::vector<LineSegment> lines = ExtractLines(TwoWalls(7, 7, 1));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NEAR(lines[0].segment.start_m.y(), 3.0, 0.05);  // the wall hit by scans 10-20
}

TEST(ScanSupport, KeepsALineSeenByTwoScansOrWhenTheFilterIsOff) {
  EXPECT_EQ(ExtractLines(TwoWalls(7, 8, 1)).size(), 2u);
  LineExtractionOptions options;
  options.min_scans = 0;
  EXPECT_EQ(ExtractLines(TwoWalls(7, 7, 1), options).size(), 2u);
  grid::GridImage no_record = TwoWalls(7, 7, 1);
  no_record.first_hit_scans.release();
  no_record.last_hit_scans.release();
  EXPECT_EQ(ExtractLines(no_record).size(), 2u);  // a map read from a file: nothing to judge
}

TEST(ScanSupport, ObservationsAreTheLaserHitsOnTheSupportingCells) {
  const std::vector<LineSegment> lines = ExtractLines(TwoWalls(7, 8, 3));
  ASSERT_EQ(lines.size(), 2u);
  for (const LineSegment& line : lines) {
    EXPECT_GT(line.support_cells, 70.0);
    EXPECT_DOUBLE_EQ(line.observations, 3.0 * line.support_cells);
  }
}

TEST(ScanSupport, RejectsHitLayersOfTheWrongTypeOrSize) {
  grid::GridImage grid = TwoWalls(7, 8, 1);
  grid.hit_counts = cv::Mat::zeros(3, 3, CV_16UC1);
  EXPECT_THROW(ExtractLines(grid), std::invalid_argument);
  grid = TwoWalls(7, 8, 1);
  grid.last_hit_scans.convertTo(grid.last_hit_scans, CV_32FC1);
  EXPECT_THROW(ExtractLines(grid), std::invalid_argument);
}

TEST(ExtendEnds, ReachesOverDotsThatContinueTheWallButNotIntoTheNextPiece) {
  // A skeleton piece along y = 1 m from x = 1 to 2 m; occupied cells continue it as dots every
  // 2 cells to x = 2.6 m, then after a 0.5 m gap a collinear piece of its own starts at 3.1 m.
  grid::GridImage grid = BlankGrid({0.0, 0.0}, {5.0, 2.0}, 0.05, 0);
  const internal::GridFrame frame{grid.origin_m, grid.resolution_m, grid.occupancy.rows};
  DrawSegment(grid, {{1.0, 1.0}, {2.0, 1.0}}, 255, 1);
  for (double x_m = 2.1; x_m < 2.65; x_m += 0.1)
    DrawSegment(grid, {{x_m, 1.0}, {x_m, 1.0}}, 255, 1);
  DrawSegment(grid, {{3.1, 1.0}, {4.5, 1.0}}, 255, 1);
  cv::Mat occupied, skeleton;
  cv::threshold(grid.occupancy, occupied, 128, 255, cv::THRESH_BINARY);
  std::vector<internal::Piece> pieces(2);
  for (int col = 0; col < grid.occupancy.cols; ++col) {
    const cv::Point pixel(col, grid.occupancy.rows - 1 - 20);  // the row of y = 1.0-1.05 m
    const double x_m = frame.ToWorld(pixel).x();
    if (x_m > 1.0 && x_m < 2.0) pieces[0].pixels.push_back(pixel);
    if (x_m > 3.1 && x_m < 4.5) pieces[1].pixels.push_back(pixel);
  }
  skeleton = cv::Mat::zeros(grid.occupancy.size(), CV_8UC1);
  for (internal::Piece& piece : pieces) {
    std::vector<Eigen::Vector2d> points;
    for (const cv::Point& pixel : piece.pixels) {
      points.push_back(frame.ToWorld(pixel));
      skeleton.at<std::uint8_t>(pixel) = 1;
    }
    piece.fit = internal::FitLine(points);
  }
  const cv::Mat owners = internal::PieceOwners(pieces, skeleton, frame, 0.1);
  internal::ExtendEnds(pieces, occupied, owners, frame, 0.15, 0.0873);
  const double right_end_m =
      std::max(pieces[0].fit.segment.start_m.x(), pieces[0].fit.segment.end_m.x());
  EXPECT_NEAR(right_end_m, 2.625, 0.03);  // the last dot's centre, not the next piece
  const double left_end_m =
      std::min(pieces[0].fit.segment.start_m.x(), pieces[0].fit.segment.end_m.x());
  EXPECT_NEAR(left_end_m, 1.025, 0.03);  // nothing continues it to the left
  const double next_start_m =
      std::min(pieces[1].fit.segment.start_m.x(), pieces[1].fit.segment.end_m.x());
  EXPECT_GT(next_start_m, 3.05);  // the second piece does not reach back over the gap
}

}  // namespace
}  // namespace pena::line_map
