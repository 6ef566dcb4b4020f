// DXF export: R12 structure, layers, read back by the plan reader, bad input refused.
#include "pena/io/dxf_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io_test_util.hpp"
#include "pena/io/plan_reader.hpp"

namespace pena::io {
namespace {

std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(DxfWriter, WritesR12LinesOnNamedLayersThatReadBack) {
  const std::vector<geometry::Segment2> walls = {{{0, 0}, {4.25, 0}}, {{4.25, 0}, {4.25, -3.125}}};
  const std::vector<geometry::Segment2> doors = {{{1, 0}, {1.9, 0}}};
  const auto path = testing::TempPath("map.dxf");
  WriteLineDxf(path, {DxfLayer{"WALLS", 7, walls}, DxfLayer{"doors-1", 1, doors}});
  const std::string text = Slurp(path);
  EXPECT_NE(text.find("$ACADVER\n  1\nAC1009\n"), std::string::npos);
  EXPECT_NE(text.find("  0\nLAYER\n  2\nWALLS\n 70\n0\n 62\n7\n"), std::string::npos);
  EXPECT_NE(text.find("  0\nLAYER\n  2\ndoors-1\n 70\n0\n 62\n1\n"), std::string::npos);
  EXPECT_NE(text.find("  0\nLINE\n  8\ndoors-1\n 10\n1.0000\n 20\n0.0000\n"), std::string::npos);
  EXPECT_TRUE(text.ends_with("  0\nENDSEC\n  0\nEOF\n"));
  const auto plan = ReadPlan(path);
  ASSERT_EQ(plan.size(), 3u);
  EXPECT_NEAR((plan[1].end_m - walls[1].end_m).norm(), 0.0, 1e-9);
  EXPECT_NEAR((plan[2].start_m - doors[0].start_m).norm(), 0.0, 1e-9);
}

TEST(DxfWriter, EmptyMapIsAValidDrawing) {
  const auto path = testing::TempPath("empty.dxf");
  WriteLineDxf(path, std::vector<geometry::Segment2>{});
  EXPECT_TRUE(ReadPlan(path).empty());
}

TEST(DxfWriter, RefusesBadLayerNamesColoursAndCoordinates) {
  const auto path = testing::TempPath("bad.dxf");
  EXPECT_THROW(WriteLineDxf(path, {DxfLayer{"two words", 7, {}}}), std::invalid_argument);
  EXPECT_THROW(WriteLineDxf(path, {DxfLayer{"", 7, {}}}), std::invalid_argument);
  EXPECT_THROW(WriteLineDxf(path, {DxfLayer{std::string(32, 'A'), 7, {}}}), std::invalid_argument);
  EXPECT_THROW(WriteLineDxf(path, {DxfLayer{"A", 0, {}}}), std::invalid_argument);
  EXPECT_THROW(WriteLineDxf(path, std::vector<geometry::Segment2>{{{0, 0}, {NAN, 1}}}),
               std::invalid_argument);
  EXPECT_THROW(WriteLineDxf(testing::TempPath("no/such/dir/x.dxf"),
                            std::vector<geometry::Segment2>{{{0, 0}, {1, 1}}}),
               std::runtime_error);
}

}  // namespace
}  // namespace pena::io
