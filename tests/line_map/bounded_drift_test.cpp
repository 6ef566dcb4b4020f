// LineMapOptions::refit_band_m and absorb_distance_m (docs/line-map.md, "Bounded drift"): a piece
// off a wall's line does not move it, the better supported side keeps its line, near duplicates
// are absorbed, and the drift of a revisited wall stays within the band.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "loop_walls.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::line_map {
namespace {

using testing::Piece;

LineMapOptions Bounded(double band_m, double absorb_m = 0.0) {
  LineMapOptions options;
  options.refit_band_m = band_m;
  options.absorb_distance_m = absorb_m;
  return options;
}

// Largest distance of a segment's endpoints from the line y = y_m.
double OffsetFromY(const LineSegment& line, double y_m) {
  return std::max(std::abs(line.segment.start_m.y() - y_m), std::abs(line.segment.end_m.y() - y_m));
}

TEST(BoundedDrift, PieceOffTheLineOnlyExtendsIt) {
  LineMap map(Bounded(0.03));
  map.Integrate({Piece(0.0, 0.0, 4.0, 0.0, 900.0)}, "ff1");
  map.Integrate({Piece(2.0, 0.08, 6.0, 0.08, 100.0)}, "ff1");
  ASSERT_EQ(map.size(), 1u);
  const LineSegment wall = map.segments().front();
  // Without the band the line moves to y = 0.008 (LineMapMerge.WeightsRefitByObservations).
  EXPECT_EQ(wall.segment.start_m.y(), 0.0);
  EXPECT_EQ(wall.segment.end_m.y(), 0.0);
  EXPECT_EQ(wall.segment.start_m.x(), 0.0);
  EXPECT_EQ(wall.segment.end_m.x(), 6.0);
  EXPECT_EQ(wall.observations, 900.0);  // the piece does not support the line where it lies
  EXPECT_GT(wall.rms_error_m, 0.02);    // but its offset shows in the fit error
}

TEST(BoundedDrift, PieceWithinTheBandRefitsAsBefore) {
  LineMap bounded(Bounded(0.03));
  LineMap plain;
  for (LineMap* map : {&bounded, &plain}) {
    map->Integrate({Piece(0.0, 0.0, 4.0, 0.0, 900.0)}, "ff1");
    map->Integrate({Piece(2.0, 0.02, 6.0, 0.02, 100.0)}, "ff1");
  }
  EXPECT_TRUE(SameMap(bounded.Snapshot(), plain.Snapshot()));
}

TEST(BoundedDrift, HeavierPieceCorrectsALightLineAndKeepsItsDirectionAndId) {
  LineMap map(Bounded(0.03));
  map.Integrate({Piece(4.0, 0.09, 0.0, 0.0, 20.0)}, "ff1");  // weak, tilted, pointing -x
  map.Integrate({Piece(0.0, 0.0, 5.0, 0.0, 900.0)}, "ff1");
  ASSERT_EQ(map.size(), 1u);
  const LineSegment wall = map.segments().front();
  EXPECT_EQ(wall.id, 1);
  EXPECT_EQ(OffsetFromY(wall, 0.0), 0.0);
  EXPECT_EQ(wall.segment.start_m.x(), 5.0);  // still points -x like the oldest part
  EXPECT_EQ(wall.segment.end_m.x(), 0.0);
  EXPECT_EQ(wall.observations, 900.0);
}

TEST(BoundedDrift, AbsorbsANearDuplicateButKeepsParallelWallsApart) {
  for (const double absorb_m : {0.0, 0.2}) {
    LineMap map(Bounded(0.03, absorb_m));
    map.Integrate({Piece(0.0, 0.0, 5.0, 0.0, 900.0), Piece(0.0, 0.6, 5.0, 0.6, 900.0)}, "ff1");
    map.Integrate({Piece(1.0, 0.15, 4.0, 0.14, 30.0)}, "ff1");  // 15 cm off the first
    map.Integrate({Piece(1.0, 0.3, 4.0, 0.3, 900.0)}, "ff1");   // 30 cm from both: a wall
    EXPECT_EQ(map.size(), absorb_m > 0.0 ? 3u : 4u) << "absorb " << absorb_m;
    EXPECT_EQ(OffsetFromY(map.segments().front(), 0.0), 0.0);
  }
}

// A wall seen well once, then revisited 30 times by pieces lying 4-8 cm to one side of it (a
// moving local window that sees it only at a grazing angle). Without the band the pieces pull
// the line towards them; with it, the line stays where the good view put it.
double DriftAfterRevisits(const LineMapOptions& options) {
  LineMap map(options);
  map.Integrate({Piece(0.0, 0.0, 8.0, 0.0, 400.0)}, "ff1");
  for (int visit = 0; visit < 30; ++visit) {
    const double x0 = 0.2 * (visit % 25);
    const double y_m = 0.06 + 0.02 * std::sin(visit);
    map.Integrate({Piece(x0, y_m, x0 + 3.0, y_m + 0.01 * std::cos(visit), 100.0)}, "ff1");
  }
  EXPECT_EQ(map.size(), 1u);
  return map.size() == 0 ? 0.0 : OffsetFromY(map.segments().front(), 0.0);
}

TEST(BoundedDrift, RevisitedWallStaysWithinTheBand) {
  const double plain_m = DriftAfterRevisits({});
  const double bounded_m = DriftAfterRevisits(Bounded(0.03));
  std::cout << "wall revisited 30 times, pieces 4-8 cm off: line off by " << plain_m
            << " m without the band, " << bounded_m << " m with a 3 cm band\n";
  EXPECT_LE(bounded_m, 0.03);
  EXPECT_LT(bounded_m, plain_m);
}

TEST(BoundedDrift, RejectsBadOptions) {
  for (const double bad : {-0.01, std::nan("")}) {
    EXPECT_THROW(LineMap(Bounded(bad)), std::invalid_argument);
    try {
      LineMap(Bounded(0.03, bad));
      FAIL() << "accepted absorb_distance_m " << bad;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("absorb_distance_m"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace pena::line_map
