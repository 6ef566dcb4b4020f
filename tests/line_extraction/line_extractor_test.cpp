#include "pena/line_map/line_extractor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "pena/eval/line_map_error.hpp"
#include "synthetic_grid.hpp"

namespace pena::line_map {
namespace {

using testing::BlankGrid;
using testing::Building;
using testing::DrawSegment;
using testing::FillRect;

std::vector<geometry::Segment2> Geometry(const std::vector<LineSegment>& lines) {
  std::vector<geometry::Segment2> segments;
  for (const LineSegment& line : lines) segments.push_back(line.segment);
  return segments;
}

eval::LineMapErrorSummary Score(const std::vector<LineSegment>& lines,
                                const std::vector<geometry::Segment2>& walls) {
  return eval::EvaluateLineMap(Geometry(lines), walls);
}

double AngleRad(const geometry::Segment2& segment) {
  const Eigen::Vector2d d = segment.end_m - segment.start_m;
  return std::atan2(d.y(), d.x());
}

// A free room 6 m x 4 m with closed walls, drawn 2 cells thick, unknown outside.
grid::GridImage PlainRoom(std::vector<geometry::Segment2>* walls) {
  grid::GridImage grid = BlankGrid({-1.0, -1.0}, {8.0, 6.0}, 0.05);
  FillRect(grid, {0.0, 0.0}, {6.0, 4.0}, 0);
  *walls = testing::WallWithDoor({0.0, 0.0}, {6.0, 0.0}, 0.0);
  walls->push_back({{6.0, 0.0}, {6.0, 4.0}});
  walls->push_back({{6.0, 4.0}, {0.0, 4.0}});
  walls->push_back({{0.0, 4.0}, {0.0, 0.0}});
  for (const geometry::Segment2& wall : *walls) DrawSegment(grid, wall, 255, 2);
  return grid;
}

TEST(LineExtraction, ExtractsWallsOfRoomsWithDoorGaps) {
  for (const int thickness_cells : {1, 2, 3}) {
    std::vector<geometry::Segment2> walls;
    const grid::GridImage grid = Building(3, 2, 5.0, 0.9, 0.05, thickness_cells, &walls);
    const std::vector<LineSegment> lines = ExtractLines(grid);
    const eval::LineMapErrorSummary score = Score(lines, walls);
    EXPECT_GT(score.coverage, 0.95) << "thickness " << thickness_cells;
    EXPECT_GT(score.precision, 0.95) << "thickness " << thickness_cells;
    EXPECT_LE(score.fragmentation, 1.2) << "thickness " << thickness_cells;
    // Door gaps stay open: no segment crosses the middle of a door.
    for (const LineSegment& line : lines) {
      EXPECT_GT(geometry::DistanceToSegment(line.segment, {2.5, 0.0}), 0.3);
    }
  }
}

TEST(LineExtraction, EachSegmentCarriesSupportAndFitQuality) {
  std::vector<geometry::Segment2> walls;
  const std::vector<LineSegment> lines = ExtractLines(PlainRoom(&walls));
  ASSERT_EQ(lines.size(), 4u);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].id, static_cast<std::int64_t>(i));
    // A 2-cell-thick wall: about two cells per 5 cm of length.
    const double length_m = geometry::Length(lines[i].segment);
    EXPECT_GT(lines[i].support_cells, 1.5 * length_m / 0.05);
    EXPECT_LT(lines[i].support_cells, 3.5 * length_m / 0.05);
    EXPECT_EQ(lines[i].observations, lines[i].support_cells);
    EXPECT_GT(lines[i].rms_error_m, 0.0);
    EXPECT_LT(lines[i].rms_error_m, 0.05);
  }
}

TEST(LineExtraction, ClosingJoinsSplitObstacle) {
  grid::GridImage grid = BlankGrid({0.0, 0.0}, {6.0, 2.0}, 0.05, 0);
  const geometry::Segment2 wall{{0.5, 1.0}, {5.5, 1.0}};
  DrawSegment(grid, wall, 255, 2);
  grid.occupancy.colRange(60, 63).setTo(0);  // a 15 cm (3-cell) gap in the wall at x = 3 m
  const std::vector<LineSegment> joined = ExtractLines(grid);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_GT(eval::EvaluateLineMap(Geometry(joined), {wall}).coverage, 0.95);
  const std::vector<LineSegment> split = ExtractLines(grid, {.closing_radius_m = 0.0});
  EXPECT_EQ(split.size(), 2u);
}

TEST(LineExtraction, ClosingJoinsDottedThinWallInEveryDirection) {
  // A wall seen at a grazing angle: single occupied cells every 15 cm (3 cells; up to 3.6 cells
  // apart once rounded to cells), one cell thin. A true closing with digital disks joins none.
  for (const double angle_rad : {0.0, 0.3, std::numbers::pi / 4, 1.2}) {
    grid::GridImage grid = BlankGrid({0.0, 0.0}, {6.0, 6.0}, 0.05, 0);
    const Eigen::Vector2d direction(std::cos(angle_rad), std::sin(angle_rad));
    const geometry::Segment2 wall{{0.5, 0.5}, Eigen::Vector2d(0.5, 0.5) + 4.0 * direction};
    for (double along_m = 0.0; along_m <= 4.0 + 1e-9; along_m += 0.15) {
      const Eigen::Vector2d p = wall.start_m + along_m * direction;
      grid.occupancy.at<std::uint8_t>(grid.occupancy.rows - 1 - static_cast<int>(p.y() / 0.05),
                                      static_cast<int>(p.x() / 0.05)) = 255;
    }
    const std::vector<LineSegment> lines = ExtractLines(grid);
    ASSERT_EQ(lines.size(), 1u) << "angle " << angle_rad;
    EXPECT_GT(eval::EvaluateLineMap(Geometry(lines), {wall}).coverage, 0.95) << angle_rad;
  }
}

TEST(LineExtraction, IgnoresSpeckleNoise) {
  std::vector<geometry::Segment2> walls;
  grid::GridImage grid = PlainRoom(&walls);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> col(0, grid.occupancy.cols - 1);
  std::uniform_int_distribution<int> row(0, grid.occupancy.rows - 1);
  for (int k = 0; k < 100; ++k) {
    // Column first, then row, in two statements: the order of a call's arguments is unspecified
    // (gcc and clang differ), and the speckles must land on the same cells with every compiler.
    const int c = col(random);
    const int r = row(random);
    grid.occupancy.at<std::uint8_t>(r, c) = 255;
  }
  const std::vector<LineSegment> lines = ExtractLines(grid);
  const eval::LineMapErrorSummary score = Score(lines, walls);
  EXPECT_GT(score.coverage, 0.95);
  EXPECT_GT(score.precision, 0.98);
  EXPECT_LE(score.fragmentation, 1.5);
  EXPECT_LE(lines.size(), 6u);
}

TEST(LineExtraction, DropsWeakFloorReflectionArc) {
  std::vector<geometry::Segment2> walls;
  grid::GridImage grid = PlainRoom(&walls);
  // A floor reflection: an arc of radius 1.5 m in front of a walker at (3, 0.5), seen weakly
  // (occupancy 0.6: a few hits among misses), in short straight pieces.
  grid::GridImage with_strong_arc = grid;
  with_strong_arc.occupancy = grid.occupancy.clone();
  for (int k = 0; k < 30; ++k) {
    const double a0 = std::numbers::pi * k / 30.0, a1 = std::numbers::pi * (k + 1) / 30.0;
    const geometry::Segment2 piece{{3.0 + 1.5 * std::cos(a0), 0.5 + 1.5 * std::sin(a0)},
                                   {3.0 + 1.5 * std::cos(a1), 0.5 + 1.5 * std::sin(a1)}};
    DrawSegment(grid, piece, 153, 1);
    DrawSegment(with_strong_arc, piece, 255, 1);
  }
  const eval::LineMapErrorSummary weak = Score(ExtractLines(grid), walls);
  EXPECT_GT(weak.precision, 0.99);
  EXPECT_GT(weak.coverage, 0.95);
  // The same arc seen as strongly as a wall does become segments: the threshold removed it.
  EXPECT_LT(Score(ExtractLines(with_strong_arc), walls).precision, 0.9);
}

TEST(LineExtraction, SplitsLCornerIntoTwoSegments) {
  grid::GridImage grid = BlankGrid({0.0, 0.0}, {5.0, 4.0}, 0.05, 0);
  const std::vector<geometry::Segment2> walls{{{0.5, 0.5}, {3.5, 0.5}}, {{3.5, 0.5}, {3.5, 3.0}}};
  for (const geometry::Segment2& wall : walls) DrawSegment(grid, wall, 255, 2);
  const std::vector<LineSegment> lines = ExtractLines(grid);
  ASSERT_EQ(lines.size(), 2u);
  const double turn_rad = std::abs(
      std::remainder(AngleRad(lines[0].segment) - AngleRad(lines[1].segment), std::numbers::pi));
  EXPECT_NEAR(turn_rad, std::numbers::pi / 2, 0.02);
  for (const LineSegment& line : lines) {
    const double corner_m = std::min((line.segment.start_m - Eigen::Vector2d(3.5, 0.5)).norm(),
                                     (line.segment.end_m - Eigen::Vector2d(3.5, 0.5)).norm());
    EXPECT_LT(corner_m, 0.1);
  }
  EXPECT_GT(Score(lines, walls).coverage, 0.95);
}

TEST(LineExtraction, FollowsObliqueWall) {
  grid::GridImage grid = BlankGrid({0.0, 0.0}, {6.0, 4.0}, 0.05, 0);
  const geometry::Segment2 wall{{0.5, 0.5}, {5.0, 3.1}};  // about 30 deg
  DrawSegment(grid, wall, 255, 2);
  const std::vector<LineSegment> lines = ExtractLines(grid);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NEAR(
      std::abs(std::remainder(AngleRad(lines[0].segment) - AngleRad(wall), std::numbers::pi)), 0.0,
      0.01);
  EXPECT_GT(eval::EvaluateLineMap(Geometry(lines), {wall}).coverage, 0.95);
}

TEST(LineExtraction, FindsNothingInFreeOrUnknownGrid) {
  EXPECT_TRUE(ExtractLines(BlankGrid({0.0, 0.0}, {3.0, 3.0}, 0.05, 0)).empty());
  EXPECT_TRUE(ExtractLines(BlankGrid({0.0, 0.0}, {3.0, 3.0}, 0.05, 128)).empty());
  EXPECT_TRUE(ExtractLines(grid::GridImage{}).empty());
}

void ExpectRejected(const LineExtractionOptions& options, const std::string& field,
                    const std::string& unit) {
  try {
    ExtractLines(BlankGrid({0.0, 0.0}, {1.0, 1.0}, 0.05), options);
    ADD_FAILURE() << field << " accepted";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("line_extraction." + field), std::string::npos) << message;
    EXPECT_NE(message.find(unit), std::string::npos) << message;
  }
}

TEST(LineExtraction, RejectsOptionsOutOfRangeNamingFieldAndUnit) {
  ExpectRejected({.occupied_probability = 1.0}, "occupied_probability", "(0, 1)");
  ExpectRejected({.occupied_probability = 0.0}, "occupied_probability", "(0, 1)");
  ExpectRejected({.closing_radius_m = -0.1}, "closing_radius_m", " m");
  ExpectRejected({.min_blob_m = -1.0}, "min_blob_m", " m");
  ExpectRejected({.split_distance_m = 0.0}, "split_distance_m", " m");
  ExpectRejected({.merge_gap_m = -0.5}, "merge_gap_m", " m");
  ExpectRejected({.merge_angle_rad = 2.0}, "merge_angle_rad", "rad");
  ExpectRejected({.min_length_m = std::nan("")}, "min_length_m", " m");
  EXPECT_NO_THROW(ValidateLineExtractionOptions({}));
}

TEST(LineExtraction, RejectsGridThatIsNotAnOccupancyImage) {
  grid::GridImage wrong_type = BlankGrid({0.0, 0.0}, {1.0, 1.0}, 0.05);
  wrong_type.occupancy.convertTo(wrong_type.occupancy, CV_32F);
  EXPECT_THROW(ExtractLines(wrong_type), std::invalid_argument);
  grid::GridImage no_resolution = BlankGrid({0.0, 0.0}, {1.0, 1.0}, 0.05);
  no_resolution.resolution_m = 0.0;
  EXPECT_THROW(ExtractLines(no_resolution), std::invalid_argument);
}

}  // namespace
}  // namespace pena::line_map
