// `pena simulate` as the acceptance states it: the mission layout, byte-identical output
// for a seed, and a truth trajectory that scores zero against itself.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pena/io/line_csv.hpp"
#include "pena/io/log_source.hpp"
#include "run_pena.hpp"

namespace pena::testing {
namespace {

std::vector<std::filesystem::path> FilesUnder(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(std::filesystem::relative(entry.path(), dir));
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(CliSimulate, Loop170IsByteIdenticalForOneSeed) {
  const auto a = FreshDir("sim_a");
  const auto b = FreshDir("sim_b");
  ASSERT_EQ(RunPena("simulate --scenario loop170 --seed 1 --out " + a.string()).exit_code, 0);
  ASSERT_EQ(RunPena("simulate --scenario loop170 --seed 1 --out " + b.string()).exit_code, 0);
  const auto files = FilesUnder(a);
  ASSERT_EQ(files, FilesUnder(b));
  for (const auto& file : files) {
    EXPECT_TRUE(ReadBytes(a / file) == ReadBytes(b / file)) << file << " differs";
  }
}

TEST(CliSimulate, OfficeWritesTheDocumentedLayout) {
  const auto dir = FreshDir("sim_office");
  const PenaRun run = RunPena("simulate --scenario office --seed 3 --out " + dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* file :
       {"floorplan.csv", "floorplan.svg", "observed.csv", "apriori.csv", "mission.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
  }
  bool found_entity = false;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (!entry.is_directory()) continue;
    found_entity = true;
    for (const char* file : {"sensors.penalog", "truth.tum", "truth.relations"}) {
      EXPECT_TRUE(std::filesystem::exists(entry.path() / file)) << entry.path() / file;
    }
    // The truth scores zero against itself, through the user's own commands.
    const std::string truth = (entry.path() / "truth.tum").string();
    const PenaRun eval = RunPena("eval --trajectory " + truth + " --truth " + truth);
    EXPECT_EQ(eval.exit_code, 0) << eval.err;
    const PenaRun info = RunPena("info " + (entry.path() / "sensors.penalog").string());
    EXPECT_EQ(info.exit_code, 0) << info.err;
  }
  EXPECT_TRUE(found_entity);
  // Observed walls are parts of the true walls, never more than the plan.
  const auto observed = io::ReadLineCsv(dir / "observed.csv");
  EXPECT_FALSE(observed.empty());
}

TEST(CliSimulate, UnknownScenarioIsAClearError) {
  const PenaRun run = RunPena("simulate --scenario no-such-scenario --seed 1 --out " +
                              FreshDir("sim_bad").string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("no-such-scenario"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace pena::testing
