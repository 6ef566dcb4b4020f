// A priori plans: CSV, SVG and DXF read into the mission frame; options; bad files named.
#include "pena/io/plan_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "io_test_util.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/line_svg.hpp"

namespace pena::io {
namespace {

using testing::WriteText;
constexpr double kTolM = 1e-9;

void ExpectSegment(const geometry::Segment2& s, double x1, double y1, double x2, double y2) {
  EXPECT_NEAR(s.start_m.x(), x1, kTolM);
  EXPECT_NEAR(s.start_m.y(), y1, kTolM);
  EXPECT_NEAR(s.end_m.x(), x2, kTolM);
  EXPECT_NEAR(s.end_m.y(), y2, kTolM);
}

TEST(PlanReader, ReadsLineCsvAndAppliesScaleThenPose) {
  const auto path =
      WriteText("plan.csv", "id,x1,y1,x2,y2,label\n1,0,0,1000,0,wall\n2,0,0,0,2000\n");
  PlanOptions options;
  options.unit_scale_m = 0.001;  // a millimetre drawing
  options.mission_from_plan = {10.0, -5.0, std::numbers::pi / 2};
  const auto plan = ReadPlan(path, options);
  ASSERT_EQ(plan.size(), 2u);
  ExpectSegment(plan[0], 10.0, -5.0, 10.0, -4.0);  // +x of the plan is +y of the mission
  ExpectSegment(plan[1], 10.0, -5.0, 8.0, -5.0);
}

TEST(PlanReader, RejectsBadOptionsNamingTheField) {
  const auto path = WriteText("plan.csv", "id,x1,y1,x2,y2\n1,0,0,1,0\n");
  for (const double scale : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    PlanOptions options;
    options.unit_scale_m = scale;
    try {
      ReadPlan(path, options);
      ADD_FAILURE() << "scale " << scale << " accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("plan.unit_scale_m"), std::string::npos);
    }
  }
}

TEST(PlanReader, UnknownExtensionAndMissingFileAreInputErrors) {
  EXPECT_THROW(ReadPlan(WriteText("plan.pdf", "%PDF")), InputError);
  EXPECT_THROW(ReadPlan(testing::TempPath("missing.dxf")), InputError);
  EXPECT_THROW(ReadPlan(testing::TempPath("missing.svg")), InputError);
}

TEST(PlanReader, ExtensionIsCaseInsensitiveAndZeroLengthSegmentsAreDropped) {
  const auto plan = ReadPlan(WriteText("PLAN.CSV", "id,x1,y1,x2,y2\n1,0,0,1,0\n2,3,3,3,3\n"));
  ASSERT_EQ(plan.size(), 1u);
  ExpectSegment(plan[0], 0, 0, 1, 0);
}

TEST(PlanReader, ReadsBackOwnSvgUpToItsMarginShift) {
  // WriteLineSvg draws y up through a flipping group; the reader undoes the flip, so the walls
  // come back translated by (margin - min_x, -(max_y + margin)) and nothing else.
  std::vector<geometry::Segment2> walls = {{{0, 0}, {4, 0}}, {{4, 0}, {4, 3}}, {{1, 2}, {3, 2.5}}};
  const auto path = testing::TempPath("walls.svg");
  WriteLineSvg(path, {SvgLayer{"walls", "#000000", 0.05, walls}}, 1.0);
  const auto plan = ReadPlan(path);
  ASSERT_GE(plan.size(), walls.size());  // plus the scale bar and the legend swatch
  const Eigen::Vector2d shift(1.0, -4.0);
  for (std::size_t i = 0; i < walls.size(); ++i) {
    EXPECT_NEAR((plan[i].start_m - walls[i].start_m - shift).norm(), 0.0, 1e-4);
    EXPECT_NEAR((plan[i].end_m - walls[i].end_m - shift).norm(), 0.0, 1e-4);
  }
}

}  // namespace
}  // namespace pena::io
