// OUT/global_versions.csv across a kill -9 (services/fusion/versions_log.hpp). No DDS.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "scoped_temp_dir.hpp"
#include "versions_log.hpp"

namespace pena::services {
namespace {

namespace fs = std::filesystem;

// A path `name` in this test's own temporary directory, no file there yet.
fs::path FreshFile(const std::string& name) {
  const fs::path path = pena::testing::ProcessTempDir() / name;
  fs::remove(path);
  return path;
}

std::string Contents(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(VersionsLog, AReopenedLogContinuesFromItsLastRow) {
  const fs::path path = FreshFile("reopened.csv");
  {
    VersionsLog log(path);
    EXPECT_FALSE(log.had_rows());
    log.Append(0, 1, 100);
    log.Append(1, 2, 200);
  }
  const VersionsLog reopened(path);
  EXPECT_TRUE(reopened.had_rows());
  EXPECT_EQ(reopened.last_version(), 2u);
}

TEST(VersionsLog, VersionsRecoveredButNeverPublishedGetOneRowSoTheSequenceStaysContiguous) {
  // The fusion journaled the input of version 3 and was killed before it logged the delta 2 -> 3;
  // the restart recovers version 3 and publishes it in its snapshot.
  const fs::path path = FreshFile("killed.csv");
  VersionsLog(path).Append(1, 2, 100);
  VersionsLog restarted(path);
  EXPECT_EQ(restarted.CatchUp(3, 300), std::optional<std::uint64_t>(3));
  restarted.Append(3, 4, 400);
  EXPECT_EQ(Contents(path), "1,2,100\n2,3,300\n3,4,400\n");
}

TEST(VersionsLog, NothingIsWrittenWhenEveryRecoveredVersionWasPublished) {
  const fs::path path = FreshFile("clean.csv");
  VersionsLog(path).Append(1, 2, 100);
  VersionsLog restarted(path);
  EXPECT_EQ(restarted.CatchUp(2, 300), std::nullopt);
  // A new log on a recovered state has no sequence to continue.
  VersionsLog fresh(FreshFile("fresh.csv"));
  EXPECT_EQ(fresh.CatchUp(7, 300), std::nullopt);
  EXPECT_EQ(Contents(path), "1,2,100\n");
}

TEST(VersionsLog, ForeignLinesAreSkippedAndAnUnwritablePathIsNamed) {
  const fs::path path = FreshFile("foreign.csv");
  std::ofstream(path) << "from,to,wall_ns\n4,5,100\nnot,a,row\n";
  EXPECT_EQ(VersionsLog(path).last_version(), 5u);
  try {
    VersionsLog(path.parent_path() / "no_such_dir" / "v.csv");
    FAIL() << "an unwritable log was opened";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_dir/v.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace pena::services
