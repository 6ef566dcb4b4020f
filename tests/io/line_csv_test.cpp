// Line CSV: round trip with extra columns, and bad headers and rows.
#include <gtest/gtest.h>

#include "io_test_util.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"

namespace pena::io {
namespace {

using testing::WriteText;

std::size_t ErrorLine(const std::filesystem::path& path) {
  try {
    ReadLineCsv(path);
  } catch (const InputError& error) {
    return error.line();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return 0;
}

TEST(LineCsv, RoundTripKeepsIdsMillimetresAndExtraColumns) {
  std::vector<LineRow> rows(3);
  rows[0] = {7, {{1.2344, -0.5}, {3.0, 4.0}}, "12,outer"};
  rows[1] = {-2, {{0.0, 0.0}, {0.0005, 10.0}}, "3,"};
  rows[2] = {40000000000, {{-100.25, 5.5}, {-99.75, 5.5}}, "0,door"};
  const auto path = testing::TempPath("lines.csv");
  WriteLineCsv(path, rows, ",wall_id,label");
  const auto read = ReadLineCsv(path);
  ASSERT_EQ(read.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(read[i].id, rows[i].id);
    EXPECT_EQ(read[i].extra, rows[i].extra);
    EXPECT_NEAR(read[i].segment.start_m.x(), rows[i].segment.start_m.x(), 0.0005);
    EXPECT_NEAR(read[i].segment.start_m.y(), rows[i].segment.start_m.y(), 0.0005);
    EXPECT_NEAR(read[i].segment.end_m.x(), rows[i].segment.end_m.x(), 0.0005);
    EXPECT_NEAR(read[i].segment.end_m.y(), rows[i].segment.end_m.y(), 0.0005);
  }
  EXPECT_DOUBLE_EQ(read[0].segment.start_m.x(), 1.234);  // millimetre precision
}

TEST(LineCsv, ReadsRowsWithoutExtraColumns) {
  const auto rows = ReadLineCsv(WriteText("plain.csv", "id,x1,y1,x2,y2\n1,0,0,1,1\n\n2,1,1,2,2\n"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(rows[1].extra.empty());
  EXPECT_DOUBLE_EQ(rows[1].segment.end_m.y(), 2.0);
}

TEST(LineCsv, BadHeaderAndRowsNameTheirLine) {
  EXPECT_EQ(ErrorLine(WriteText("header.csv", "x1,y1,x2,y2\n1,0,0,1,1\n")), 1u);
  EXPECT_EQ(ErrorLine(WriteText("empty.csv", "")), 1u);
  EXPECT_EQ(ErrorLine(WriteText("cols.csv", "id,x1,y1,x2,y2\n1,0,0,1,1\n2,0,0,1\n")), 3u);
  EXPECT_EQ(ErrorLine(WriteText("num.csv", "id,x1,y1,x2,y2\n1,0,zero,1,1\n")), 2u);
  EXPECT_EQ(ErrorLine(WriteText("id.csv", "id,x1,y1,x2,y2\n1.5,0,0,1,1\n")), 2u);
  EXPECT_EQ(ErrorLine(testing::TempPath("missing.csv")), 0u);
}

}  // namespace
}  // namespace pena::io
