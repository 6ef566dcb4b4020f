// `pena odometry` as the issue states it: one pose per scan at the scan's own stamp, the picture
// and the per-scan CSV, real logs through to `pena eval`, and clean one-line errors on bad input.
// Accuracy is not asserted here: the lead measures it (docs/odometry.md, Figures).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "pena/io/trajectory_io.hpp"
#include "run_pena.hpp"

namespace pena::testing {
namespace {

// Simulates the small office mission into a fresh directory; returns ff1's native log.
std::filesystem::path SimulateOffice(const std::string& name) {
  const auto dir = FreshDir(name);
  const PenaRun run = RunPena("simulate --scenario office --seed 2 --out " + dir.string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return dir / "ff1" / "sensors.penalog";
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The status column (5th) of every data row of odometry.csv.
std::vector<std::string> Statuses(const std::filesystem::path& csv) {
  std::vector<std::string> statuses;
  const std::vector<std::string> lines = Lines(ReadBytes(csv));
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream row(lines[i]);
    std::string field;
    for (int column = 0; column < 5; ++column) std::getline(row, field, ',');
    statuses.push_back(field);
  }
  return statuses;
}

// Expects a failed run whose stderr is exactly one "pena: error:" line that mentions `needle`.
void ExpectOneLineError(const PenaRun& run, const std::string& needle) {
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_EQ(run.err.rfind("pena: error: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
}

TEST(CliOdometry, SimulatedMissionGivesOnePosePerScanAtTheScanStamps) {
  const auto log = SimulateOffice("odo_sim");
  const auto out = FreshDir("odo_sim_out");
  const PenaRun run = RunPena("odometry --log " + log.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // truth.tum has one pose at every scan time: the estimate must have exactly those stamps.
  const geometry::Trajectory truth = io::ReadTum(log.parent_path() / "truth.tum");
  const geometry::Trajectory estimate = io::ReadTum(out / "trajectory.tum");
  ASSERT_EQ(estimate.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    ASSERT_EQ(estimate[i].stamp_s, truth[i].stamp_s) << "pose " << i;
  }
  // The native log's first ground truth is the known start pose.
  EXPECT_NEAR(estimate.front().pose.x_m, truth.front().pose.x_m, 1e-6);
  EXPECT_NEAR(estimate.front().pose.y_m, truth.front().pose.y_m, 1e-6);
  // One CSV row per scan behind a header; the first scan starts the map.
  const std::vector<std::string> statuses = Statuses(out / "odometry.csv");
  ASSERT_EQ(statuses.size(), truth.size());
  EXPECT_EQ(statuses.front(), "first");
  EXPECT_EQ(ReadBytes(out / "odometry.png").substr(0, 4), "\x89PNG");
  EXPECT_NE(ReadBytes(out / "summary.json").find("\"scans\": " + std::to_string(truth.size())),
            std::string::npos);
  EXPECT_NE(run.out.find(std::to_string(truth.size()) + " scans"), std::string::npos) << run.out;
  // A person's strides are spread over the scans by default; the summary says how many.
  const std::string summary = ReadBytes(out / "summary.json");
  EXPECT_NE(summary.find("\"dead_reckoning\": {\"compass_rejected\": "), std::string::npos);
  EXPECT_NE(summary.find("\"stride_spreading\": {\"strides_spread\": "), std::string::npos);
  EXPECT_EQ(summary.find("\"strides_spread\": 0,"), std::string::npos) << summary;
  EXPECT_NE(run.out.find(" strides spread over "), std::string::npos) << run.out;
  // Where the time went and the peak memory (docs/odometry.md, "Where the time goes").
  EXPECT_NE(summary.find("\"stage_times\": {\"pipeline\": {\"total\": {\"s\": "), std::string::npos);
  EXPECT_NE(summary.find("\"odometry\": {\"total\": {\"s\": "), std::string::npos);
  EXPECT_NE(summary.find("\"search_base\": {\"s\": "), std::string::npos);
  const std::size_t peak = summary.find("\"peak_rss_mb\": ");
  ASSERT_NE(peak, std::string::npos) << summary;
  EXPECT_GT(std::stod(summary.substr(peak + std::string("\"peak_rss_mb\": ").size())), 1.0);
}

TEST(CliOdometry, SummarySaysWhenStridesAreNotSpread) {
  const auto log = SimulateOffice("odo_unspread");
  const auto out = FreshDir("odo_unspread_out");
  const PenaRun run = RunPena("odometry --no-matching --log " + log.string() + " --out " +
                              out.string() + " --set dead_reckoning.stride_interpolation.enabled=0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("; strides not spread"), std::string::npos) << run.out;
  // No counts of the spreading (the stage times name the stage whether or not it ran).
  EXPECT_EQ(ReadBytes(out / "summary.json").find("\"stride_spreading\": {\"strides_spread\""),
            std::string::npos);
}

TEST(CliOdometry, NoMatchingGivesTheSamePosesFromThePriorAlone) {
  const auto log = SimulateOffice("odo_nomatch");
  const auto out = FreshDir("odo_nomatch_out");
  const PenaRun run =
      RunPena("odometry --no-matching --log " + log.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const geometry::Trajectory truth = io::ReadTum(log.parent_path() / "truth.tum");
  EXPECT_EQ(io::ReadTum(out / "trajectory.tum").size(), truth.size());
  const std::vector<std::string> statuses = Statuses(out / "odometry.csv");
  ASSERT_EQ(statuses.size(), truth.size());
  EXPECT_EQ(std::count(statuses.begin(), statuses.end(), "prior_only"),
            static_cast<long>(truth.size()) - 1);
}

TEST(CliOdometry, StartOptionSetsTheFirstPose) {
  const auto log = SimulateOffice("odo_start");
  const auto out = FreshDir("odo_start_out");
  const PenaRun run = RunPena("odometry --no-matching --start=-3.5,2,90 --log " + log.string() +
                              " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const geometry::Pose2 first = io::ReadTum(out / "trajectory.tum").front().pose;
  EXPECT_NEAR(first.x_m, -3.5, 1e-6);
  EXPECT_NEAR(first.y_m, 2.0, 1e-6);
  EXPECT_NEAR(first.theta_rad, std::numbers::pi / 2.0, 1e-6);
}

TEST(CliOdometry, MitCsailRunsAndItsTrajectoryEvaluates) {
  const auto out = FreshDir("odo_mit");
  const PenaRun run =
      RunPena("odometry --quiet --log " + DataPath("freiburg/mit-csail.clf.gz").string() +
              " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(io::ReadTum(out / "trajectory.tum").size(), 1988u);  // one pose per FLASER line
  EXPECT_EQ(run.out.find("dead reckoning:"), std::string::npos) << "a robot: " << run.out;
  const PenaRun eval =
      RunPena("eval --json --relations " + DataPath("freiburg/mit-csail.relations").string() +
              " --trajectory " + (out / "trajectory.tum").string());
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_NE(eval.out.find("\"translational_error_m\""), std::string::npos) << eval.out;
  EXPECT_EQ(eval.out.find("\"used\": 0,"), std::string::npos) << eval.out;
}

TEST(CliOdometry, TruncatedNativeLogFailsWithOneErrorLine) {
  const auto log = SimulateOffice("odo_trunc");
  const std::string bytes = ReadBytes(log);
  const auto truncated = FreshDir("odo_trunc_log") / "cut.penalog";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2 + 7);
  ExpectOneLineError(RunPena("odometry --quiet --log " + truncated.string() + " --out " +
                             FreshDir("odo_trunc_out").string()),
                     "cut.penalog:");
}

TEST(CliOdometry, GarbageLogFailsWithOneErrorLine) {
  const auto garbage = FreshDir("odo_garbage_log") / "garbage.clf";
  std::ofstream(garbage) << "this is not a log\n\x01\x02\x03 at all\n";
  ExpectOneLineError(RunPena("odometry --quiet --log " + garbage.string() + " --out " +
                             FreshDir("odo_garbage_out").string()),
                     "garbage.clf:");
}

TEST(CliOdometry, BadCarmenLineNamesFileAndLine) {
  std::string text;
  for (int i = 0; i < 3; ++i) {
    const std::string stamp = std::to_string(1.0 + 0.25 * i);
    text += "FLASER 181";
    for (int b = 0; b < 181; ++b) text += " 2.0";
    text += " 0 0 0 0 0 0 " + stamp + " host " + stamp + "\n";
  }
  text += "FLASER 181 1.0 2.0\n";
  const auto log = FreshDir("odo_badline_log") / "short.clf";
  std::ofstream(log) << text;
  ExpectOneLineError(RunPena("odometry --quiet --log " + log.string() + " --out " +
                             FreshDir("odo_badline_out").string()),
                     "short.clf:4:");
}

TEST(CliOdometry, BadStartIsAClearError) {
  const auto log = SimulateOffice("odo_badstart");
  ExpectOneLineError(RunPena("odometry --start 1,2 --log " + log.string() + " --out " +
                             FreshDir("odo_badstart_out").string()),
                     "--start");
}

}  // namespace
}  // namespace pena::testing
