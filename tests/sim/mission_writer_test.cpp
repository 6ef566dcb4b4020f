// Writing a mission directory: the documented layout, readable back through io, and the same
// bytes for the same seed.
#include "pena/sim/mission_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>

#include "pena/io/line_csv.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/sim/mission_picture.hpp"
#include "scoped_temp_dir.hpp"
#include "sim_test_util.hpp"

namespace pena::sim {
namespace {

namespace fs = std::filesystem;

// A human and a robot in the corridor loop, with a partial plan, smoke and a steel pillar.
Scenario TwoEntityMission() {
  Scenario scenario = testing::CorridorLoop();
  EntitySpec robot = testing::CorridorLoop(sensors::EntityKind::kRobot).entities[0];
  robot.start_time_s = 3.0;
  scenario.entities.push_back(robot);
  scenario.apriori = testing::Rectangle(0.0, 0.0, 20.0, 12.0);
  scenario.smoke.push_back({{{15.0, 0.0}, {20.0, 12.0}}, 3.0});
  scenario.magnetic.push_back({{10.0, 1.0}, 2.0, 0.4});
  return scenario;
}

// A path `name` in this test's own temporary directory, not yet created.
fs::path FreshDir(const std::string& name) {
  const fs::path dir = pena::testing::ProcessTempDir() / name;
  fs::remove_all(dir);
  return dir;
}

// Runs and writes the mission, PNG included (as `pena simulate` does).
void WriteAll(const Scenario& scenario, std::uint64_t seed, const fs::path& dir) {
  SimulationOptions options;
  options.seed = seed;
  const SimulationResult result = Simulator(options).Run(scenario);
  WriteMission(scenario, result, dir, "test");
  ASSERT_TRUE(cv::imwrite((dir / "mission.png").string(), RenderMission(scenario, result)));
}

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> FilesUnder(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir));
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(MissionWriter, SameSeedWritesIdenticalBytesAndAnotherSeedDoesNot) {
  const Scenario scenario = TwoEntityMission();
  const fs::path a = FreshDir("a"), b = FreshDir("b"), c = FreshDir("c");
  WriteAll(scenario, 5, a);
  WriteAll(scenario, 5, b);
  WriteAll(scenario, 6, c);
  const auto files = FilesUnder(a);
  // floorplan .csv and .svg, observed, apriori, png + 2 x (log, tum, relations)
  ASSERT_EQ(files.size(), 11u);
  ASSERT_EQ(files, FilesUnder(b));
  for (const fs::path& file : files) {
    EXPECT_TRUE(Bytes(a / file) == Bytes(b / file)) << file;
  }
  // observed.csv may agree: the corridor loop is seen whole whatever the seed.
  for (const char* file :
       {"ff1/sensors.penalog", "ff1/truth.tum", "robot1/sensors.penalog", "mission.png"}) {
    EXPECT_FALSE(Bytes(a / file) == Bytes(c / file)) << file;
  }
  EXPECT_TRUE(Bytes(a / "floorplan.csv") == Bytes(c / "floorplan.csv"));
}

TEST(MissionWriter, WritesTheDocumentedLayoutReadableThroughIo) {
  const Scenario scenario = TwoEntityMission();
  const SimulationResult result = Simulator().Run(scenario);
  const fs::path dir = FreshDir("layout");
  const MissionFiles files = WriteMission(scenario, result, dir, "pena simulate test");
  EXPECT_EQ(files.floorplan, dir / "floorplan.csv");
  ASSERT_TRUE(files.apriori.has_value());
  EXPECT_EQ(io::ReadLineCsv(files.floorplan).size(), scenario.walls.size());
  EXPECT_EQ(io::ReadLineCsv(*files.apriori).size(), scenario.apriori->size());
  const auto observed = io::ReadLineCsv(files.observed);
  ASSERT_EQ(observed.size(), result.observed.size());
  for (std::size_t i = 0; i < observed.size(); ++i) {
    EXPECT_EQ(observed[i].extra, std::to_string(result.observed[i].wall_index));
  }
  ASSERT_EQ(files.entities.size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) {
    const EntityRecording& entity = result.entities[e];
    EXPECT_EQ(files.entities[e].log, dir / entity.id / "sensors.penalog");
    EXPECT_EQ(io::ReadTum(files.entities[e].truth_tum).size(), entity.scans);
    geometry::Trajectory truth;
    for (const auto& pose : entity.truth) truth.push_back({pose.stamp_s, pose.world_from_body});
    EXPECT_EQ(io::ReadRelations(files.entities[e].truth_relations).size(),
              TruthRelations(truth).size());
    io::MissionLogReader reader(files.entities[e].log);
    EXPECT_EQ(reader.header().entity_id, entity.id);
    EXPECT_EQ(reader.header().mission, "corridor-loop");
    EXPECT_EQ(reader.header().kind, entity.kind);
    EXPECT_EQ(reader.header().laser_height_m, entity.laser_height_m);
    EXPECT_EQ(reader.header().producer, "pena simulate test");
    std::size_t records = 0;
    while (reader.Next()) ++records;
    EXPECT_EQ(records, entity.records.size());
  }
}

TEST(MissionPicture, DrawsWallsPathsAndLegend) {
  const Scenario scenario = TwoEntityMission();
  const SimulationResult result = Simulator().Run(scenario);
  const cv::Mat picture = RenderMission(scenario, result);
  ASSERT_EQ(picture.type(), CV_8UC3);
  // 21 x 13 m at 5 cm plus margins and the legend panel.
  EXPECT_NEAR(picture.cols, 420 + 80 + MissionPictureOptions::DefaultCanvas().legend_panel_px, 2);
  EXPECT_NEAR(picture.rows, 260 + 80, 2);
  const cv::Mat blank(picture.size(), picture.type(), cv::Scalar(255, 255, 255));
  EXPECT_GT(cv::norm(picture, blank, cv::NORM_L1), 0.0);
}

}  // namespace
}  // namespace pena::sim
