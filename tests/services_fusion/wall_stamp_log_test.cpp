#include "wall_stamp_log.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace pena::services {
namespace {

std::filesystem::path Fresh(const char* name) {
  const auto path = std::filesystem::path(testing::TempDir()) / name;
  std::filesystem::remove(path);
  return path;
}

TEST(WallStampLog, KeepsEachWallsFirstStampAcrossAReopen) {
  const auto path = Fresh("wall_stamp_log_test.csv");
  {
    WallStampLog log(path);
    log.Append("ff2", {{1, 10.5}, {2, 10.5}});
    log.Append("ff2", {{2, 31.0}, {3, 31.0}});  // 2 again: it keeps 10.5
    log.Append("robot,1", {{1, 4.25}});         // any entity id
  }
  // A crash while writing leaves a torn last line: it does not count.
  { std::ofstream(path, std::ios::app) << "ff2,4,5"; }
  const WallStampLog reopened(path);
  const auto& stamps = reopened.stamps();
  ASSERT_EQ(stamps.size(), 2u);
  EXPECT_EQ(stamps.at("ff2"), (std::map<std::int64_t, double>{{1, 10.5}, {2, 10.5}, {3, 31.0}}));
  EXPECT_EQ(stamps.at("robot,1"), (std::map<std::int64_t, double>{{1, 4.25}}));
}

TEST(WallStampLog, ABadWholeLineIsAnErrorNamingFileAndLine) {
  const auto path = Fresh("wall_stamp_log_bad.csv");
  { std::ofstream(path) << "# entity,segment_id,stamp_s\nff1,1,2.5\nff1,x,3\n"; }
  try {
    WallStampLog log(path);
    FAIL() << "a bad line was accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("wall_stamp_log_bad.csv:3"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::services
