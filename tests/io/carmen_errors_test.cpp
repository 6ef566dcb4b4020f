// Bad CARMEN input: every error names the file and the line, and skip mode keeps the good lines.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "io_test_util.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/input_error.hpp"

namespace pena::io {
namespace {

using testing::FlaserLine;
using testing::ReadAll;
using testing::WriteText;

// Reads the whole log and returns the InputError it throws (fails the test if none).
InputError ReadExpectingError(const std::filesystem::path& path, const ReadOptions& options = {}) {
  try {
    auto source = OpenLog(path, options);
    ReadAll(*source);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError reading " << path;
  return InputError(path, 0, "none");
}

// Two good lines, then `bad` on line 3, then a good line.
std::string WithBadThirdLine(const std::string& bad) {
  return FlaserLine(181, "3", "1.0") + "ODOM 0 0 0 0 0 0 1.0 h 1.0\n" + bad +
         FlaserLine(181, "3", "2.0");
}

struct BadLineCase {
  const char* name;
  std::string line;
  const char* message;  // expected part of what()
};

class CarmenBadLine : public ::testing::TestWithParam<BadLineCase> {};

TEST_P(CarmenBadLine, ThrowsWithFileAndLineNumber) {
  const auto path = WriteText(std::string(GetParam().name) + ".clf", WithBadThirdLine(GetParam().line));
  const InputError error = ReadExpectingError(path);
  EXPECT_EQ(error.line(), 3u);
  EXPECT_EQ(error.path(), path);
  const std::string what = error.what();
  EXPECT_EQ(what.rfind(path.string() + ":3: ", 0), 0u) << what;
  EXPECT_NE(what.find(GetParam().message), std::string::npos) << what;
}

TEST_P(CarmenBadLine, IsSkippedAndCountedInSkipMode) {
  const auto path = WriteText(std::string(GetParam().name) + ".clf", WithBadThirdLine(GetParam().line));
  ReadOptions options;
  options.skip_malformed = true;
  auto source = OpenLog(path, options);
  const auto records = ReadAll(*source);
  EXPECT_EQ(records.size(), 3u);
  EXPECT_EQ(source->skipped(), 1u);
  EXPECT_DOUBLE_EQ(sensors::StampOf(records.back()), 2.0);
}

std::string FlaserWithRange(std::size_t beam, const std::string& value) {
  std::string line = "FLASER 181";
  for (std::size_t i = 0; i < 181; ++i) line += " " + (i == beam ? value : std::string("3"));
  return line + " 0 0 0 0 0 0 1.5 h 1.5\n";
}

std::string ShortFlaser() {
  std::string line = "FLASER 180";
  for (int i = 0; i < 12; ++i) line += " 3";
  return line + " 0 0 0 0 0 0 1.5 h 1.5\n";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CarmenBadLine,
    ::testing::Values(
        BadLineCase{"TooFewRanges", ShortFlaser(), "expected 180 ranges, found 12"},
        BadLineCase{"NanRange", FlaserWithRange(17, "nan"), "range 17 is NaN"},
        BadLineCase{"NegativeRange", FlaserWithRange(3, "-0.5"), "negative range -0.5 at beam 3"},
        BadLineCase{"TextRange", FlaserWithRange(5, "abc"), "range 5 'abc' is not a number"},
        BadLineCase{"TextStamp", FlaserLine(181, "3", "noon"), "(ipc_timestamp) 'noon' is not a number"},
        BadLineCase{"TextOdom", "ODOM 0 zero 0 0 0 0 1.2 h 1.2\n", "(y) 'zero' is not a number"},
        BadLineCase{"ShortOdom", "ODOM 0 0 0 1.2 h 1.2\n", "expected 10 fields in ODOM, found 7"},
        BadLineCase{"ShortRobotLaser", "ROBOTLASER1 0 -2 4 1 30 0.01 0 5 1 2\n",
                    "expected 5 ranges and a remission count"},
        BadLineCase{"BadCount", "FLASER many 1 2 3\n", "beam count 'many' is not an integer"},
        BadLineCase{"TimeGoesBack", FlaserLine(181, "3", "-5.0"),
                    "timestamp -5 is not after the previous FLASER at 1"}),
    [](const ::testing::TestParamInfo<BadLineCase>& case_info) { return std::string(case_info.param.name); });

TEST(CarmenErrors, MissingFileIsAnInputErrorAtLineZero) {
  const auto path = testing::TempPath("does_not_exist.clf.gz");
  const InputError error = ReadExpectingError(path);
  EXPECT_EQ(error.line(), 0u);
  EXPECT_NE(std::string(error.what()).find(path.string() + ":0: no such file"), std::string::npos);
}

TEST(CarmenErrors, TruncatedGzipReportsTheLineReached) {
  std::string log;
  for (int i = 0; i < 400; ++i) log += FlaserLine(181, std::to_string(1 + i % 7), std::to_string(i));
  const auto whole = testing::WriteGzip("whole.clf.gz", log);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto cut = WriteText("cut.clf.gz", bytes.substr(0, bytes.size() / 2));

  std::size_t complete_lines = 0;
  try {
    auto source = OpenCarmenLog(cut);
    while (source->Next()) ++complete_lines;
    FAIL() << "a truncated gzip read without error";
  } catch (const InputError& error) {
    EXPECT_GT(complete_lines, 0u);
    EXPECT_LT(complete_lines, 400u);
    // The error is at the line after the last complete one: the one the data ran out in.
    EXPECT_EQ(error.line(), complete_lines + 1);
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
  }
  // Skipping malformed lines must not hide a truncated file.
  ReadOptions skip;
  skip.skip_malformed = true;
  EXPECT_THROW(ReadAll(*OpenCarmenLog(cut, skip)), InputError);
}

// A NUL byte is a byte like any other: the line holding it is the malformed one, the lines
// around it read as written, and a file ending in NULs without a newline ends cleanly (the input
// tests/fuzz found: the line reader lost the rest of such a line, or read before an empty one).
TEST(CarmenErrors, NulByteIsAnErrorOnItsOwnLine) {
  const std::string nul_in_number = std::string("FLASER 3 1 2") + '\0' + "3 0 0 0 0 0 0 2.0 h 2.0\n";
  const auto path = WriteText("nul.clf", FlaserLine(181, "3", "1.0") + nul_in_number +
                                             FlaserLine(181, "3", "3.0"));
  try {
    ReadAll(*OpenCarmenLog(path));
    ADD_FAILURE() << "a NUL byte inside a number read without error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 2u) << error.what();
  }
  ReadOptions skip;
  skip.skip_malformed = true;
  auto source = OpenCarmenLog(path, skip);
  EXPECT_EQ(ReadAll(*source).size(), 2u);
  EXPECT_EQ(source->skipped(), 1u);

  const auto tail = WriteText("nul_tail.clf", FlaserLine(181, "3", "1.0") + std::string(3, '\0'));
  EXPECT_EQ(ReadAll(*OpenCarmenLog(tail)).size(), 1u);
}

TEST(CarmenErrors, UnrecognisedFormatIsRefused) {
  const auto path = WriteText("table.csv", "id,x1,y1,x2,y2\n1,0,0,1,1\n");
  const InputError error = ReadExpectingError(path);
  EXPECT_EQ(error.line(), 0u);
  EXPECT_NE(std::string(error.what()).find("format not recognised"), std::string::npos);
}

TEST(CarmenErrors, MarkdownStartingWithHashIsRefused) {
  // '#' starts a CARMEN comment, so the first non-comment line decides.
  const auto path = WriteText("README.md", "# A title\n\nSome prose about the project.\n");
  const InputError error = ReadExpectingError(path);
  EXPECT_EQ(error.line(), 0u);
  EXPECT_NE(std::string(error.what()).find("format not recognised"), std::string::npos);
}

TEST(CarmenErrors, CommentedLogIsAccepted) {
  const auto path = WriteText("commented.clf", "# CARMEN Logfile\n# file format is ...\n" +
                                                   FlaserLine(181, "3", "1"));
  EXPECT_EQ(ReadAll(*OpenLog(path)).size(), 1u);
}

TEST(CarmenErrors, InvalidMaxRangeOptionIsRefused) {
  const auto path = WriteText("ok.clf", FlaserLine(181, "3", "1"));
  ReadOptions options;
  options.carmen_max_range_m = -1.0;
  EXPECT_THROW(OpenCarmenLog(path, options), std::invalid_argument);
}

}  // namespace
}  // namespace pena::io
