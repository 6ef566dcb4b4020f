// SVG plans: elements, path commands, transforms, hidden content and malformed files.
#include <gtest/gtest.h>

#include "io_test_util.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/plan_reader.hpp"

namespace pena::io {
namespace {

using testing::WriteText;
constexpr double kTolM = 1e-9;

std::vector<geometry::Segment2> ReadSvg(const std::string& body) {
  return ReadPlan(WriteText("plan.svg",
                            "<?xml version=\"1.0\"?>\n<!-- a plan -->\n"
                            "<svg xmlns=\"http://www.w3.org/2000/svg\">\n" +
                                body + "\n</svg>\n"));
}

// SVG's y points down; the plan frame's y is its negation.
void ExpectSvgSegment(const geometry::Segment2& s, double x1, double y1, double x2, double y2) {
  EXPECT_NEAR(s.start_m.x(), x1, kTolM);
  EXPECT_NEAR(s.start_m.y(), -y1, kTolM);
  EXPECT_NEAR(s.end_m.x(), x2, kTolM);
  EXPECT_NEAR(s.end_m.y(), -y2, kTolM);
}

std::size_t ErrorLine(const std::string& content) {
  try {
    ReadPlan(WriteText("bad.svg", content));
  } catch (const InputError& error) {
    return error.line();
  }
  ADD_FAILURE() << "no InputError for " << content;
  return 0;
}

TEST(SvgPlan, ReadsLinePolylinePolygonAndRect) {
  const auto plan = ReadSvg(
      "<line x1='1' y1='2' x2=\"3px\" y2='4'/>\n"
      "<polyline points='0,0 1,0 1,1'/>\n"
      "<polygon points='5 5, 6 5, 6 6'/>\n"
      "<rect x='10' y='10' width='2' height='1' fill='none'/>");
  ASSERT_EQ(plan.size(), 1u + 2u + 3u + 4u);
  ExpectSvgSegment(plan[0], 1, 2, 3, 4);
  ExpectSvgSegment(plan[2], 1, 0, 1, 1);
  ExpectSvgSegment(plan[5], 6, 6, 5, 5);  // the polygon closes
  ExpectSvgSegment(plan[7], 12, 10, 12, 11);
}

TEST(SvgPlan, ReadsPathCommandsAbsoluteAndRelative) {
  const auto plan = ReadSvg("<path d='M0 0 L2 0 H3 V1 l-1,1 h-1 v-1 z m5,5 4,0 1-1e0Z'/>");
  ASSERT_EQ(plan.size(), 10u);
  ExpectSvgSegment(plan[0], 0, 0, 2, 0);
  ExpectSvgSegment(plan[1], 2, 0, 3, 0);
  ExpectSvgSegment(plan[2], 3, 0, 3, 1);
  ExpectSvgSegment(plan[3], 3, 1, 2, 2);
  ExpectSvgSegment(plan[4], 2, 2, 1, 2);
  ExpectSvgSegment(plan[5], 1, 2, 1, 1);
  ExpectSvgSegment(plan[6], 1, 1, 0, 0);   // z back to the subpath start
  ExpectSvgSegment(plan[7], 5, 5, 9, 5);   // after z the pen is at (0,0); m is relative to it
  ExpectSvgSegment(plan[8], 9, 5, 10, 4);  // implicit lineto pairs after m are relative
  ExpectSvgSegment(plan[9], 10, 4, 5, 5);
}

TEST(SvgPlan, SkipsCurvesButFollowsTheirEndPoints) {
  const auto plan =
      ReadSvg("<path d='M0,0 C1,1 2,1 3,0 L4,0 a1 1 0 011 1 L5,5 Q6,6 7,7 T8,8 l1,0'/>");
  ASSERT_EQ(plan.size(), 3u);
  ExpectSvgSegment(plan[0], 3, 0, 4, 0);
  ExpectSvgSegment(plan[1], 5, 1, 5, 5);
  ExpectSvgSegment(plan[2], 8, 8, 9, 8);
}

TEST(SvgPlan, AppliesNestedTransforms) {
  const auto plan = ReadSvg(
      "<g transform='translate(10,20)'><g transform='scale(2) rotate(90)'>"
      "<line x1='0' y1='0' x2='1' y2='0' transform='matrix(1 0 0 1 0 1)'/></g></g>");
  ASSERT_EQ(plan.size(), 1u);
  // (0,0) -> (0,1) -> rotate 90: (-1,0) -> scale: (-2,0) -> (8,20).
  ExpectSvgSegment(plan[0], 8, 20, 8, 22);
}

TEST(SvgPlan, IgnoresDefsTextCdataAndViewportSizedBackgrounds) {
  const auto plan = ReadSvg(
      "<defs><line x1='0' y1='0' x2='9' y2='9'/></defs>\n"
      "<style><![CDATA[ line { stroke: <black> } ]]></style>\n"
      "<rect width='100%' height='100%' fill='white'/>\n"
      "<text x='1' y='1'>Room 1 &amp; 2</text><line x1='0' y1='0' x2='1' y2='0'/>");
  ASSERT_EQ(plan.size(), 1u);
}

TEST(SvgPlan, MalformedFilesNameTheirLine) {
  EXPECT_EQ(ErrorLine("<svg>\n<line x1='a' y1='0' x2='1' y2='1'/>\n</svg>\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n\n<path d='M0 0 X5 5'/>\n</svg>\n"), 3u);
  EXPECT_EQ(ErrorLine("<svg>\n<path d='L0 0 5 5'/>\n</svg>\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n<polyline points='0 0 1'/>\n</svg>\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n<line x1='1mm' y1='0' x2='1' y2='1'/>\n</svg>\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n<g transform='wobble(3)'>\n</g></svg>\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n<g>\n</svg>\n"), 3u);   // mismatched end tag
  EXPECT_EQ(ErrorLine("<svg>\n<g>\n<line/>\n"), 4u);  // truncated: <g> never closed
  EXPECT_EQ(ErrorLine("<svg>\n<!-- never ends\n"), 2u);
  EXPECT_EQ(ErrorLine("<svg>\n<line x1=1/>\n</svg>\n"), 2u);  // unquoted attribute
  EXPECT_EQ(ErrorLine("<html></html>\n"), 1u);                // no <svg>
}

}  // namespace
}  // namespace pena::io
