// `pena map` as the issue states it: every output file from a simulated mission with true poses,
// a line map `pena eval` can score, a radish-corrected log mapped on its logged poses, and a
// one-line error for a bad --trajectory. Map quality is measured in docs/line-extraction.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "pena/io/trajectory_io.hpp"
#include "run_pena.hpp"

namespace pena::testing {
namespace {

void ExpectMapFiles(const std::filesystem::path& dir) {
  for (const char* name : {"lines.csv", "lines.svg", "grid.pgm", "grid.yaml", "map.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
    EXPECT_GT(ReadBytes(dir / name).size(), 0u) << name;
  }
}

TEST(CliMap, SimulatedMissionWithTruePosesGivesAScorableLineMap) {
  const auto sim = FreshDir("map_sim");
  const PenaRun simulate = RunPena("simulate --scenario office --seed 4 --out " + sim.string());
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  const auto out = FreshDir("map_sim_out");
  const PenaRun run = RunPena("map --log " + (sim / "ff1" / "sensors.penalog").string() +
                              " --trajectory " + (sim / "ff1" / "truth.tum").string() +
                              " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ExpectMapFiles(out);
  EXPECT_NE(run.out.find("0 skipped"), std::string::npos) << run.out;  // truth has every stamp
  EXPECT_EQ(ReadBytes(out / "lines.csv").rfind("id,x1,y1,x2,y2,support_cells,rms_error_m\n", 0),
            0u);
  const PenaRun eval = RunPena("eval --lines " + (out / "lines.csv").string() + " --walls " +
                               (sim / "observed.csv").string() + " --json");
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_GT(JsonNumber(eval.out, "coverage"), 0.5) << eval.out;
  EXPECT_GT(JsonNumber(eval.out, "precision"), 0.5) << eval.out;
}

// Without poses `pena map` runs the odometry and the SLAM and lists the closure matches in
// closures.csv: as many kept and dropped as it prints, each measuring its two keyframes' true
// relative pose (office seed 5, whose SLAM map is right: docs/slam.md).
TEST(CliMap, SlamClosuresFileListsMatchesThatAgreeWithTheTruth) {
  const auto sim = FreshDir("map_closures_sim");
  ASSERT_EQ(RunPena("simulate --scenario office --seed 5 --out " + sim.string()).exit_code, 0);
  const auto out = FreshDir("map_closures_out");
  const PenaRun run = RunPena("map --quiet --log " + (sim / "ff1" / "sensors.penalog").string() +
                              " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  long printed_kept = -1, printed_dropped = -1;
  const std::size_t at = run.out.find(" closures kept (");
  ASSERT_NE(at, std::string::npos) << run.out;
  printed_kept = std::stol(run.out.substr(run.out.rfind(", ", at) + 2));
  printed_dropped = std::stol(run.out.substr(at + std::string(" closures kept (").size()));
  std::map<long, geometry::Pose2> truth;  // by stamp in milliseconds
  for (const geometry::StampedPose2& pose : io::ReadTum(sim / "ff1" / "truth.tum")) {
    truth[std::lround(pose.stamp_s * 1000.0)] = pose.pose;
  }
  std::istringstream rows(ReadBytes(out / "closures.csv"));
  std::string row;
  std::getline(rows, row);
  EXPECT_EQ(row, "older_stamp,stamp,x,y,theta,prior_x,prior_y,prior_theta,score,window_m,kept");
  long kept = 0, dropped = 0;
  std::vector<double> errors_m;
  while (std::getline(rows, row)) {
    std::replace(row.begin(), row.end(), ',', ' ');
    std::istringstream f(row);
    double t0 = 0, t1 = 0, x = 0, y = 0, th = 0, px = 0, py = 0, pth = 0, score = 0, window = 0;
    int is_kept = 0;
    f >> t0 >> t1 >> x >> y >> th >> px >> py >> pth >> score >> window >> is_kept;
    ASSERT_TRUE(f) << row;
    EXPECT_LT(t0, t1);
    EXPECT_GE(score, 0.6);
    (is_kept ? kept : dropped) += 1;
    if (!is_kept) continue;
    const geometry::Pose2 true_relative =
        geometry::Between(truth.at(std::lround(t0 * 1000.0)), truth.at(std::lround(t1 * 1000.0)));
    errors_m.push_back(std::hypot(x - true_relative.x_m, y - true_relative.y_m));
  }
  EXPECT_EQ(kept, printed_kept);
  EXPECT_EQ(dropped, printed_dropped);
  // summary.json: the same counts, the stage times of the SLAM pass, the peak memory.
  const std::string summary = ReadBytes(out / "summary.json");
  EXPECT_NE(summary.find("\"loop_closures\": " + std::to_string(printed_kept) + ","), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("\"slam\": {\"total\": {\"s\": "), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"loop_match\": {\"s\": "), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"peak_rss_mb\": "), std::string::npos) << summary;
  ASSERT_GT(kept, 10);
  std::nth_element(errors_m.begin(), errors_m.begin() + errors_m.size() / 2, errors_m.end());
  EXPECT_LT(errors_m[errors_m.size() / 2], 0.1);
}

TEST(CliMap, RadishCorrectedLogMapsOnItsLoggedPoses) {
  const auto log = DataPath("radish-corrected/aces-corrected.log.gz");
  const auto out = FreshDir("map_aces");
  const PenaRun run = RunPena("map --quiet --log " + log.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ExpectMapFiles(out);
  EXPECT_NE(run.out.find("poses: logged poses"), std::string::npos) << run.out;
  const std::string csv = ReadBytes(out / "lines.csv");
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 100) << "expected a building's walls";
}

TEST(CliMap, MissingTrajectoryFileGivesOneLineError) {
  const auto out = FreshDir("map_bad");
  const PenaRun run =
      RunPena("map --log " + DataPath("radish-corrected/aces-corrected.log.gz").string() +
              " --trajectory " + (out / "missing.tum").string() + " --out " + out.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_EQ(run.err.rfind("pena: error: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find("missing.tum"), std::string::npos) << run.err;
}

// `--set slam.NAME=VALUE` reaches the SLAM's options: an unknown name and an invalid value are
// one-line errors naming them.
TEST(CliMap, SlamSettingsAreCheckedByName) {
  const auto sim = FreshDir("map_slam_set");
  const PenaRun simulate = RunPena("simulate --scenario office --seed 4 --out " + sim.string());
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  const std::string map = "map --quiet --log " + (sim / "ff1" / "sensors.penalog").string() +
                          " --out " + (sim / "map").string();
  const PenaRun unknown = RunPena(map + " --set slam.no_such_option=1");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  EXPECT_NE(unknown.err.find("slam.no_such_option"), std::string::npos) << unknown.err;
  const PenaRun invalid = RunPena(map + " --set slam.loop_sigma_rad=-1");
  EXPECT_NE(invalid.exit_code, 0);
  EXPECT_NE(invalid.err.find("slam.loop_sigma_rad"), std::string::npos) << invalid.err;
  // With the poses given the SLAM does not run; the setting is still checked.
  const PenaRun unused = RunPena(map + " --trajectory " + (sim / "ff1" / "truth.tum").string() +
                                 " --set slam.no_such_option=1");
  EXPECT_NE(unused.exit_code, 0);
  EXPECT_NE(unused.err.find("slam.no_such_option"), std::string::npos) << unused.err;
}

}  // namespace
}  // namespace pena::testing
