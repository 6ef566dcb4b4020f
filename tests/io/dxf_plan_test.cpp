// DXF plans: LINE, LWPOLYLINE (open, closed, bulged), POLYLINE/VERTEX, and malformed files.
#include <gtest/gtest.h>

#include "io_test_util.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/plan_reader.hpp"

namespace pena::io {
namespace {

using testing::WriteText;
constexpr double kTolM = 1e-9;

// An ASCII DXF with a HEADER that must be ignored and the given ENTITIES groups.
std::string Dxf(const std::string& entities) {
  return "  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1009\n  0\nENDSEC\n"
         "  0\nSECTION\n  2\nENTITIES\n" +
         entities + "  0\nENDSEC\n  0\nEOF\n";
}

void ExpectSegment(const geometry::Segment2& s, double x1, double y1, double x2, double y2) {
  EXPECT_NEAR(s.start_m.x(), x1, kTolM);
  EXPECT_NEAR(s.start_m.y(), y1, kTolM);
  EXPECT_NEAR(s.end_m.x(), x2, kTolM);
  EXPECT_NEAR(s.end_m.y(), y2, kTolM);
}

std::size_t ErrorLine(const std::string& content) {
  try {
    ReadPlan(WriteText("bad.dxf", content));
  } catch (const InputError& error) {
    return error.line();
  }
  ADD_FAILURE() << "no InputError for " << content;
  return 0;
}

TEST(DxfPlan, ReadsLinesInAnyGroupOrder) {
  const auto plan = ReadPlan(WriteText(
      "plan.dxf", Dxf("  0\nLINE\n  8\nWALLS\n 11\n4.0\n 21\n0.0\n 10\n0.5\n 20\n-1\n 30\n0\n"
                      "  0\nCIRCLE\n 10\n1\n 20\n1\n 40\n1\n")));
  ASSERT_EQ(plan.size(), 1u);
  ExpectSegment(plan[0], 0.5, -1.0, 4.0, 0.0);
}

TEST(DxfPlan, ReadsLightweightPolylinesWithClosedFlagAndSkipsArcs) {
  const auto plan = ReadPlan(WriteText(
      "plan.dxf",
      Dxf("  0\nLWPOLYLINE\n 90\n3\n 70\n1\n 10\n0\n 20\n0\n 10\n2\n 20\n0\n 10\n2\n 20\n1\n"
          "  0\nLWPOLYLINE\n 90\n3\n 70\n0\n 10\n5\n 20\n5\n 42\n1.0\n 10\n6\n 20\n5\n"
          " 10\n7\n 20\n5\n")));
  ASSERT_EQ(plan.size(), 4u);
  ExpectSegment(plan[0], 0, 0, 2, 0);
  ExpectSegment(plan[1], 2, 0, 2, 1);
  ExpectSegment(plan[2], 2, 1, 0, 0);  // closed
  ExpectSegment(plan[3], 6, 5, 7, 5);  // the bulged span 5->6 is an arc, not a wall
}

TEST(DxfPlan, ReadsOldStylePolylinesAndCrLfLines) {
  std::string dxf = Dxf(
      "  0\nPOLYLINE\n 66\n1\n 70\n1\n  0\nVERTEX\n 10\n0\n 20\n0\n  0\nVERTEX\n 10\n3\n 20\n0\n"
      "  0\nVERTEX\n 10\n3\n 20\n3\n  0\nSEQEND\n");
  std::string crlf;
  for (const char c : dxf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  PlanOptions options;
  options.unit_scale_m = 0.5;
  const auto plan = ReadPlan(WriteText("plan.dxf", crlf), options);
  ASSERT_EQ(plan.size(), 3u);
  ExpectSegment(plan[1], 1.5, 0, 1.5, 1.5);
  ExpectSegment(plan[2], 1.5, 1.5, 0, 0);
}

TEST(DxfPlan, MalformedFilesNameTheirLine) {
  // Dxf() puts 14 lines before the entities: "  0" is line 15, "LINE" 16, " 10" 17, "x" 18.
  EXPECT_EQ(ErrorLine(Dxf("  0\nLINE\n 10\nx\n 20\n0\n 11\n1\n 21\n1\n")), 18u);
  EXPECT_EQ(ErrorLine(Dxf("  0\nLINE\n 10\n0\n 20\n0\n")), 16u);              // no end point
  EXPECT_EQ(ErrorLine(Dxf("  0\nLINE\nten\n0\n")), 17u);                      // code not a number
  EXPECT_EQ(ErrorLine("  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n 10\n"), 7u);  // value missing
  EXPECT_EQ(ErrorLine("  0\nSECTION\n  2\nENTITIES\n  0\nENDSEC\n"), 6u);     // no EOF
  EXPECT_EQ(ErrorLine("  0\nSECTION\n  2\nHEADER\n  0\nENDSEC\n  0\nEOF\n"), 8u);  // no ENTITIES
  EXPECT_EQ(ErrorLine("AutoCAD Binary DXF\r\n\x1a"), 1u);
}

}  // namespace
}  // namespace pena::io
