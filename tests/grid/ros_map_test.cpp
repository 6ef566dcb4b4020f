#include "pena/io/ros_map.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "grid_test_util.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/input_error.hpp"
#include "scoped_temp_dir.hpp"

namespace pena::io {
namespace {

std::filesystem::path TempStem(const std::string& name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = pena::testing::ProcessTempDir() /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A 4 x 3 image: free, unknown and occupied cells in a known layout, plus an in-between value.
grid::GridImage SmallImage() {
  grid::GridImage image;
  image.occupancy = (cv::Mat_<std::uint8_t>(3, 4) << 0, 128, 255, 0,  //
                     255, 255, 128, 128,                              //
                     0, 0, 0, 200);
  image.origin_m = {-3.25, 1.5};
  image.resolution_m = 0.05;
  return image;
}

TEST(RosMap, WritesTheYamlMapServerExpects) {
  const std::filesystem::path stem = TempStem("run.2");  // the stem's dot must survive
  WriteRosMap(stem, SmallImage());
  EXPECT_EQ(ReadBytes(stem.string() + ".yaml"),
            "image: run.2.pgm\nresolution: 0.05\norigin: [-3.25, 1.5, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
}

TEST(RosMap, WritesTrinaryP5Pixels) {
  const std::filesystem::path stem = TempStem("grid");
  WriteRosMap(stem, SmallImage());
  const std::string bytes = ReadBytes(stem.string() + ".pgm");
  ASSERT_EQ(bytes.rfind("P5\n", 0), 0u);
  const std::string trailer = "\n4 3\n255\n";
  const std::size_t data = bytes.find(trailer);
  ASSERT_NE(data, std::string::npos);
  const std::string pixels = bytes.substr(data + trailer.size());
  // 0 -> 254 (free), 128 -> 205 (unknown), 255 and 200 (p = 0.78 > 0.65) -> 0 (occupied).
  const std::string expected = {'\xfe', '\xcd', '\x00', '\xfe', '\x00', '\x00',
                                '\xcd', '\xcd', '\xfe', '\xfe', '\xfe', '\x00'};
  EXPECT_EQ(pixels, expected);
}

TEST(RosMap, RoundTripsThroughReadRosMap) {
  const std::filesystem::path stem = TempStem("grid");
  const grid::GridImage written = SmallImage();
  WriteRosMap(stem, written);
  const grid::GridImage read = ReadRosMap(stem.string() + ".yaml");
  EXPECT_EQ(read.resolution_m, written.resolution_m);
  EXPECT_EQ(read.origin_m, written.origin_m);
  cv::Mat expected = written.occupancy.clone();
  expected.at<std::uint8_t>(2, 3) = 255;  // 200 reads back as occupied: the format is trinary
  EXPECT_EQ(cv::countNonZero(read.occupancy != expected), 0);
}

TEST(RosMap, RoundTripsAnOccupancyGrid) {
  grid::OccupancyGrid occupancy;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(
        occupancy.Insert(grid::testing::MakeScan({1.0f, 2.0f, 1.5f}, -1.0, 1.0), {0.3, -0.7, 0.2}));
  }
  const grid::GridImage image = occupancy.ToImage();
  const std::filesystem::path stem = TempStem("grid");
  WriteRosMap(stem, image);
  const grid::GridImage read = ReadRosMap(stem.string() + ".yaml");
  EXPECT_EQ(read.origin_m, image.origin_m);
  EXPECT_EQ(cv::countNonZero(read.occupancy == 255), cv::countNonZero(image.occupancy > 165));
  EXPECT_EQ(cv::countNonZero(read.occupancy == 0), cv::countNonZero(image.occupancy < 50));
  EXPECT_GT(cv::countNonZero(read.occupancy == 255), 0);
}

TEST(RosMap, ReadsCommentsNegateAndQuotedImageNames) {
  const std::filesystem::path stem = TempStem("other");
  WriteBytes(stem.string() + ".pgm",
             "P5\n# made by hand\n2 1\n# mid-header comment\n255\n\x10\xf0");
  WriteBytes(stem.string() + ".yaml",
             "# a map\nimage: \"other.pgm\"\nresolution: 0.1\norigin: [1.0, -2.0, 0.0]\n"
             "negate: 1  # white is occupied\n");
  const grid::GridImage read = ReadRosMap(stem.string() + ".yaml");
  EXPECT_EQ(read.occupancy.at<std::uint8_t>(0, 0), 0);    // dark = free when negated
  EXPECT_EQ(read.occupancy.at<std::uint8_t>(0, 1), 255);  // bright = occupied
  EXPECT_EQ(read.origin_m, Eigen::Vector2d(1.0, -2.0));
  EXPECT_EQ(read.resolution_m, 0.1);
}

// What ReadRosMap throws for a yaml body (with a valid 1 x 1 PGM beside it).
std::string ReadError(const std::string& yaml,
                      const std::string& pgm = std::string("P5 1 1 255\n") + '\0') {
  const std::filesystem::path stem = TempStem("bad");
  WriteBytes(stem.string() + ".pgm", pgm);
  WriteBytes(stem.string() + ".yaml", yaml);
  try {
    ReadRosMap(stem.string() + ".yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(RosMap, RejectsMalformedMapsNamingTheProblem) {
  const std::string ok = "image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  EXPECT_EQ(ReadError(ok), "no error");
  EXPECT_NE(ReadError("image: bad.pgm\norigin: [0, 0, 0]\n").find("missing field 'resolution'"),
            std::string::npos);
  EXPECT_NE(ReadError("image: bad.pgm\nresolution: fine\norigin: [0, 0, 0]\n").find("bad.yaml:2:"),
            std::string::npos);
  EXPECT_NE(ReadError("image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0.5]\n").find("yaw"),
            std::string::npos);
  EXPECT_NE(ReadError(ok + "mode: raw\n").find("raw"), std::string::npos);
  EXPECT_NE(ReadError(ok, "P5 4 4 255\n\x01\x02").find("truncated"), std::string::npos);
  EXPECT_NE(ReadError(ok, "P2 1 1 255\n0\n").find("P5"), std::string::npos);
  EXPECT_NE(ReadError(ok, "P5 1 1 65535\n\x00\x00").find("16-bit"), std::string::npos);
  EXPECT_NE(
      ReadError("image: missing.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n").find("missing.pgm"),
      std::string::npos);
}

TEST(RosMap, RefusesToWriteAnEmptyImage) {
  grid::GridImage image;
  EXPECT_THROW(WriteRosMap(TempStem("empty"), image), std::invalid_argument);
  image = SmallImage();
  image.resolution_m = 0.0;
  EXPECT_THROW(WriteRosMap(TempStem("zero"), image), std::invalid_argument);
}

}  // namespace
}  // namespace pena::io
