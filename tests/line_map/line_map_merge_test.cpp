#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "loop_walls.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::line_map {
namespace {

using testing::Piece;

TEST(LineMapMerge, MergesCollinearOverlappingPiecesIntoOne) {
  LineMap map;
  map.Integrate({Piece(0.0, 1.0, 3.0, 1.01), Piece(2.0, 0.99, 5.0, 1.0)}, "ff1");
  map.Integrate({Piece(4.8, 1.02, 8.0, 1.0)}, "ff1");
  ASSERT_EQ(map.size(), 1u);
  const LineSegment wall = map.segments().front();
  EXPECT_EQ(wall.id, 1);
  EXPECT_NEAR(wall.segment.start_m.x(), 0.0, 0.01);
  EXPECT_NEAR(wall.segment.end_m.x(), 8.0, 0.01);
  EXPECT_NEAR(wall.segment.start_m.y(), 1.0, 0.02);
  EXPECT_NEAR(wall.segment.end_m.y(), 1.0, 0.02);
  EXPECT_EQ(wall.observations, 150.0);
  EXPECT_GT(wall.rms_error_m, 0.0);
  EXPECT_LT(wall.rms_error_m, 0.03);
}

TEST(LineMapMerge, WeightsRefitByObservations) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 4.0, 0.0, 900.0)}, "ff1");
  map.Integrate({Piece(0.0, 0.08, 4.0, 0.08, 100.0)}, "ff1");
  ASSERT_EQ(map.size(), 1u);
  // Nine times the hits on y = 0: the refit lies at 0.1 of the way to y = 0.08.
  EXPECT_NEAR(map.segments().front().segment.start_m.y(), 0.008, 0.0011);
}

TEST(LineMapMerge, KeepsParallelWallsThirtyCentimetresApart) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 5.0, 0.0), Piece(0.0, 0.3, 5.0, 0.3)}, "ff1");
  map.Integrate({Piece(1.0, 0.01, 6.0, 0.0), Piece(1.0, 0.29, 6.0, 0.31)}, "ff2");
  EXPECT_EQ(map.size(), 2u);
}

TEST(LineMapMerge, KeepsDoorwayAndCornerApart) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 4.0, 0.0), Piece(4.9, 0.0, 8.0, 0.0)}, "ff1");
  map.Integrate({Piece(8.0, 0.0, 8.0, 5.0)}, "ff1");
  EXPECT_EQ(map.size(), 3u);
}

TEST(LineMapMerge, BridgingPieceKeepsOldestIdAndProvenance) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 3.0, 0.0)}, "ff1");
  map.Integrate({Piece(3.6, 0.0, 6.0, 0.0)}, "ff2");  // 0.6 m gap: two walls so far
  ASSERT_EQ(map.size(), 2u);
  const MapDelta delta = map.Integrate({Piece(2.5, 0.0, 4.0, 0.0)}, "robot1");
  ASSERT_EQ(map.size(), 1u);
  const LineSegment wall = map.segments().front();
  EXPECT_EQ(wall.id, 1);
  EXPECT_EQ(wall.provenance, (std::vector<std::string>{"ff1", "#2", "ff2", "robot1"}));
  EXPECT_NEAR(geometry::Length(wall.segment), 6.0, 0.002);
  EXPECT_TRUE(delta.added.empty());
  ASSERT_EQ(delta.changed.size(), 1u);
  EXPECT_EQ(delta.changed.front().id, 1);
  EXPECT_EQ(delta.removed, (std::vector<std::int64_t>{2}));
}

TEST(LineMapMerge, NewIdsAreNeverReused) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 3.0, 0.0), Piece(3.5, 0.0, 6.0, 0.0)}, "ff1");
  map.Integrate({Piece(2.0, 0.0, 4.0, 0.0)}, "ff1");  // absorbs id 2
  const MapDelta delta = map.Integrate({Piece(0.0, 5.0, 3.0, 5.0)}, "ff1");
  ASSERT_EQ(delta.added.size(), 1u);
  EXPECT_EQ(delta.added.front().id, 3);
}

TEST(LineMapMerge, StoresWholeMillimetres) {
  LineMap map;
  map.Integrate({Piece(0.12345, 0.00049, 2.71828, 0.0)}, "ff1");
  const LineSegment wall = map.segments().front();
  EXPECT_EQ(wall.segment.start_m.x(), 0.123);
  EXPECT_EQ(wall.segment.start_m.y(), 0.0);
  EXPECT_EQ(wall.segment.end_m.x(), 2.718);
}

TEST(LineMapMerge, KeepsCountAndLengthBoundedOnLoopWalkedThreeTimes) {
  LineMap once;
  for (const auto& batch : testing::WalkLoop(1, 0.02, 7)) once.Integrate(batch, "ff1");
  LineMap thrice;
  for (const auto& batch : testing::WalkLoop(3, 0.02, 7)) thrice.Integrate(batch, "ff1");
  const double walls = static_cast<double>(testing::LoopWalls().size());
  const double count_once = static_cast<double>(once.size());
  const double count_thrice = static_cast<double>(thrice.size());
  const double length_once_m = testing::TotalLength(once.segments());
  const double length_thrice_m = testing::TotalLength(thrice.segments());
  ::testing::Test::RecordProperty("segments_once", std::to_string(once.size()));
  ::testing::Test::RecordProperty("segments_thrice", std::to_string(thrice.size()));
  std::cout << "loop: " << walls << " walls; once " << count_once << " segments, "
            << length_once_m << " m; three times " << count_thrice << " segments, "
            << length_thrice_m << " m\n";
  EXPECT_LE(count_once, 1.5 * walls);
  EXPECT_LE(std::abs(count_thrice - count_once), 0.1 * count_once);
  EXPECT_LE(std::abs(length_thrice_m - length_once_m), 0.1 * length_once_m);
}

LineMapOptions With(double LineMapOptions::*field, double value) {
  LineMapOptions options;
  options.*field = value;
  return options;
}

TEST(LineMapMerge, RejectsBadOptions) {
  EXPECT_THROW(LineMap(With(&LineMapOptions::merge_distance_m, 0.0)), std::invalid_argument);
  EXPECT_THROW(LineMap(With(&LineMapOptions::merge_angle_rad, std::numbers::pi / 2)),
               std::invalid_argument);
  EXPECT_THROW(LineMap(With(&LineMapOptions::max_gap_m, -0.1)), std::invalid_argument);
  try {
    LineMap(With(&LineMapOptions::merge_distance_m, -1.0));
    FAIL() << "accepted a negative merge distance";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("merge_distance_m"), std::string::npos);
  }
}

TEST(LineMapMerge, RejectsNonFiniteInputAndLeavesMapUnchanged) {
  LineMap map;
  map.Integrate({Piece(0.0, 0.0, 3.0, 0.0)}, "ff1");
  const MapSnapshot before = map.Snapshot();
  EXPECT_THROW(map.Integrate({Piece(0.0, 1.0, 1.0, 1.0), Piece(0.0, NAN, 1.0, 0.0)}, "ff1"),
               std::invalid_argument);
  LineSegment negative = Piece(0.0, 1.0, 1.0, 1.0);
  negative.observations = -1.0;
  EXPECT_THROW(map.Integrate({negative}, "ff1"), std::invalid_argument);
  EXPECT_TRUE(SameMap(before, map.Snapshot()));
}

TEST(LineMapMerge, DropsPiecesShorterThanAMillimetre) {
  LineMap map;
  const MapDelta delta = map.Integrate({Piece(1.0, 1.0, 1.0002, 1.0)}, "ff1");
  EXPECT_TRUE(delta.empty());
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.version(), 0u);
}

}  // namespace
}  // namespace pena::line_map
