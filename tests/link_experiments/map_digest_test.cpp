// pena-monitor's map digest (services/monitor/map_digest.hpp): the link experiments decide that
// the command post's map equals fusion's by comparing digests, so equal maps must agree however
// they were carried (LineMap, line CSV) and any moved or renumbered segment must change it.
#include "map_digest.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "pena/io/line_csv.hpp"
#include "pena/line_map/line_segment.hpp"
#include "scoped_temp_dir.hpp"

namespace pena::services {
namespace {

std::vector<line_map::LineSegment> TwoWalls() {
  line_map::LineSegment a;
  a.id = 3;
  a.segment = {{1.234, -2.0}, {5.0, -2.0}};
  line_map::LineSegment b;
  b.id = 7;
  b.segment = {{0.0, 0.0}, {0.0, 10.5}};
  return {a, b};
}

TEST(MapDigest, EqualForTheSameMapReadBackFromALineCsv) {
  const std::vector<line_map::LineSegment> walls = TwoWalls();
  std::vector<io::LineRow> rows;
  for (auto it = walls.rbegin(); it != walls.rend(); ++it)
    rows.push_back({it->id, it->segment, "1"});
  const pena::testing::ScopedTempDir dir("map-digest");
  const auto path = dir / "walls.csv";
  io::WriteLineCsv(path, rows, ",observations");
  EXPECT_EQ(MapDigest(walls), MapDigest(io::ReadLineCsv(path)));
}

TEST(MapDigest, ChangesWhenASegmentMovesOneMillimetre) {
  std::vector<line_map::LineSegment> walls = TwoWalls();
  const std::uint64_t before = MapDigest(walls);
  walls[1].segment.end_m.y() += 0.001;
  EXPECT_NE(before, MapDigest(walls));
}

TEST(MapDigest, IgnoresSubMillimetreNoiseBelowTheMapQuantum) {
  std::vector<line_map::LineSegment> walls = TwoWalls();
  const std::uint64_t before = MapDigest(walls);
  walls[0].segment.start_m.x() += 0.0001;
  EXPECT_EQ(before, MapDigest(walls));
}

TEST(MapDigest, ChangesWhenASegmentIsRenumberedOrRemoved) {
  std::vector<line_map::LineSegment> walls = TwoWalls();
  const std::uint64_t before = MapDigest(walls);
  walls[1].id = 8;
  EXPECT_NE(before, MapDigest(walls));
  walls.pop_back();
  EXPECT_NE(before, MapDigest(walls));
  EXPECT_EQ(DigestHex(0x1234), "0000000000001234");
}

}  // namespace
}  // namespace pena::services
